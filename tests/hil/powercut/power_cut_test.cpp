// Power-cut test ("Evidence"; label hil, slow): a session journal written with the
// project's JournalWriter and fsync policy onto a qemu virtio disk (ext4, `cache=none`, so what
// the guest syncs is on the host file), the guest reset (`system_reset` on the qemu monitor) at
// seeded random points while it writes. After each reset the guest boots again, and the
// journal it reads back must hold every record it had synced, lose at most the last second of
// what it had written, and be byte for byte the source's first records (so the rest replays);
// the guest then carries on appending. At the end the disk's journal is taken out of the image
// (debugfs) and `cloudbrush replay` gives the source journal's volume. The seed is printed
// (CB_TEST_SEED=N repeats a run); CB_POWERCUT_RESETS sets the number of resets (10).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "qemu_vm.h"
#include "tests/support/reference_journal.h"
#include "tests/support/test_seed.h"

namespace cb::hil {
namespace {

constexpr int kW = 320, kH = 180;

std::string capture(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? match[1].str() : std::string();
}

struct Kernel {
  std::string cache, vmlinuz, error;
};

Kernel fetchKernel() {
  Kernel k;
  const char* env = std::getenv("CB_HIL_CACHE");
  k.cache = env && *env ? env : CB_HIL_CACHE;
  std::string out;
  const int status = runCommand(
      "bash " CB_SOURCE_DIR "/tests/hil/common/fetch_kernel.sh '" + k.cache + "' 2>&1", &out);
  k.vmlinuz = capture(out, "VMLINUZ=([^\n]+)");
  if (status != 0 || k.vmlinuz.empty())
    k.error = "fetch_kernel.sh into " + k.cache + " failed (status " + std::to_string(status) +
              "); it needs apt access to Debian's archive once:\n" + out;
  return k;
}

// What the guest said of one boot between its WRITING line and the next boot's READBACK: the
// records written (W index t at) and synced (S index at ms), with the guest's own clock.
struct BootLog {
  long last_written = 0, last_synced = -1;
  std::map<long, long long> written_at;  // record -> when it was handed to the OS
  long long last_seen = 0;               // the guest's last sign of life before the reset
  double longest_sync_ms = 0;
};

BootLog readBootLog(const std::vector<std::string>& lines, size_t from, size_t to, long first) {
  BootLog b;
  b.last_written = first - 1;
  for (size_t i = from; i < to; ++i) {
    const std::string& line = lines[i];
    if (line.find("POWERCUT BOOT") != std::string::npos) break;
    long index = 0;
    long long t = 0, at = 0;
    double ms = 0;
    if (std::sscanf(line.c_str(), "W %ld %lld %lld", &index, &t, &at) == 3) {
      b.last_written = index;
      b.written_at[index] = at;
      b.last_seen = std::max(b.last_seen, at);
    } else if (std::sscanf(line.c_str(), "S %ld %lld %lf", &index, &at, &ms) == 3) {
      b.last_synced = index;
      b.longest_sync_ms = std::max(b.longest_sync_ms, ms);
      b.last_seen = std::max(b.last_seen, at);
    } else if (std::sscanf(line.c_str(), "H %lld", &at) == 1) {
      b.last_seen = std::max(b.last_seen, at);
    }
  }
  return b;
}

// `cloudbrush replay` of both journals gives the same volume checksum; returns it.
std::string expectSameReplay(const std::string& source, const std::string& final_journal) {
  std::string source_replay, final_replay;
  EXPECT_EQ(
      runCommand(std::string(CB_CLOUDBRUSH_BIN) + " replay " + source + " 2>&1", &source_replay), 0)
      << source_replay;
  EXPECT_EQ(runCommand(std::string(CB_CLOUDBRUSH_BIN) + " replay " + final_journal + " 2>&1",
                       &final_replay),
            0)
      << final_replay;
  const std::string checksum = capture(source_replay, "volume checksum: ([0-9a-f]{16})");
  EXPECT_FALSE(checksum.empty()) << source_replay;
  EXPECT_EQ(capture(final_replay, "volume checksum: ([0-9a-f]{16})"), checksum) << final_replay;
  return checksum;
}

TEST(PowerCut, ResetWhileWritingTheJournalLosesAtMostTheLastSecond) {
  const Kernel kernel = fetchKernel();
  ASSERT_TRUE(kernel.error.empty()) << kernel.error;
  const std::string work = CB_POWERCUT_WORK;
  std::filesystem::create_directories(work);
  const std::string source = work + "/source.cbj", disk = work + "/disk.img",
                    initrd = work + "/powercut.cpio.gz", final_journal = work + "/final.cbj";
  std::string error;
  // A painting session's journal: the reference strokes six times over, 0.3 s apart (about 22 s
  // of pen), recorded by a real PaintSession (Session, Settings, Device, samples, StrokeMapped).
  ASSERT_TRUE(test::recordReferenceJournal(source, kW, kH, 6, &error)) << error;
  const JournalReadResult source_read = readJournal(source);
  ASSERT_TRUE(source_read.error.empty()) << source_read.error;
  std::vector<int64_t> times;
  for (const JournalRecord& r : source_read.records) times.push_back(r.t_ns);
  std::string out;
  ASSERT_EQ(
      runCommand("bash " CB_SOURCE_DIR "/tests/hil/common/build_initramfs.sh --kernel-cache '" +
                     kernel.cache + "' --out '" + initrd +
                     "' --init " CB_SOURCE_DIR
                     "/tests/hil/powercut/init.sh --module virtio_pci --module virtio_blk "
                     "--module ext4 --module crc32c_generic --binary " CB_POWER_WRITER
                     ":/powercut/journal_power_writer --file '" +
                     source + "':/powercut/source.cbj 2>&1",
                 &out),
      0)
      << out;
  std::filesystem::remove(disk);
  ASSERT_EQ(runCommand("mkfs.ext4 -q -F '" + disk + "' 32M 2>&1", &out), 0) << out;

  const unsigned seed = cb::test::testSeed("power-cut test");
  const int resets =
      std::getenv("CB_POWERCUT_RESETS") ? std::atoi(std::getenv("CB_POWERCUT_RESETS")) : 10;
  std::printf("power-cut test: %d resets; %zu records\n", resets, times.size());
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> delay_ms(300, 4000);

  QemuVm vm(kernel.vmlinuz, initrd,
            QemuVm::Options{
                "powercut", {"-drive", "file=" + disk + ",if=virtio,format=raw,cache=none"}, true},
            work);
  ASSERT_TRUE(vm.started());
  const auto console = [&] {
    std::string text;
    for (const std::string& l : vm.lines()) text += l + "\n";
    return text;
  };
  size_t from = 0;
  double worst_loss_s = 0, worst_sync_ms = 0;
  for (int r = 0; r < resets; ++r) {
    size_t writing_at = 0;
    const std::string writing =
        vm.waitForLine("POWERCUT WRITING", "POWERCUT FAIL", 600, from, &writing_at);
    ASSERT_NE(writing.find("WRITING"), std::string::npos)
        << "boot " << r << " did not start writing; console:\n"
        << console();
    const int wait = delay_ms(random);
    std::this_thread::sleep_for(std::chrono::milliseconds(wait));
    std::string reply, error;
    ASSERT_TRUE(vm.monitor("system_reset", &reply, &error)) << error;
    size_t back_at = 0;
    const std::string back =
        vm.waitForLine("POWERCUT READBACK", "POWERCUT FAIL", 600, writing_at + 1, &back_at);
    ASSERT_NE(back.find("READBACK"), std::string::npos) << "no boot after the reset:\n"
                                                        << console();
    // What the guest had written and synced before the reset: the lines of the boot that was
    // reset (up to the next boot's first line), with the guest's own clock.
    const long first = std::atol(capture(writing, "from=([0-9]+)").c_str());
    const BootLog boot = readBootLog(vm.lines(), writing_at + 1, back_at, first);
    const long last_written = boot.last_written, last_synced = boot.last_synced;
    const double longest_sync_ms = boot.longest_sync_ms;
    const long kept = std::atol(capture(back, "records=([0-9]+)").c_str());
    EXPECT_NE(back.find("prefix=ok"), std::string::npos) << back;
    EXPECT_GE(kept, last_synced + 1) << "a synced record was lost at reset " << r << "\n" << back;
    EXPECT_GE(kept, first) << "records read back by the boot before were lost at reset " << r;
    const long lost = std::max(0L, last_written + 1 - kept);
    // How long before the reset the oldest lost record was handed to the OS (the reset came
    // after the guest's last line), and how much of the session the lost records span.
    const double lost_age_s = lost > 0 && boot.written_at.count(kept)
                                  ? double(boot.last_seen - boot.written_at.at(kept)) / 1e9
                                  : 0.0;
    const double lost_span_s =
        lost > 0 ? double(times[size_t(last_written)] - times[size_t(kept)]) / 1e9 : 0.0;
    worst_loss_s = std::max(worst_loss_s, lost_age_s);
    worst_sync_ms = std::max(worst_sync_ms, longest_sync_ms);
    std::printf(
        "reset %2d after %4d ms: written %ld, synced %ld, read back %ld (%s); lost %ld "
        "records, written %.3f s before the reset at the oldest, spanning %.3f s of the "
        "session; longest sync %.1f ms\n",
        r, wait, last_written + 1, last_synced + 1, kept, capture(back, "tail=([^ ]+)").c_str(),
        lost, lost_age_s, lost_span_s, longest_sync_ms);
    std::fflush(stdout);
    // At most the last second: every record older than a second at the reset survived, but
    // for a sync that was under way when the power went (the guest's longest sync, plus the
    // 50 ms between the guest's signs of life).
    EXPECT_LE(lost_age_s, 1.0 + longest_sync_ms / 1e3 + 0.05)
        << "more than the last second lost at reset " << r;
    from = back_at + 1;
  }
  // Let it finish: all written, unmounted, powered off.
  const std::string done = vm.waitForLine("POWERCUT EXIT", "POWERCUT FAIL", 600, from, nullptr);
  ASSERT_NE(done.find("POWERCUT EXIT 0"), std::string::npos) << console();
  for (int i = 0; i < 300 && vm.running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_FALSE(vm.running()) << "the guest did not power off";
  std::filesystem::remove(final_journal);
  ASSERT_EQ(
      runCommand("debugfs -R 'dump /session.cbj " + final_journal + "' '" + disk + "' 2>&1", &out),
      0)
      << out;
  const JournalReadResult final_read = readJournal(final_journal);
  EXPECT_TRUE(final_read.error.empty()) << final_read.error;
  ASSERT_EQ(final_read.records.size(), source_read.records.size());
  const std::string checksum = expectSameReplay(source, final_journal);
  std::printf(
      "%d resets; oldest lost record written %.3f s before its reset at worst; longest "
      "sync %.1f ms; the final journal replays to %s\n",
      resets, worst_loss_s, worst_sync_ms, checksum.c_str());
}

}  // namespace
}  // namespace cb::hil
