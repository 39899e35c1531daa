// Fuzz target: the session journal parser (outside bytes: journals come from other machines),
// the binary payloads, and the texts of the Settings, StrokeMapped and Sync records.
#include <cstdint>
#include <string>

#include "drivers/core/journal.h"
#include "drivers/core/journal_records.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cb::JournalReadResult r = cb::parseJournal(data, size, "fuzz");
  for (const auto& rec : r.records) {
    if (rec.type == cb::JournalRecordType::kPenSample) (void)cb::decodePenSample(rec.payload);
    if (rec.type == cb::JournalRecordType::kDevice) (void)cb::decodeDeviceInfo(rec.payload);
  }
  // The record texts, straight from the bytes (a journal's CRC does not make them sensible).
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string name, toml, error;
  (void)cb::parseSettingsRecord(text, &name, &toml, &error);
  (void)cb::parseStrokeMapped(text);
  if (const auto marker = cb::parseSyncMarker(text)) (void)cb::formatSyncMarker(*marker);
  return 0;
}
