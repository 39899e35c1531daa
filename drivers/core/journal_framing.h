// How one journal record is framed in each file version (JOURNAL.md section 1), shared by the
// reader and the writer: the bytes of a record, and whether a whole valid record starts at a
// given offset (what the reader resynchronises on).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cb {

inline constexpr char kJournalMagic[8] = {'C', 'B', 'J', 'O', 'U', 'R', 'N', 'L'};
inline constexpr size_t kJournalHeaderSize = 16;
// Version 2 records begin with these four bytes, so a reader that lost its place finds the
// next record without trying every offset.
inline constexpr char kJournalRecordMarker[4] = {'C', 'B', 'R', 'C'};
inline constexpr uint32_t kJournalMaxPayload = 64u << 20;

// Bytes a record of `payload` bytes takes in a file of `version`: the marker (version 2), type,
// length, t_ns, payload, CRC.
size_t journalRecordSize(uint32_t version, size_t payload);

std::vector<uint8_t> journalFileHeader(uint32_t version);
void appendJournalRecord(uint32_t version, uint32_t type, int64_t t_ns, const uint8_t* data,
                         size_t n, std::vector<uint8_t>* out);

struct JournalRecordView {
  enum class Status { kWhole, kTruncated, kTooLarge, kNoMarker, kBadChecksum };
  Status status = Status::kTruncated;
  uint32_t type = 0;
  int64_t t_ns = 0;
  const uint8_t* payload = nullptr;
  uint32_t length = 0;
  size_t size = 0;  // bytes of the whole record (kWhole only)
};

// Looks at the record that should start at data[pos] (pos < n).
JournalRecordView journalRecordAt(uint32_t version, const uint8_t* data, size_t n, size_t pos);
const char* journalRecordProblem(JournalRecordView::Status status);

// The offset of the next whole valid record after `pos`, or n when there is none: version 2
// looks only where a marker is; version 1 tries every offset whose type and length are
// plausible (the CRC decides, a chance of 2^-32 per candidate of a false match).
size_t nextWholeJournalRecord(uint32_t version, const uint8_t* data, size_t n, size_t pos);

}  // namespace cb
