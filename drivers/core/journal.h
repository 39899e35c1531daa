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
  kPenSample = 1,     // payload: encodePenSample()
  kDevice = 2,        // payload: encodeDeviceInfo()
  kCalibration = 3,   // payload: calibration profile in force from now on (TOML text)
  kUi = 4,            // payload: UI change, "key=value" text (camera, canvas, light, brush, ...)
  kMode = 5,          // payload: mode name (paint, erase, light, camera, canvas, ...)
  kSession = 6,       // payload: session metadata (TOML text: protocol, participant, task, ...)
  kMarker = 7,        // payload: free text marker (notes, "opened PATH")
  kSettings = 8,      // payload: one config file in force (TOML; first line "# NAME.toml")
  kStrokeMapped = 9,  // payload: a recorded measurement of one mapped stroke (TOML; not input)
  kSync = 10,         // payload: a sync marker (task or stroke boundary), as sent over UDP
  kFrame = 11,        // payload: encodeFrameRecord() (journal_frame.h), one presented frame
};
inline constexpr uint32_t kLastJournalRecordType = 11;

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
  // Re-opens an existing journal to carry on appending after its last whole record: a torn or
  // corrupt tail (a crash mid-write) is cut off, and *warning names the file, the byte offset
  // and what was cut (empty when the file was whole). A missing file, or one too short to hold
  // a header, is created as open() does. False with error() for a file that is not a journal
  // of a version this writer writes (it is left untouched).
  bool openForAppend(const std::string& path, std::string* warning);

  // Durability (issue 10: a crash or power cut loses at most the last second). Every append
  // hands its record to the OS at once (fflush), so killing the process loses nothing written;
  // sync() also forces it to the disk (fsync). The painter syncs at every stroke end, and
  // syncIfDue() syncs when records written more than `interval_ns` ago are not yet on disk: it
  // is called by append() itself and by the frame loop's timer (no thread: deterministic).
  // Times are CLOCK_MONOTONIC ns.
  bool sync();
  bool syncIfDue(int64_t now_ns, int64_t interval_ns = kJournalSyncIntervalNs);
  static constexpr int64_t kJournalSyncIntervalNs = 1'000'000'000;
  uint64_t syncCount() const { return syncs_; }
  bool hasUnsyncedRecords() const { return unsynced_since_ns_ >= 0; }
  bool isOpen() const { return file_ != nullptr; }
  const std::string& path() const { return path_; }

  void close();
  const std::string& error() const { return error_; }

 private:
  bool writeHeader();

  std::FILE* file_ = nullptr;
  std::string path_;
  std::string error_;
  int64_t unsynced_since_ns_ = -1;  // monotonic time of the oldest record not yet fsynced
  uint64_t syncs_ = 0;
};

struct JournalReadResult {
  uint32_t version = 0;
  std::vector<JournalRecord> records;
  // Empty when the whole file was read cleanly; otherwise names the file, the byte offset and
  // what was wrong. Records before the fault are still returned.
  std::string error;
  uint64_t skipped_unknown = 0;  // records of types this version does not know
  // Bytes from the start of the file through the last whole record: where an append resumes.
  uint64_t intact_bytes = 0;
};

// Parses a journal held in memory (the file reader and the fuzz target share this).
JournalReadResult parseJournal(const uint8_t* data, size_t n, const std::string& name = "journal");
JournalReadResult readJournal(const std::string& path);

}  // namespace cb
