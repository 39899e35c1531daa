#include "app/study/study_sync_markers.h"

namespace cb {
namespace {

struct SyncKinds {
  const char* event;      // the marker's first word
  const char* kind;       // its sync kind
  const char* task_kind;  // the kind when the marker names a task (null: the same)
};

const SyncKinds kSyncKinds[] = {
    {"study.session", "session_start", nullptr},
    {"study.stage-begin", "stage_begin", "task_begin"},
    {"study.stage-closing", "stage_closing", "task_end"},
    {"study.stage-end", "stage_end", nullptr},
    {"study.consent", "consent", nullptr},
    {"study.answer", "answer", nullptr},
    {"study.operator", "operator", nullptr},
    {"study.end", "session_end", nullptr},
};

}  // namespace

std::optional<StudySyncMarker> studySyncMarker(const std::string& record_text) {
  const size_t space = record_text.find(' ');
  const std::string event = record_text.substr(0, space);
  for (const SyncKinds& k : kSyncKinds) {
    if (event != k.event) continue;
    StudySyncMarker marker;
    marker.label = space == std::string::npos ? "" : record_text.substr(space + 1);
    const bool task = marker.label.rfind("stage=task ", 0) == 0;
    marker.kind = task && k.task_kind ? k.task_kind : k.kind;
    return marker;
  }
  return std::nullopt;
}

}  // namespace cb
