#include "app/study/protocol.h"

#include "drivers/core/toml_number.h"

#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "app/core/config_paths.h"

namespace cb {
namespace {

// Error and field helpers bound to one file: every message is "FILE:LINE: FIELD: what".
class ProtocolReader {
 public:
  explicit ProtocolReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const toml::node& at, const std::string& field,
                         const std::string& what) const {
    const auto line = at.source().begin.line;
    throw StudyProtocolError(source_ + ":" + std::to_string(line) + ": " + field + ": " + what);
  }

  void onlyKeys(const toml::table& table, const std::string& path,
                std::initializer_list<std::string_view> allowed) const {
    for (const auto& [key, value] : table) {
      bool known = false;
      for (std::string_view name : allowed) known = known || key.str() == name;
      if (!known)
        fail(value, join(path, key.str()), "unknown field (allowed: " + list(allowed) + ")");
    }
  }

  const toml::table& table(const toml::table& parent, std::string_view key,
                           const std::string& path) const {
    const toml::node* node = parent.get(key);
    if (!node) fail(parent, join(path, key), "missing table");
    if (!node->is_table()) fail(*node, join(path, key), "expected a table");
    return *node->as_table();
  }

  // The array of tables `key` (may be absent when `required` is false).
  std::vector<const toml::table*> tables(const toml::table& parent, std::string_view key,
                                         const std::string& path, bool required) const {
    std::vector<const toml::table*> result;
    const toml::node* node = parent.get(key);
    if (!node) {
      if (required)
        fail(parent, join(path, key), "missing: at least one [[" + std::string(key) + "]]");
      return result;
    }
    const toml::array* array = node->as_array();
    if (!array) fail(*node, join(path, key), "expected [[" + std::string(key) + "]] tables");
    for (size_t i = 0; i < array->size(); ++i) {
      const toml::table* entry = (*array)[i].as_table();
      if (!entry) fail((*array)[i], indexed(join(path, key), i), "expected a table");
      result.push_back(entry);
    }
    if (required && result.empty()) fail(*node, join(path, key), "at least one entry is needed");
    return result;
  }

  std::string text(const toml::table& table, std::string_view key, const std::string& path,
                   bool required, const std::string& fallback = "") const {
    const toml::node* node = table.get(key);
    if (!node) {
      if (required) fail(table, join(path, key), "missing (a string)");
      return fallback;
    }
    const auto value = node->value<std::string>();
    if (!node->is_string() || !value) fail(*node, join(path, key), "expected a string");
    if (required && trimmedEmpty(*value)) fail(*node, join(path, key), "must not be empty");
    return *value;
  }

  bool flag(const toml::table& table, std::string_view key, const std::string& path,
            bool fallback) const {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    if (!node->is_boolean()) fail(*node, join(path, key), "expected true or false");
    return *node->value<bool>();
  }

  int64_t integer(const toml::table& table, std::string_view key, const std::string& path,
                  int64_t low, int64_t high, std::optional<int64_t> fallback) const {
    const toml::node* node = table.get(key);
    if (!node) {
      if (!fallback) fail(table, join(path, key), "missing (an integer)");
      return *fallback;
    }
    if (!node->is_integer()) fail(*node, join(path, key), "expected an integer");
    std::string why;
    if (auto v = toml_number::integerIn(*node, source_, join(path, key), low, high, &why))
      return *v;
    throw StudyProtocolError(why);
  }

  double minutes(const toml::table& table, std::string_view key, const std::string& path,
                 double fallback) const {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    if (!node->is_number()) fail(*node, join(path, key), "expected a number of minutes");
    std::string why;
    const auto number = toml_number::numberIn(*node, source_, join(path, key), 0, 600, &why);
    if (!number) fail(*node, join(path, key), "minutes must be more than 0 and at most 600");
    const double value = *number;
    if (!(value > 0 && value <= 600))
      fail(*node, join(path, key), "minutes must be more than 0 and at most 600");
    return value;
  }

  std::vector<std::string> strings(const toml::table& table, std::string_view key,
                                   const std::string& path, bool required) const {
    std::vector<std::string> result;
    const toml::node* node = table.get(key);
    if (!node) {
      if (required) fail(table, join(path, key), "missing (a list of strings)");
      return result;
    }
    const toml::array* array = node->as_array();
    if (!array) fail(*node, join(path, key), "expected a list of strings");
    for (size_t i = 0; i < array->size(); ++i) {
      const auto value = (*array)[i].value<std::string>();
      if (!(*array)[i].is_string() || !value || trimmedEmpty(*value))
        fail((*array)[i], indexed(join(path, key), i), "expected a non-empty string");
      result.push_back(*value);
    }
    if (required && result.empty()) fail(*node, join(path, key), "must not be empty");
    return result;
  }

