#include "app/kiosk/kiosk_texts.h"

#include <algorithm>
#include <stdexcept>

#include <toml++/toml.h>

#include "app/core/toml_file.h"

namespace cb {
namespace {

std::map<std::string, std::string> readTable(const toml::table& root, const std::string& path,
                                             const std::string& language) {
  const toml::table* table = root[language].as_table();
  if (!table) {
    std::string known;
    for (const auto& [name, node] : root)
      if (node.is_table()) known += (known.empty() ? "" : ", ") + std::string(name.str());
    throw std::runtime_error(path + ": no texts for language '" + language + "' (it has: " + known +
                             ")");
  }
  std::map<std::string, std::string> texts;
  for (const auto& [key, node] : *table) {
    auto v = node.value<std::string>();
    if (!node.is_string() || !v)
      throw std::runtime_error(path + ": " + language + "." + std::string(key.str()) +
                               " must be a string");
    texts[std::string(key.str())] = *v;
  }
  return texts;
}

}  // namespace

KioskTexts KioskTexts::load(const std::string& path, const std::string& language, Log log) {
  const toml::table root = parseTomlFileOrThrow(path);
  KioskTexts texts;
  texts.language_ = language;
  texts.log_ = std::move(log);
  texts.english_ = readTable(root, path, "en");
  for (const char* key : kKioskTextKeys)
    if (!texts.english_.count(key))
      throw std::runtime_error(path + ": en." + key + " is missing (English must have every key)");
  texts.chosen_ = language == "en" ? texts.english_ : readTable(root, path, language);
  return texts;
}

std::string KioskTexts::text(const std::string& key) const {
  if (auto it = chosen_.find(key); it != chosen_.end()) return it->second;
  if (std::find(logged_.begin(), logged_.end(), key) == logged_.end()) {
    logged_.push_back(key);
    if (log_)
      log_("texts: '" + key + "' is missing in language '" + language_ + "'; English shown");
  }
  if (auto it = english_.find(key); it != english_.end()) return it->second;
  return key;
}

std::string KioskTexts::format(const std::string& key,
                               const std::map<std::string, std::string>& values) const {
  std::string out = text(key);
  for (const auto& [name, value] : values) {
    const std::string placeholder = "{" + name + "}";
    for (size_t at = out.find(placeholder); at != std::string::npos;
         at = out.find(placeholder, at + value.size()))
      out.replace(at, placeholder.size(), value);
  }
  return out;
}

std::string KioskTexts::allText() const {
  std::string all;
  for (const auto& [key, value] : chosen_) all += value;
  for (const auto& [key, value] : english_) all += value;
  return all;
}

}  // namespace cb
