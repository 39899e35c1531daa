#include "app/study/bids_phenotype.h"

#include "app/core/json_text.h"
#include "app/study/bids_text.h"
#include "app/study/study_marker_text.h"

namespace cb {
namespace {

std::string constructsOf(const StudyProtocol& protocol, const std::string& item) {
  std::string out;
  for (const ProtocolConstruct& c : protocol.constructs)
    for (const std::string& id : c.items)
      if (id == item) out += (out.empty() ? "" : "; ") + c.name;
  return out;
}

// The sidecar member of one Likert item.
std::string itemJson(const StudyProtocol& protocol, const QuestionnaireItem& item) {
  std::string levels;
  for (size_t k = 0; k < protocol.scale_labels.size(); ++k) {
    std::string label = protocol.scale_labels[k];
    if (k < protocol.scale_labels_zh.size()) label += " / " + protocol.scale_labels_zh[k];
    levels +=
        (levels.empty() ? "" : ", ") + jsonString(std::to_string(k + 1)) + ": " + jsonString(label);
  }
  std::string body = "{\"Description\": " + jsonString(item.text);
  if (!item.text_zh.empty()) body += ", \"Description_zh\": " + jsonString(item.text_zh);
  body += ", \"Levels\": {" + levels + "}";
  const std::string constructs = constructsOf(protocol, item.id);
  if (!constructs.empty()) body += ", \"Construct\": " + jsonString(constructs);
  if (!item.section.empty()) body += ", \"Section\": " + jsonString(item.section);
  if (!item.origin.empty()) body += ", \"Origin\": " + jsonString(item.origin);
  return body + "}";
}

const char kParticipantIdJson[] =
    "{\"Description\": \"The participant's BIDS label (participants.tsv)\"}";
const char kSessionIdJson[] =
    "{\"Description\": \"The participant's session the answers were given in (sessions.tsv)\"}";

std::string tsvOf(const std::vector<BidsPhenotypeRow>& rows, const std::vector<std::string>& ids,
                  std::map<std::string, std::string> BidsPhenotypeRow::*answers) {
  std::string tsv = "participant_id\tsession_id";
  for (const std::string& id : ids) tsv += '\t' + id;
  tsv += '\n';
  for (const BidsPhenotypeRow& r : rows) {
    tsv += r.participant_id + '\t' + r.session_id;
    for (const std::string& id : ids) {
      const auto it = (r.*answers).find(id);
      tsv += '\t' + bidsTsvText(it == (r.*answers).end() ? "" : it->second);
    }
    tsv += '\n';
  }
  return tsv;
}

std::string toolJson(const StudyProtocol& protocol, const std::string& what) {
  return "{\"Description\": " +
         jsonString(what + " of the study protocol '" + protocol.name + "' version " +
                    protocol.version +
                    ", answered on the kiosk after the painting tasks. In a statement, text "
                    "between asterisks (*...*) is the emphasis shown to the participant in "
                    "bold; each answer is a level of the scale, n/a when skipped or never "
                    "reached") +
         "}";
}

}  // namespace

BidsPhenotypeRow phenotypeAnswers(const SessionTrace& trace) {
  BidsPhenotypeRow row;
  for (const TraceEvent& e : trace.events) {
    if (e.type != JournalRecordType::kMarker || e.text.rfind("study.answer ", 0) != 0) continue;
    const StudyMarkerFields m = parseStudyMarker(e.text);
    const std::string value = m.isNa("value") ? "" : m.get("value");
    if (m.has("item")) row.items[m.get("item")] = value;
    if (m.has("free_text")) row.free_text[m.get("free_text")] = value;
  }
  return row;
}

std::map<std::string, std::string> bidsPhenotypeFiles(const StudyProtocol& protocol,
                                                      const std::vector<BidsPhenotypeRow>& rows) {
  std::map<std::string, std::string> files;
  if (!protocol.items.empty()) {
    std::vector<std::string> ids;
    std::vector<std::pair<std::string, std::string>> members = {
        {"MeasurementToolMetadata",
         toolJson(protocol, "The Likert questionnaire (" +
                                std::to_string(protocol.scale_labels.size()) + "-point scale)")},
        {"participant_id", kParticipantIdJson},
        {"session_id", kSessionIdJson}};
    for (const QuestionnaireItem& item : protocol.items) {
      ids.push_back(item.id);
      members.emplace_back(item.id, itemJson(protocol, item));
    }
    files["phenotype/questionnaire.tsv"] = tsvOf(rows, ids, &BidsPhenotypeRow::items);
    files["phenotype/questionnaire.json"] = bidsJsonObject(members);
  }
  if (!protocol.free_text.empty()) {
    std::vector<std::string> ids;
    std::vector<std::pair<std::string, std::string>> members = {
        {"MeasurementToolMetadata", toolJson(protocol, "The free-text questions")},
        {"participant_id", kParticipantIdJson},
        {"session_id", kSessionIdJson}};
    for (const FreeTextQuestion& q : protocol.free_text) {
      ids.push_back(q.id);
      members.emplace_back(q.id, "{\"Description\": " + jsonString(q.prompt) + "}");
    }
    files["phenotype/feedback.tsv"] = tsvOf(rows, ids, &BidsPhenotypeRow::free_text);
    files["phenotype/feedback.json"] = bidsJsonObject(members);
  }
  return files;
}

}  // namespace cb
