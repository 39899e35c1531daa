// Fuzz target: the study protocol parser (outside bytes: protocols are written by hand and
// passed between labs). Either a protocol comes back whose declared parts are consistent, or a
// StudyProtocolError whose message starts with the source name.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "app/study/protocol.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const cb::StudyProtocol protocol = cb::parseStudyProtocol(text, "fuzz.toml");
    if (protocol.tasks.empty() || protocol.tutorial.empty() || protocol.items.empty()) std::abort();
    for (const cb::TutorialStep& step : protocol.tutorial)
      for (const cb::TutorialCondition& condition : step.expect)
        if (cb::parseTutorialCondition(condition.text()).text() != condition.text()) std::abort();
    for (int participant = 1; participant <= 3; ++participant) {
      if (protocol.tasksForParticipant(participant).size() != protocol.tasks.size()) std::abort();
      (void)protocol.participant_ids.idFor(participant);
    }
  } catch (const cb::StudyProtocolError& e) {
    if (std::string_view(e.what()).substr(0, 10) != "fuzz.toml:") std::abort();
  }
  return 0;
}