  // An identifier: letters, digits, '_' and '-'.
  std::string identifier(const toml::table& table, std::string_view key,
                         const std::string& path) const {
    const std::string value = text(table, key, path, true);
    for (char c : value)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
        fail(*table.get(key), join(path, key),
             "'" + value + "': only letters, digits, '_' and '-'");
    return value;
  }

  static std::string join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
  }
  static std::string indexed(const std::string& path, size_t i) {
    return path + "[" + std::to_string(i + 1) + "]";
  }

 private:
  static bool trimmedEmpty(const std::string& value) {
    return value.find_first_not_of(" \t\r\n") == std::string::npos;
  }
  static std::string list(std::initializer_list<std::string_view> names) {
    std::string result;
    for (std::string_view name : names) result += (result.empty() ? "" : ", ") + std::string(name);
    return result;
  }

  std::string source_;
};

std::string resolvePath(const std::string& source, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(source).parent_path() / p).lexically_normal().string();
}

StudyStage readStage(const ProtocolReader& r, const toml::table& root, std::string_view key,
                     const std::string& source, bool default_questions) {
  const std::string path(key);
  const toml::table& t = r.table(root, key, "");
  r.onlyKeys(t, path, {"text", "video", "minutes", "questions_allowed"});
  StudyStage stage;
  stage.text = r.text(t, "text", path, true);
  stage.video = r.text(t, "video", path, false);
  if (!stage.video.empty()) stage.video = resolvePath(source, stage.video);
  stage.minutes = r.minutes(t, "minutes", path, 0);
  stage.questions_allowed = r.flag(t, "questions_allowed", path, default_questions);
  return stage;
}

}  // namespace

std::string_view taskSaveKindName(TaskSaveKind kind) {
  switch (kind) {
    case TaskSaveKind::kJournal:
      return "journal";
    case TaskSaveKind::kVolumeVdb:
      return "volume_vdb";
    case TaskSaveKind::kVolumeRaw:
      return "volume_raw";
    case TaskSaveKind::kRenderExr:
      return "render_exr";
    case TaskSaveKind::kRenderPng:
      return "render_png";
  }
  return "?";
}

std::vector<const StudyTask*> StudyProtocol::tasksForParticipant(int number) const {
  std::vector<const StudyTask*> ordered;
  for (int index : taskOrderForParticipant(task_order, int(tasks.size()), number))
    ordered.push_back(&tasks[size_t(index)]);
  return ordered;
}

