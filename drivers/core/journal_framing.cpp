#include "drivers/core/journal_framing.h"

#include <algorithm>
#include <cstring>

#include "drivers/core/journal.h"

namespace cb {
namespace {

constexpr size_t kHeadV1 = 16;  // type, length, t_ns
constexpr size_t kCrcBytes = 4;
// A version 1 resync candidate's type must be below this: later versions add types one by
// one, so a larger value is a payload byte, not a record (saves computing its CRC).
constexpr uint32_t kPlausibleTypes = 1u << 16;

size_t markerBytes(uint32_t version) {
  return version >= 2 ? sizeof(kJournalRecordMarker) : 0;
}

template <typename T>
void put(std::vector<uint8_t>* out, T v) {
  uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // x86-64 and aarch64 are little-endian
  out->insert(out->end(), b, b + sizeof(T));
}

template <typename T>
T get(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

}  // namespace

size_t journalRecordSize(uint32_t version, size_t payload) {
  return markerBytes(version) + kHeadV1 + payload + kCrcBytes;
}

std::vector<uint8_t> journalFileHeader(uint32_t version) {
  std::vector<uint8_t> out(kJournalMagic, kJournalMagic + sizeof(kJournalMagic));
  put(&out, version), put(&out, uint32_t(0));
  return out;
}

void appendJournalRecord(uint32_t version, uint32_t type, int64_t t_ns, const uint8_t* data,
                         size_t n, std::vector<uint8_t>* out) {
  const size_t begin = out->size();
  if (version >= 2)
    out->insert(out->end(), kJournalRecordMarker,
                kJournalRecordMarker + sizeof(kJournalRecordMarker));
  put(out, type), put(out, uint32_t(n)), put(out, t_ns);
  out->insert(out->end(), data, data + n);
  put(out, crc32(out->data() + begin, out->size() - begin));
}

JournalRecordView journalRecordAt(uint32_t version, const uint8_t* data, size_t n, size_t pos) {
  using S = JournalRecordView::Status;
  JournalRecordView v;
  const size_t marker = markerBytes(version);
  const size_t left = n - pos;
  if (left < marker + kHeadV1 + kCrcBytes) return v.status = S::kTruncated, v;
  if (marker && std::memcmp(data + pos, kJournalRecordMarker, marker) != 0)
    return v.status = S::kNoMarker, v;
  const uint8_t* head = data + pos + marker;
  v.type = get<uint32_t>(head);
  v.length = get<uint32_t>(head + 4);
  v.t_ns = get<int64_t>(head + 8);
  if (v.length > kJournalMaxPayload) return v.status = S::kTooLarge, v;
  const size_t size = journalRecordSize(version, v.length);
  if (left < size) return v.status = S::kTruncated, v;
  const uint32_t stored = get<uint32_t>(data + pos + size - kCrcBytes);
  if (crc32(data + pos, size - kCrcBytes) != stored) return v.status = S::kBadChecksum, v;
  v.payload = head + kHeadV1;
  v.size = size;
  v.status = S::kWhole;
  return v;
}

const char* journalRecordProblem(JournalRecordView::Status status) {
  switch (status) {
    case JournalRecordView::Status::kWhole:
      return "whole record";
    case JournalRecordView::Status::kTruncated:
      return "truncated record";
    case JournalRecordView::Status::kTooLarge:
      return "record length too large";
    case JournalRecordView::Status::kNoMarker:
      return "no record marker";
    case JournalRecordView::Status::kBadChecksum:
      return "checksum mismatch";
  }
  return "damaged record";
}

size_t nextWholeJournalRecord(uint32_t version, const uint8_t* data, size_t n, size_t pos) {
  const size_t min_record = journalRecordSize(version, 0);
  for (size_t q = pos + 1; q + min_record <= n; ++q) {
    if (version >= 2) {
      const uint8_t* hit = std::search(data + q, data + n, kJournalRecordMarker,
                                       kJournalRecordMarker + sizeof(kJournalRecordMarker));
      if (hit == data + n) return n;
      q = size_t(hit - data);
    } else if (get<uint32_t>(data + q) >= kPlausibleTypes ||
               get<uint32_t>(data + q + 4) > n - q - min_record) {
      continue;
    }
    if (journalRecordAt(version, data, n, q).status == JournalRecordView::Status::kWhole) return q;
  }
  return n;
}

}  // namespace cb
