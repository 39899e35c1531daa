#include "app/study/construct_definitions.h"

#include <set>

#include "app/core/toml_file.h"
#include "app/study/session_trace.h"  // StudyInputError

namespace cb {
namespace {

std::vector<std::string> itemRange(int first, int last) {
  std::vector<std::string> items;
  for (int i = first; i <= last; ++i) items.push_back("Q" + std::to_string(i));
  return items;
}

}  // namespace

std::vector<ConstructDefinition> appendixCSections() {
  return {{"Paint style", itemRange(1, 6)},
          {"Cloud drawing", itemRange(7, 18)},
          {"System use", itemRange(19, 27)}};
}

std::vector<ConstructDefinition> loadConstructDefinitions(const std::string& path) {
  toml::table table;
  try {
    table = parseTomlFileOrThrow(path);
  } catch (const std::exception& e) {
    throw StudyInputError(e.what());
  }
  const toml::array* list = table["construct"].as_array();
  if (!list || list->empty())
    throw StudyInputError(path + ": no [[construct]] tables (each needs name and items)");
  std::vector<ConstructDefinition> constructs;
  std::set<std::string> names;
  for (size_t i = 0; i < list->size(); ++i) {
    const std::string where = path + ": construct " + std::to_string(i + 1);
    const toml::table* entry = (*list)[i].as_table();
    if (!entry) throw StudyInputError(where + ": not a table");
    for (const auto& [key, value] : *entry)
      if (key.str() != "name" && key.str() != "items")
        throw StudyInputError(where + ": unknown field '" + std::string(key.str()) + "'");
    ConstructDefinition definition;
    const auto name = (*entry)["name"].value<std::string>();
    if (!name || name->empty())
      throw StudyInputError(where + ": name: expected a non-empty string");
    if (!names.insert(*name).second)
      throw StudyInputError(where + ": name: '" + *name + "' is declared twice");
    definition.name = *name;
    const toml::array* items = (*entry)["items"].as_array();
    if (!items || items->empty())
      throw StudyInputError(where + " (" + *name +
                            "): items: expected a non-empty list of item ids");
    for (const toml::node& item : *items) {
      const auto id = item.value<std::string>();
      if (!id || id->empty())
        throw StudyInputError(where + " (" + *name +
                              "): items: every entry must be an item id string");
      definition.items.push_back(*id);
    }
    constructs.push_back(std::move(definition));
  }
  return constructs;
}

}  // namespace cb