namespace {

// [study] and [consent].
void readStudySection(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol) {
  const toml::table& study = r.table(root, "study", "");
  r.onlyKeys(study, "study", {"name", "version"});
  protocol->name = r.text(study, "name", "study", true);
  protocol->version = r.text(study, "version", "study", false);

  const toml::table& consent = r.table(root, "consent", "");
  r.onlyKeys(consent, "consent", {"text"});
  protocol->consent = r.text(consent, "text", "consent", true);
}

// [participants]: how participant ids are made.
void readParticipantIds(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol) {
  // Participant ids: never from names (participant_ids.h).
  const toml::table& ids = r.table(root, "participants", "");
  r.onlyKeys(ids, "participants", {"id_scheme", "prefix", "digits", "seed", "length", "key_file"});
  ParticipantIdScheme& scheme = protocol->participant_ids;
  const std::string kind = r.text(ids, "id_scheme", "participants", true);
  if (kind == "counter") {
    scheme.kind = ParticipantIdScheme::Kind::kCounter;
    scheme.digits = int(r.integer(ids, "digits", "participants", 1, 9, 2));
    if (ids.get("seed") || ids.get("length"))
      r.fail(ids.get("seed") ? *ids.get("seed") : *ids.get("length"), "participants",
             "seed and length belong to id_scheme = \"random\"");
  } else if (kind == "random") {
    scheme.kind = ParticipantIdScheme::Kind::kRandom;
    scheme.seed = uint64_t(r.integer(ids, "seed", "participants", 0, INT64_MAX, std::nullopt));
    scheme.length = int(r.integer(ids, "length", "participants", 4, 16, 6));
    if (ids.get("digits"))
      r.fail(*ids.get("digits"), "participants.digits", "belongs to id_scheme = \"counter\"");
  } else {
    r.fail(*ids.get("id_scheme"), "participants.id_scheme",
           "'" + kind + "': expected \"counter\" or \"random\"");
  }
  scheme.prefix = r.text(ids, "prefix", "participants", false, "P");
  if (scheme.prefix.empty() && scheme.kind == ParticipantIdScheme::Kind::kCounter)
    r.fail(*ids.get("prefix"), "participants.prefix", "a counter id needs a prefix");
  for (char c : scheme.prefix)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      r.fail(*ids.get("prefix"), "participants.prefix", "only letters, digits, '_' and '-'");
  scheme.key_file = r.text(ids, "key_file", "participants", false);
  if (!scheme.key_file.empty() && !std::filesystem::path(scheme.key_file).is_absolute())
    r.fail(*ids.get("key_file"), "participants.key_file",
           "must be an absolute path, kept apart from the study data");
}

// [[venue]] and [operator].
void readVenues(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol) {
  // Venues (§7.4) and the operator.
  std::set<std::string> venue_ids;
  const auto venues = r.tables(root, "venue", "", true);
  for (size_t i = 0; i < venues.size(); ++i) {
    const std::string path = ProtocolReader::indexed("venue", i);
    r.onlyKeys(*venues[i], path, {"id", "name"});
    StudyVenue venue{r.identifier(*venues[i], "id", path), r.text(*venues[i], "name", path, true)};
    if (!venue_ids.insert(venue.id).second)
      r.fail(*venues[i]->get("id"), path + ".id", "'" + venue.id + "' is declared twice");
    protocol->venues.push_back(std::move(venue));
  }
  if (const toml::node* node = root.get("operator")) {
    if (!node->is_table()) r.fail(*node, "operator", "expected a table");
    r.onlyKeys(*node->as_table(), "operator", {"required"});
    protocol->operator_required = r.flag(*node->as_table(), "required", "operator", true);
  }
}

// [introduction], [tutorial] with its [[tutorial.step]]s, and [free_drawing].
void readStages(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol,
                const std::string& source) {
  // Stages (§7.5).
  protocol->introduction = readStage(r, root, "introduction", source, true);
  const toml::table& tutorial = r.table(root, "tutorial", "");
  r.onlyKeys(tutorial, "tutorial", {"minutes", "step"});
  protocol->tutorial_minutes = r.minutes(tutorial, "minutes", "tutorial", 10);
  const auto steps = r.tables(tutorial, "step", "tutorial", true);
  for (size_t i = 0; i < steps.size(); ++i) {
    const std::string path = ProtocolReader::indexed("tutorial.step", i);
    r.onlyKeys(*steps[i], path, {"instruction", "expect"});
    TutorialStep step;
    step.number = int(i + 1);
    step.instruction = r.text(*steps[i], "instruction", path, true);
    const std::vector<std::string> expect = r.strings(*steps[i], "expect", path, true);
    const toml::array& expect_nodes = *steps[i]->get("expect")->as_array();
    for (size_t k = 0; k < expect.size(); ++k) {
      try {
        step.expect.push_back(parseTutorialCondition(expect[k]));
      } catch (const TutorialConditionError& e) {
        r.fail(expect_nodes[k], ProtocolReader::indexed(path + ".expect", k), e.what());
      }
    }
    protocol->tutorial.push_back(std::move(step));
  }
  protocol->free_drawing = readStage(r, root, "free_drawing", source, true);
}

// [tasks] and the [[task]]s.
void readTasks(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol,
               const std::string& source) {
  // Tasks (Appendix B) and their order.
  const toml::table& tasks = r.table(root, "tasks", "");
  r.onlyKeys(tasks, "tasks", {"order", "minutes", "questions_allowed"});
  const std::string order = r.text(tasks, "order", "tasks", true);
  const auto scheme_kind = counterbalanceSchemeFromName(order);
  if (!scheme_kind)
    r.fail(*tasks.get("order"), "tasks.order",
           "'" + order + "': expected \"fixed\", \"rotation\" or \"williams\"");
  protocol->task_order = *scheme_kind;
  const double default_minutes = r.minutes(tasks, "minutes", "tasks", 10);
  protocol->task_questions_allowed = r.flag(tasks, "questions_allowed", "tasks", false);
  std::set<std::string> task_ids;
  const auto task_tables = r.tables(root, "task", "", true);
  for (size_t i = 0; i < task_tables.size(); ++i) {
    const toml::table& t = *task_tables[i];
    const std::string path = ProtocolReader::indexed("task", i);
    r.onlyKeys(t, path, {"id", "title", "image", "minutes", "save"});
    StudyTask task;
    task.id = r.identifier(t, "id", path);
    if (!task_ids.insert(task.id).second)
      r.fail(*t.get("id"), path + ".id", "'" + task.id + "' is declared twice");
    task.title = r.text(t, "title", path, true);
    task.image = resolvePath(source, r.text(t, "image", path, true));
    task.minutes = r.minutes(t, "minutes", path, default_minutes);
    const std::vector<std::string> save = r.strings(t, "save", path, true);
    for (size_t k = 0; k < save.size(); ++k) {
      bool known = false;
      for (TaskSaveKind kind_option :
           {TaskSaveKind::kJournal, TaskSaveKind::kVolumeVdb, TaskSaveKind::kVolumeRaw,
            TaskSaveKind::kRenderExr, TaskSaveKind::kRenderPng}) {
        if (save[k] == taskSaveKindName(kind_option)) {
          task.save.push_back(kind_option);
          known = true;
        }
      }
      if (!known)
        r.fail((*t.get("save")->as_array())[k], ProtocolReader::indexed(path + ".save", k),
               "'" + save[k] +
                   "': expected journal, volume_vdb, volume_raw, render_exr or render_png");
    }
    protocol->tasks.push_back(std::move(task));
  }
}

// [[demographic]] fields; their ids join *answer_ids (one answer column each).
void readDemographics(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol,
                      std::set<std::string>* answer_ids) {
  // Demographics (Appendix C's head).
  for (const toml::table* t : r.tables(root, "demographic", "", false)) {
    const std::string path = ProtocolReader::indexed("demographic", protocol->demographics.size());
    r.onlyKeys(*t, path, {"id", "label", "kind", "min", "max", "choices"});
    DemographicField field;
    field.id = r.identifier(*t, "id", path);
    if (!answer_ids->insert(field.id).second)
      r.fail(*t->get("id"), path + ".id", "'" + field.id + "' is already an answer column");
    field.label = r.text(*t, "label", path, true);
    const std::string field_kind = r.text(*t, "kind", path, true);
    if (field_kind == "integer") {
      field.kind = DemographicField::Kind::kInteger;
      field.min = long(r.integer(*t, "min", path, -1000000, 1000000, std::nullopt));
      field.max = long(r.integer(*t, "max", path, -1000000, 1000000, std::nullopt));
      if (field.max < field.min) r.fail(*t->get("max"), path + ".max", "is less than min");
    } else if (field_kind == "text") {
      field.kind = DemographicField::Kind::kText;
    } else if (field_kind == "choice") {
      field.kind = DemographicField::Kind::kChoice;
      field.choices = r.strings(*t, "choices", path, true);
    } else {
      r.fail(*t->get("kind"), path + ".kind",
             "'" + field_kind + "': expected \"integer\", \"text\" or \"choice\"");
    }
    if (field.kind != DemographicField::Kind::kInteger && (t->get("min") || t->get("max")))
      r.fail(*t, path, "min and max belong to kind = \"integer\"");
    if (field.kind != DemographicField::Kind::kChoice && t->get("choices"))
      r.fail(*t->get("choices"), path + ".choices", "belongs to kind = \"choice\"");
    protocol->demographics.push_back(std::move(field));
  }
}

// [questionnaire], its [[item]]s and [[free_text]] questions; their ids join *answer_ids.
void readQuestionnaire(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol,
                       std::set<std::string>* answer_ids) {
  // Questionnaire (Appendix C).
  const toml::table& questionnaire = r.table(root, "questionnaire", "");
  r.onlyKeys(questionnaire, "questionnaire", {"scale", "scale_zh"});
  protocol->scale_labels = r.strings(questionnaire, "scale", "questionnaire", true);
  if (protocol->scale_labels.size() < 2 || protocol->scale_labels.size() > 11)
    r.fail(*questionnaire.get("scale"), "questionnaire.scale", "2 to 11 labels, lowest first");
  protocol->scale_labels_zh = r.strings(questionnaire, "scale_zh", "questionnaire", false);
  if (!protocol->scale_labels_zh.empty() &&
      protocol->scale_labels_zh.size() != protocol->scale_labels.size())
    r.fail(*questionnaire.get("scale_zh"), "questionnaire.scale_zh",
           "as many labels as questionnaire.scale (" +
               std::to_string(protocol->scale_labels.size()) + ")");
  const auto item_tables = r.tables(root, "item", "", true);
  for (size_t i = 0; i < item_tables.size(); ++i) {
    const toml::table& t = *item_tables[i];
    const std::string path = ProtocolReader::indexed("item", i);
    r.onlyKeys(t, path, {"id", "text", "text_zh", "section", "origin"});
    QuestionnaireItem item;
    item.id = r.identifier(t, "id", path);
    if (!answer_ids->insert(item.id).second)
      r.fail(*t.get("id"), path + ".id", "'" + item.id + "' is already an answer column");
    item.text = r.text(t, "text", path, true);
    item.text_zh = r.text(t, "text_zh", path, false);
    item.section = r.text(t, "section", path, false);
    item.origin = r.text(t, "origin", path, false);
    protocol->items.push_back(std::move(item));
  }
  for (const toml::table* t : r.tables(root, "free_text", "", false)) {
    const std::string path = ProtocolReader::indexed("free_text", protocol->free_text.size());
    r.onlyKeys(*t, path, {"id", "prompt"});
    FreeTextQuestion question{r.identifier(*t, "id", path), r.text(*t, "prompt", path, true)};
    if (!answer_ids->insert(question.id).second)
      r.fail(*t->get("id"), path + ".id", "'" + question.id + "' is already an answer column");
    protocol->free_text.push_back(std::move(question));
  }
}

// [keyboard]: the optional answer keyboard.
void readKeyboard(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol) {
  if (root.get("keyboard")) {
    const toml::table& keyboard = r.table(root, "keyboard", "");
    r.onlyKeys(keyboard, "keyboard", {"label", "keys"});
    protocol->keyboard.label = r.text(keyboard, "label", "keyboard", true);
    protocol->keyboard.keys = r.strings(keyboard, "keys", "keyboard", true);
    const toml::node& keys = *keyboard.get("keys");
    if (protocol->keyboard.keys.empty() || protocol->keyboard.keys.size() > kMaxKeyboardKeys)
      r.fail(keys, "keyboard.keys", "1 to " + std::to_string(kMaxKeyboardKeys) + " keys");
  }
}

// [[construct]]s: groups of declared items.
void readConstructs(const ProtocolReader& r, const toml::table& root, StudyProtocol* protocol) {
  std::set<std::string> item_ids;
  for (const QuestionnaireItem& item : protocol->items) item_ids.insert(item.id);
  std::set<std::string> construct_names;
  const auto constructs = r.tables(root, "construct", "", false);
  for (size_t i = 0; i < constructs.size(); ++i) {
    const toml::table& t = *constructs[i];
    const std::string path = ProtocolReader::indexed("construct", i);
    r.onlyKeys(t, path, {"name", "items"});
    ProtocolConstruct construct{r.text(t, "name", path, true), r.strings(t, "items", path, true)};
    if (!construct_names.insert(construct.name).second)
      r.fail(*t.get("name"), path + ".name", "'" + construct.name + "' is declared twice");
    for (size_t k = 0; k < construct.items.size(); ++k)
      if (!item_ids.count(construct.items[k]))
        r.fail((*t.get("items")->as_array())[k], ProtocolReader::indexed(path + ".items", k),
               "'" + construct.items[k] + "' is not a declared [[item]] id");
    protocol->constructs.push_back(std::move(construct));
  }
}

}  // namespace

