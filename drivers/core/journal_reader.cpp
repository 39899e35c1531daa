// Reading a journal: every whole record, resynchronising after a damaged stretch.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "drivers/core/journal.h"
#include "drivers/core/journal_framing.h"

namespace cb {
namespace {

// "NAME: byte OFFSET: WHY" for the first gap, then what was skipped in all.
std::string describeGaps(const std::string& name, const JournalReadResult& r, size_t n) {
  const JournalGap& first = r.gaps.front();
  std::string text = name + ": byte " + std::to_string(first.offset) + ": " + first.why;
  uint64_t bytes = 0;
  for (const JournalGap& g : r.gaps) bytes += g.bytes;
  text += "; skipped " + std::to_string(bytes) + " damaged bytes in " +
          std::to_string(r.gaps.size()) + (r.gaps.size() == 1 ? " stretch" : " stretches") + " (";
  for (size_t i = 0; i < r.gaps.size() && i < 8; ++i)
    text += (i ? ", " : "") + std::to_string(r.gaps[i].bytes) + " at byte " +
            std::to_string(r.gaps[i].offset);
  if (r.gaps.size() > 8) text += ", ...";
  text += ")";
  if (r.gaps.back().offset + r.gaps.back().bytes == n && r.intact_bytes <= r.gaps.back().offset)
    text += ", the last one a damaged tail";
  return text;
}

}  // namespace

JournalReadResult parseJournal(const uint8_t* data, size_t n, const std::string& name) {
  JournalReadResult out;
  auto fail = [&](uint64_t offset, const std::string& why) {
    out.error = name + ": byte " + std::to_string(offset) + ": " + why;
    return out;
  };
  if (n < kJournalHeaderSize)
    return fail(0, "too short for a journal header (" + std::to_string(n) + " bytes)");
  if (std::memcmp(data, kJournalMagic, sizeof(kJournalMagic)) != 0)
    return fail(0, "not a cloudbrush journal (bad magic)");
  uint32_t version;
  std::memcpy(&version, data + 8, 4);
  if (version == 0 || version > kJournalVersion)
    return fail(8, "unsupported journal version " + std::to_string(version));
  out.version = version;
  size_t pos = kJournalHeaderSize;
  out.intact_bytes = pos;
  while (pos < n) {
    const JournalRecordView v = journalRecordAt(version, data, n, pos);
    if (v.status != JournalRecordView::Status::kWhole) {
      const size_t next = nextWholeJournalRecord(version, data, n, pos);
      out.gaps.push_back({pos, next - pos, journalRecordProblem(v.status)});
      pos = next;
      continue;
    }
    if (v.type >= uint32_t(JournalRecordType::kPenSample) && v.type <= kLastJournalRecordType) {
      JournalRecord rec;
      rec.type = JournalRecordType(v.type);
      rec.t_ns = v.t_ns;
      rec.payload.assign(v.payload, v.payload + v.length);
      out.records.push_back(std::move(rec));
    } else {
      ++out.skipped_unknown;
    }
    pos += v.size;
    out.intact_bytes = pos;
  }
  if (!out.gaps.empty()) out.error = describeGaps(name, out, n);
  return out;
}

JournalReadResult readJournal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    JournalReadResult r;
    r.error = path + ": cannot open: " + std::strerror(errno);
    return r;
  }
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  return parseJournal(bytes.data(), bytes.size(), path);
}

}  // namespace cb
