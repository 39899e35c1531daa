// The session journal: an append-only, versioned record of raw pen samples plus every
// calibration, UI and mode change, so a session can be replayed exactly.
//
// File layout (all integers little-endian; JOURNAL.md is the specification):
//   header : "CBJOURNL" (8 bytes), u32 file version, u32 flags (0)
//   record : version 2: "CBRC" marker, then as version 1; version 1: u32 type, u32 payload
//            length, i64 t_ns (monotonic), payload, u32 CRC-32 of everything in the record
//            before it
// Readers skip record types they do not know (later versions add types, never change them).
// A damaged stretch (a flipped byte, a torn write) is skipped: reading resynchronises on the
// next whole record (its marker and CRC) and reports what it skipped, offset and bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/core/pen_sample.h"

namespace cb {

// The file version new journals are written in. Version 1 files are still read, and a resumed
// version 1 journal is carried on in version 1 (one file, one framing).
inline constexpr uint32_t kJournalVersion = 2;

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
};
inline constexpr uint32_t kLastJournalRecordType = 10;

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
  // Re-opens an existing journal to carry on appending after its last whole record. Damage in
  // its middle stays where it is (readers skip it); damaged bytes after the last whole record
  // (a crash mid-write) are first copied to "PATH.damaged-at-OFFSET" next to it, synced, and
  // only then cut from the journal, so no byte is lost. *warning names the file, what was
  // skipped and where the damaged tail went (empty when the file was whole). A missing file, or
  // one too short to hold a header, is created as open() does. False with error() for a file
  // that is not a journal of a version this writer reads (it is left untouched).
  bool openForAppend(const std::string& path, std::string* warning);

  // Durability (a crash or power cut loses at most the last second). Every append hands its
  // record to the OS at once (pwrite), so killing the process loses nothing written; sync()
  // also forces it to the disk (fsync). The painter syncs at every stroke end, and syncIfDue()
  // syncs when records written more than `interval_ns` ago are not yet on disk: it is called by
  // append() itself and by the frame loop's timer (no thread: deterministic). Times are
  // CLOCK_MONOTONIC ns.
  //
  // A failed write (disk full, I/O error) never leaves a torn record followed by good ones: the
  // file is cut back to its last whole record, and every record not yet known to be on the disk
  // is held in memory (up to kMaxHeldBytes) and written again, in order, at the next append or
  // sync, so the journal carries on whole when space returns. A failed fsync (the kernel may
  // have dropped the pages) rewrites everything since the last good one. append() and sync()
  // return false while records are held; failing() says so and error() says why.
  bool sync();
  bool syncIfDue(int64_t now_ns, int64_t interval_ns = kJournalSyncIntervalNs);
  static constexpr int64_t kJournalSyncIntervalNs = 1'000'000'000;
  static constexpr size_t kMaxHeldBytes = 64u << 20;
  uint64_t syncCount() const { return syncs_; }
  bool hasUnsyncedRecords() const { return unsynced_since_ns_ >= 0; }
  bool isOpen() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }
  uint32_t version() const { return version_; }
  // True while records wait in memory because writing them failed.
  bool failing() const { return failing_; }
  // Bytes of records written or held but not yet known to be on the disk.
  size_t heldBytes() const { return held_.size(); }
  // Records refused because kMaxHeldBytes were already held (lost; reported in error()).
  uint64_t droppedRecords() const { return dropped_; }

  void close();
  const std::string& error() const { return error_; }

 private:
  bool writeHeld();
  bool fail(const std::string& what, int err);
  void reset();

  int fd_ = -1;
  uint32_t version_ = kJournalVersion;
  std::string path_;
  std::string error_;
  // held_ holds the bytes from file offset synced_end_ on; its first written_ bytes are in the
  // file (written, not yet fsynced), the rest wait to be written. written_ is always at a
  // record boundary.
  std::vector<uint8_t> held_;
  uint64_t synced_end_ = 0;
  size_t written_ = 0;
  bool failing_ = false;
  bool trim_ = false;  // a failed write may have left bytes past the last whole record
  uint64_t dropped_ = 0;
  int64_t unsynced_since_ns_ = -1;  // monotonic time of the oldest record not yet fsynced
  uint64_t syncs_ = 0;
};

// A stretch of a journal that held no whole record: a flipped byte, a torn write.
struct JournalGap {
  uint64_t offset = 0;  // first byte skipped
  uint64_t bytes = 0;   // bytes skipped
  std::string why;      // what was wrong at `offset` ("checksum mismatch", ...)
};

struct JournalReadResult {
  uint32_t version = 0;
  std::vector<JournalRecord> records;
  // Empty when the whole file was read cleanly; otherwise names the file, the byte offset of
  // the first fault and what was wrong, and sums up every stretch skipped. Every whole record
  // is still returned, those after a damaged stretch included.
  std::string error;
  std::vector<JournalGap> gaps;  // every stretch skipped, in file order
  uint64_t skipped_unknown = 0;  // records of types this version does not know
  // Bytes from the start of the file through the last whole record: where an append resumes.
  uint64_t intact_bytes = 0;
};

// Parses a journal held in memory (the file reader and the fuzz target share this).
JournalReadResult parseJournal(const uint8_t* data, size_t n, const std::string& name = "journal");
JournalReadResult readJournal(const std::string& path);

}  // namespace cb
