// Fuzz target: the typed UI change parser (app/session/ui_change.h). Journals come from other
// machines, so Ui and Mode record texts are outside bytes. The first byte picks the record type
// (even: Ui, odd: Mode), the rest is the text. A change that parses formats to a text that
// parses to the same text again (floats round-trip with 9 digits).
#include <cstdint>
#include <cstdlib>
#include <string>

#include "app/session/ui_change.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const cb::JournalRecordType type =
      data[0] % 2 ? cb::JournalRecordType::kMode : cb::JournalRecordType::kUi;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  cb::UiChange change;
  std::string error;
  if (!cb::parseUiChange(type, text, &change, &error)) return 0;
  const cb::UiRecordText once = cb::formatUiChange(change);
  cb::UiChange again;
  if (!cb::parseUiChange(once.type, once.text, &again, &error)) std::abort();
  if (cb::formatUiChange(again).text != once.text) std::abort();
  return 0;
}
