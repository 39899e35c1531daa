// Fuzz target: the session journal parser (outside bytes: journals come from other machines).
#include <cstdint>

#include "drivers/core/journal.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cb::JournalReadResult r = cb::parseJournal(data, size, "fuzz");
  for (const auto& rec : r.records) {
    if (rec.type == cb::JournalRecordType::kPenSample) (void)cb::decodePenSample(rec.payload);
    if (rec.type == cb::JournalRecordType::kDevice) (void)cb::decodeDeviceInfo(rec.payload);
  }
  return 0;
}
