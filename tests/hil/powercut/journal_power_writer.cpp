// The guest side of the power-cut test (tests/hil/powercut/README.md): writes a recorded session
// journal again, at its own pace, into a journal on the guest's virtio disk with the project's
// JournalWriter and the painter's fsync policy (a sync at every stroke end; append() and the
// wait between records sync whatever is more than a second old). Every boot first reads back
// what the disk kept (the records must be the source's first N, byte for byte), then carries on
// appending after them, as a resumed session does.
//
//   journal_power_writer SOURCE.cbj TARGET.cbj
//
// Console lines (the host reads them): `POWERCUT READBACK records=N last_t_ns=T tail=...
// prefix=ok|MISMATCH`, `POWERCUT WRITING from=N`, `W I T_NS AT_NS` after record I (session time
// T_NS) was handed to the OS at AT_NS (this boot's CLOCK_MONOTONIC), `S I AT_NS MS` after a sync
// that covers records up to I ended (it took MS), `H AT_NS` every 50 ms while waiting for the
// next record (so the host knows how late the guest was still running), `POWERCUT DONE
// records=N`, `POWERCUT FAIL ...`.
#include <time.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

#include "drivers/core/journal.h"

namespace {

int64_t monotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

bool tipDown(const cb::JournalRecord& r) {
  const auto s = cb::decodePenSample(r.payload);
  return s && (s->buttons & cb::kPenTip) != 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (argc != 3) {
    std::printf("POWERCUT FAIL usage: journal_power_writer SOURCE.cbj TARGET.cbj\n");
    return 2;
  }
  const cb::JournalReadResult source = cb::readJournal(argv[1]);
  if (!source.error.empty() || source.records.empty()) {
    std::printf("POWERCUT FAIL source %s: %s\n", argv[1], source.error.c_str());
    return 2;
  }
  const std::string target = argv[2];
  size_t next = 0;
  std::error_code ec;
  if (std::filesystem::exists(target, ec)) {
    const cb::JournalReadResult back = cb::readJournal(target);
    size_t mismatch = back.records.size();
    for (size_t i = 0; i < back.records.size() && mismatch == back.records.size(); ++i) {
      const cb::JournalRecord &a = back.records[i],
                              &b = i < source.records.size() ? source.records[i] : back.records[i];
      if (i >= source.records.size() || a.type != b.type || a.t_ns != b.t_ns ||
          a.payload != b.payload)
        mismatch = i;
    }
    std::printf(
        "POWERCUT READBACK records=%zu last_t_ns=%lld bytes=%llu intact_bytes=%llu tail=%s "
        "prefix=%s\n",
        back.records.size(),
        static_cast<long long>(back.records.empty() ? -1 : back.records.back().t_ns),
        static_cast<unsigned long long>(std::filesystem::file_size(target, ec)),
        static_cast<unsigned long long>(back.intact_bytes),
        back.error.empty() ? "whole" : "\"torn\"",
        mismatch == back.records.size() ? "ok" : ("MISMATCH@" + std::to_string(mismatch)).c_str());
    if (!back.error.empty()) std::printf("POWERCUT TAIL %s\n", back.error.c_str());
    if (mismatch != back.records.size()) return 1;
    next = back.records.size();
  } else {
    std::printf(
        "POWERCUT READBACK records=0 last_t_ns=-1 bytes=0 intact_bytes=0 tail=none "
        "prefix=ok\n");
  }
  cb::JournalWriter journal;
  std::string warning;
  if (!journal.openForAppend(target, &warning)) {
    std::printf("POWERCUT FAIL %s\n", journal.error().c_str());
    return 1;
  }
  if (!warning.empty()) std::printf("POWERCUT CUT %s\n", warning.c_str());
  if (next >= source.records.size()) {
    std::printf("POWERCUT DONE records=%zu\n", next);
    return 0;
  }
  std::printf("POWERCUT WRITING from=%zu of %zu\n", next, source.records.size());
  bool down = next > 0 && source.records[next - 1].type == cb::JournalRecordType::kPenSample &&
              tipDown(source.records[next - 1]);
  const int64_t t0_source = source.records[next].t_ns, t0 = monotonicNs();
  uint64_t syncs = journal.syncCount();
  size_t written = next;  // records handed to the OS: [0, written)
  int64_t before = monotonicNs(), last_heartbeat = 0;
  const auto noteSync = [&] {
    const int64_t now = monotonicNs();
    if (journal.syncCount() != syncs) {
      syncs = journal.syncCount();
      std::printf("S %zu %lld %.1f\n", written - 1, static_cast<long long>(now),
                  double(now - before) / 1e6);
    }
    before = now;
  };
  for (size_t i = next; i < source.records.size(); ++i) {
    const cb::JournalRecord& r = source.records[i];
    // The recorded pace; the frame loop's once-a-second sync while waiting.
    for (;;) {
      const int64_t due = t0 + (r.t_ns - t0_source), now = monotonicNs();
      if (now >= due) break;
      before = now;
      if (!journal.syncIfDue(now))
        return std::printf("POWERCUT FAIL %s\n", journal.error().c_str()), 1;
      noteSync();
      if (now - last_heartbeat >= 50'000'000) {
        last_heartbeat = now;
        std::printf("H %lld\n", static_cast<long long>(now));
      }
      std::this_thread::sleep_for(
          std::chrono::nanoseconds(std::min<int64_t>(due - now, 10'000'000)));
    }
    before = monotonicNs();
    if (!journal.append(r.type, r.t_ns, r.payload.data(), r.payload.size()))
      return std::printf("POWERCUT FAIL %s\n", journal.error().c_str()), 1;
    written = i + 1;
    std::printf("W %zu %lld %lld\n", i, static_cast<long long>(r.t_ns),
                static_cast<long long>(before));
    noteSync();
    if (r.type == cb::JournalRecordType::kPenSample) {
      const bool tip = tipDown(r);
      if (down && !tip) {  // a stroke ended: the painter syncs
        before = monotonicNs();
        if (!journal.sync()) return std::printf("POWERCUT FAIL %s\n", journal.error().c_str()), 1;
        noteSync();
      }
      down = tip;
    }
  }
  if (!journal.sync()) return std::printf("POWERCUT FAIL %s\n", journal.error().c_str()), 1;
  noteSync();
  std::printf("POWERCUT DONE records=%zu\n", written);
  return 0;
}