StudyProtocol parseStudyProtocol(std::string_view text, const std::string& source) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw StudyProtocolError(source + ":" + std::to_string(e.source().begin.line) +
                             ": TOML syntax: " + std::string(e.description()));
  }
  const ProtocolReader r(source);
  r.onlyKeys(root, "",
             {"study", "consent", "participants", "venue", "operator", "introduction", "tutorial",
              "free_drawing", "tasks", "task", "demographic", "questionnaire", "item", "free_text",
              "keyboard", "construct"});
  StudyProtocol protocol;
  protocol.source = source;

  readStudySection(r, root, &protocol);
  readParticipantIds(r, root, &protocol);
  readVenues(r, root, &protocol);
  readStages(r, root, &protocol, source);
  readTasks(r, root, &protocol, source);
  std::set<std::string> answer_ids = {"participant"};
  readDemographics(r, root, &protocol, &answer_ids);
  readQuestionnaire(r, root, &protocol, &answer_ids);
  readKeyboard(r, root, &protocol);
  readConstructs(r, root, &protocol);
  return protocol;
}

StudyProtocol loadStudyProtocol(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StudyProtocolError(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return parseStudyProtocol(text.str(), path);
}

std::string defaultStudyProtocolPath() {
  return configFile("study/thesis_2014.toml");
}

}  // namespace cb
