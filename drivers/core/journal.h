// The session journal: an append-only, versioned record of raw pen samples plus every
// calibration, UI and mode change, so a session can be replayed exactly.
//
// File layout (all integers little-endian):
//   header : "CBJOURNL" (8 bytes), u32 format version, u32 flags (0)
//   record : u32 type, u32 payload length, i64 t_ns (monotonic), payload, u32 CRC-32 of
//            everything in the record before it
// Readers skip record types they do not know (later versions add types, never change them).
// A torn or corrupt tail is reported with its byte offset; every record before it is kept.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/core/pen_sample.h"

namespace cb {

inline constexpr uint32_t kJournalVersion = 1;

enum class JournalRecordType : uint32_t {
  kPenSample = 1,    // payload: encodePenSample()
  kDevice = 2,       // payload: encodeDeviceInfo()
  kCalibration = 3,  // payload: calibration profile in force from now on (TOML text)
  kUi = 4,           // payload: UI change, "key=value" text (camera, canvas, light, brush, ...)
  kMode = 5,         // payload: mode name (paint, erase, light, camera, canvas, ...)
  kSession = 6,      // payload: session metadata (TOML text: protocol, participant, task, ...)
  kMarker = 7,       // payload: free text marker (task start/end, stroke boundaries, notes)
};

struct JournalRecord {
  JournalRecordType type{};
  int64_t t_ns = 0;
  std::vector<uint8_t> payload;

  std::string_view text() const {
    return {reinterpret_cast<const char*>(payload.data()), payload.size()};
  }
};

std::vector<uint8_t> encodePenSample(const PenSample& s);
// Returns nullopt when the payload has the wrong size.
std::optional<PenSample> decodePenSample(const std::vector<uint8_t>& payload);
std::vector<uint8_t> encodeDeviceInfo(const PenDeviceInfo& d);
std::optional<PenDeviceInfo> decodeDeviceInfo(const std::vector<uint8_t>& payload);

uint32_t crc32(const uint8_t* data, size_t n, uint32_t crc = 0);

class JournalWriter {
 public:
  JournalWriter() = default;
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;

  // Creates (or truncates) the file and writes the header. Returns false and sets error().
  bool open(const std::string& path);
  bool append(JournalRecordType type, int64_t t_ns, const uint8_t* data, size_t n);
  bool append(JournalRecordType type, int64_t t_ns, std::string_view text) {
    return append(type, t_ns, reinterpret_cast<const uint8_t*>(text.data()), text.size());
  }
  bool appendPenSample(const PenSample& s);
  // Pushes buffered records to the OS (each append already flushes the stdio buffer).
  bool sync();
  void close();
  const std::string& error() const { return error_; }

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  std::string error_;
};

struct JournalReadResult {
  uint32_t version = 0;
  std::vector<JournalRecord> records;
  // Empty when the whole file was read cleanly; otherwise names the file, the byte offset and
  // what was wrong. Records before the fault are still returned.
  std::string error;
  uint64_t skipped_unknown = 0;  // records of types this version does not know
};

// Parses a journal held in memory (the file reader and the fuzz target share this).
JournalReadResult parseJournal(const uint8_t* data, size_t n, const std::string& name = "journal");
JournalReadResult readJournal(const std::string& path);

}  // namespace cb
