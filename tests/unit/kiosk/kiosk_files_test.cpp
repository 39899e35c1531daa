// The kiosk's files without a display: its settings (config/kiosk.toml), the visitor texts
// (config/kiosk/texts.toml: English complete, Chinese bundled, a missing key falling back to
// English with one log line), the gallery store (sequential pseudonymous numbers, quota
// oldest-first, retention, entries written atomically, the floor of free space on a real full
// tmpfs), journal retention, the operator log, and the bundled attract journal
// being exactly what its documented command writes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/core/atomic_file.h"
#include "app/kiosk/data_retention.h"
#include "app/kiosk/gallery_store.h"
#include "app/kiosk/kiosk_config.h"
#include "app/kiosk/kiosk_texts.h"
#include "app/kiosk/operator_log.h"
#include "app/kiosk/operator_pin.h"
#include "app/kiosk/reserved_file.h"
#include "app/shell/kiosk/attract_journal.h"
#include "drivers/core/journal.h"
#include "small_tmpfs.h"

namespace cb {
namespace {
namespace fs = std::filesystem;

class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

const std::string kConfigDir = std::string(CB_SOURCE_DIR) + "/config";

TEST(KioskConfig, BundledFileParsesToItsDocumentedValues) {
  const KioskConfig c = loadKioskConfig(kConfigDir + "/kiosk.toml");
  EXPECT_EQ(c.language, "en");
  EXPECT_EQ(c.idle_seconds, 90.0);
  EXPECT_EQ(c.warning_seconds, 10.0);
  EXPECT_EQ(c.attract_journal, "kiosk/attract.cbj");
  EXPECT_EQ(c.operator_keys, "ctrl+alt+o");
  EXPECT_FALSE(c.gallery_enabled);
  EXPECT_EQ(c.gallery_quota_bytes, 2000ull << 20);
  EXPECT_EQ(c.min_free_bytes, 256ull << 20);
  EXPECT_EQ(c.metrics_dir, "");
  EXPECT_EQ(c.journal_keep_days, 30.0);
  EXPECT_TRUE(fs::exists(kConfigDir + "/" + c.attract_journal));
}

// Every field, for comparing two settings.
std::string describe(const KioskConfig& c) {
  return c.language + "|" + std::to_string(c.idle_seconds) + "|" +
         std::to_string(c.warning_seconds) + "|" + c.attract_journal + "|" +
         std::to_string(c.orbit_degrees_per_second) + "|" + std::to_string(c.attract_hold_seconds) +
         "|" + std::to_string(c.attract_speed) + "|" + c.operator_keys + "|" +
         std::to_string(c.gallery_enabled) + "|" + std::to_string(c.gallery_quota_bytes) + "|" +
         std::to_string(c.gallery_keep_days) + "|" + std::to_string(c.min_free_bytes) + "|" +
         std::to_string(c.journal_keep_days) + "|" + c.metrics_dir;
}

// The package's /etc/cloudbrush/kiosk.toml (made from the shipped file, config/CMakeLists.txt):
// as installed it changes nothing over the defaults; every key it shows commented out parses
// when uncommented, to the shipped default (so the template never shows a stale value).
TEST(KioskConfig, EtcTemplateChangesNothingAndShowsTheDefaults) {
  const std::string etc = CB_ETC_KIOSK_TOML;
  const KioskConfig shipped = loadKioskConfig(kConfigDir + "/kiosk.toml");
  KioskConfig other;
  other.language = "zh", other.idle_seconds = 33.0, other.gallery_enabled = true;
  other.min_free_bytes = 5ull << 20, other.metrics_dir = "/elsewhere";
  EXPECT_EQ(describe(loadKioskConfig(etc, other)), describe(other)) << "every key is commented out";
  TempDir dir("cb_kiosk_etc");
  std::string text = slurp(etc), uncommented;
  int keys = 0;
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find('\n', at);
    end = end == std::string::npos ? text.size() : end + 1;
    std::string line = text.substr(at, end - at);
    if (line.size() > 1 && line[0] == '#' && std::islower(static_cast<unsigned char>(line[1])) &&
        line.find(" = ") != std::string::npos)
      line.erase(0, 1), ++keys;
    uncommented += line;
    at = end;
  }
  writeText(dir.str() + "/kiosk.toml", uncommented);
  EXPECT_EQ(keys, 14) << "one commented line per key of kiosk.toml";
  EXPECT_EQ(describe(loadKioskConfig(dir.str() + "/kiosk.toml", other)), describe(shipped));
}

TEST(KioskConfig, BadValuesNameTheFileAndKey) {
  TempDir dir("cb_kiosk_config");
  const std::string path = dir.str() + "/kiosk.toml";
  const auto error_of = [&](const std::string& text) {
    writeText(path, text);
    try {
      loadKioskConfig(path);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("[operator]\npin = \"2468\"\n").find(path + ":2: operator.pin is not read"),
            std::string::npos)
      << "no PIN in a config file";
  EXPECT_NE(error_of("[visitor]\n\nidle_seconds = \"long\"\n")
                .find(path + ":3: visitor.idle_seconds: expected a number"),
            std::string::npos)
      << "the file and the line of the key";
  EXPECT_NE(error_of("[gallery]\nmin_free_mb = -1\n").find(path + ":2: gallery.min_free_mb"),
            std::string::npos);
  EXPECT_NE(error_of("[visitor]\nidle_seconds = 5\nwarning_seconds = 6\n")
                .find("warning_seconds must be less than"),
            std::string::npos);
  EXPECT_NE(error_of("[gallery]\nenabled = 1\n").find("gallery.enabled must be true or false"),
            std::string::npos);
  EXPECT_NE(error_of("[visitor\n").find(path), std::string::npos) << "syntax errors name the file";
}

TEST(KioskTexts, EnglishAndChineseBundledWithEveryKey) {
  std::vector<std::string> log;
  const auto collect = [&](const std::string& line) { log.push_back(line); };
  const KioskTexts en = KioskTexts::load(kConfigDir + "/kiosk/texts.toml", "en", collect);
  const KioskTexts zh = KioskTexts::load(kConfigDir + "/kiosk/texts.toml", "zh", collect);
  for (const char* key : kKioskTextKeys) {
    EXPECT_FALSE(en.text(key).empty()) << key;
    EXPECT_NE(zh.text(key), en.text(key)) << key << " is translated";
  }
  EXPECT_TRUE(log.empty()) << log.front();
  EXPECT_EQ(en.text("invitation"), "Pick up the pen and paint a cloud");
  EXPECT_EQ(zh.text("invitation"), "拿起笔，画一朵云");
  EXPECT_EQ(en.format("countdown", {{"seconds", "7"}}),
            "Still there? The sky clears in 7 s - touch the pen to keep painting");
  EXPECT_NE(zh.format("countdown", {{"seconds", "7"}}).find("7 秒"), std::string::npos);
  EXPECT_NE(zh.allText().find("画"), std::string::npos);
}

TEST(KioskTexts, MissingKeyFallsBackToEnglishWithOneLogLine) {
  TempDir dir("cb_kiosk_texts");
  const std::string path = dir.str() + "/texts.toml";
  std::string english = "[en]\n";
  for (const char* key : kKioskTextKeys) english += std::string(key) + " = \"EN " + key + "\"\n";
  writeText(path, english + "[fr]\ninvitation = \"Prenez le stylo\"\n");
  std::vector<std::string> log;
  const KioskTexts fr =
      KioskTexts::load(path, "fr", [&](const std::string& line) { log.push_back(line); });
  EXPECT_EQ(fr.text("invitation"), "Prenez le stylo");
  EXPECT_EQ(fr.text("countdown"), "EN countdown");
  EXPECT_EQ(fr.text("countdown"), "EN countdown");
  ASSERT_EQ(log.size(), 1u) << "one line per missing key";
  EXPECT_EQ(log[0], "texts: 'countdown' is missing in language 'fr'; English shown");
  // An unknown language and an incomplete English table are errors naming the file.
  try {
    KioskTexts::load(path, "de", nullptr);
    ADD_FAILURE() << "no error for an unknown language";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("no texts for language 'de' (it has: en, fr)"),
              std::string::npos)
        << e.what();
  }
  writeText(path, "[en]\ninvitation = \"x\"\n");
  try {
    KioskTexts::load(path, "en", nullptr);
    ADD_FAILURE() << "no error for missing English keys";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": en.invitation_hint is missing"),
              std::string::npos)
        << e.what();
  }
}

void fill(const std::string& dir, size_t bytes) {
  std::ofstream(dir + "/cloud.bin", std::ios::binary) << std::string(bytes, 'x');
}

// An entry with one file of `bytes`, written the way the kiosk writes one (temporary folder,
// committed); its number.
long addEntry(GalleryStore& store, size_t bytes) {
  GalleryWrite write;
  std::string error;
  EXPECT_TRUE(store.begin(&write, &error)) << error;
  fill(write.temp_dir, bytes);
  EXPECT_TRUE(store.commit(write, &error)) << error;
  return write.number;
}

std::vector<std::string> incomingFolders(const std::string& gallery) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& item : fs::directory_iterator(gallery, ec))
    if (item.path().filename().string().rfind(".incoming-", 0) == 0)
      found.push_back(item.path().string());
  return found;
}

TEST(GalleryStore, SequentialNumbersQuotaOldestFirstAndRetention) {
  TempDir dir("cb_kiosk_gallery");
  GalleryStore store(dir.str() + "/gallery", 2500, 30.0);
  std::vector<long> numbers;
  for (int i = 0; i < 3; ++i) numbers.push_back(addEntry(store, 1000));
  EXPECT_EQ(numbers, (std::vector<long>{1, 2, 3}));
  EXPECT_TRUE(fs::is_directory(dir.str() + "/gallery/000002"));
  EXPECT_TRUE(incomingFolders(dir.str() + "/gallery").empty());
  std::string error;
  const auto now = fs::file_time_type::clock::now();
  GalleryCleanup cleanup = store.enforce(3, now, &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_EQ(cleanup.removed_for_quota, (std::vector<long>{1})) << "the oldest goes first";
  EXPECT_EQ(cleanup.bytes_after, 2000u);
  // Numbers are never reused, even when the newest entries are gone.
  fs::remove_all(dir.str() + "/gallery/000003");
  const long fourth = addEntry(store, 10);
  EXPECT_EQ(fourth, 4);
  // Retention: an entry last written 31 days ago goes, a fresh one stays.
  fs::last_write_time(dir.str() + "/gallery/000002/cloud.bin", now - std::chrono::hours(24 * 31));
  fs::last_write_time(dir.str() + "/gallery/000002", now - std::chrono::hours(24 * 31));
  cleanup = store.enforce(-1, now, &error);
  EXPECT_EQ(cleanup.removed_for_age, (std::vector<long>{2}));
  ASSERT_EQ(store.entries().size(), 1u);
  EXPECT_EQ(store.entries()[0].number, 4);
}

TEST(GalleryStore, AnInterruptedSaveLeavesNoEntryAndIsCleanedUp) {
  TempDir dir("cb_kiosk_gallery_interrupted");
  GalleryStore store(dir.str() + "/gallery", 1u << 30, 30.0);
  addEntry(store, 100);
  GalleryWrite write;
  std::string error;
  ASSERT_TRUE(store.begin(&write, &error)) << error;
  fill(write.temp_dir, 100);  // ... and the kiosk is killed here
  ASSERT_EQ(store.entries().size(), 1u) << "a half-written entry is not an entry";
  EXPECT_EQ(GalleryStore(dir.str() + "/gallery", 1u << 30, 30.0).removeIncomplete(),
            (std::vector<std::string>{write.temp_dir}));
  EXPECT_TRUE(incomingFolders(dir.str() + "/gallery").empty());
  EXPECT_EQ(addEntry(store, 100), 2) << "the interrupted number is given again";
}

// A REAL full file system: a 5 MB tmpfs (needs root). The floor of free space is measured with
// statvfs, whatever fills the disk; the oldest entries go to keep it; a write that meets ENOSPC
// leaves no half-written entry and no temporary file; space coming back is seen at once.
TEST(GalleryStore, KeepsTheFloorOfFreeSpaceOnARealFullDisk) {
  test::SmallTmpfs disk(
      fs::temp_directory_path().string() + "/cb_kiosk_full_" + std::to_string(::getpid()),
      5u << 20);
  if (!disk.mounted()) GTEST_SKIP() << disk.why();
  constexpr uint64_t kFloor = 1u << 20;  // 1 MB kept free
  GalleryStore store(disk.dir() + "/gallery", 1u << 30, 30.0, kFloor);
  for (int i = 0; i < 3; ++i) addEntry(store, 1u << 20);  // 3 MB of entries: ~2 MB free
  ASSERT_EQ(store.entries().size(), 3u);
  std::string error;
  GalleryRoom room = store.makeRoom(0, -1, &error);
  EXPECT_TRUE(room.enough && room.removed.empty()) << "above the floor: nothing goes";
  // Something else (journals, logs) fills the disk to half the floor: the oldest entry goes,
  // and one is enough (1 MB back, the floor is 1 MB).
  disk.fillLeaving(kFloor / 2, disk.dir() + "/filler-1");
  ASSERT_LT(disk.freeBytes(), kFloor);
  room = store.makeRoom(0, -1, &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_EQ(room.removed, (std::vector<long>{1}));
  EXPECT_TRUE(room.enough);
  ASSERT_TRUE(room.free_bytes);
  EXPECT_GE(*room.free_bytes, kFloor);
  EXPECT_EQ(*room.free_bytes, disk.freeBytes()) << "statvfs of the disk, not the gallery's sum";
  // The disk completely full (ENOSPC): room for one more entry is asked; all but `keep` (3) go
  // and it is still not enough.
  disk.fillLeaving(0, disk.dir() + "/filler-2");
  room = store.makeRoom(1u << 20, 3, &error);
  EXPECT_EQ(room.removed, (std::vector<long>{2}));
  EXPECT_FALSE(room.enough);
  disk.fillLeaving(0, disk.dir() + "/filler-3");
  // Writing an entry now fails; abandon leaves nothing behind.
  GalleryWrite write;
  ASSERT_TRUE(store.begin(&write, &error)) << error;  // a folder takes no data blocks on tmpfs
  {
    std::ofstream out(write.temp_dir + "/cloud.bin", std::ios::binary);
    out << std::string(1u << 20, 'x');
    out.flush();
    EXPECT_FALSE(out.good()) << "the write met ENOSPC";
  }
  store.abandon(write);
  EXPECT_TRUE(incomingFolders(store.dir()).empty());
  ASSERT_EQ(store.entries().size(), 1u);
  EXPECT_EQ(store.entries()[0].number, 3);
  // An atomic replacement on the full disk fails, leaves no temporary and keeps the old file.
  const std::string counter = store.dir() + "/last-number";
  const std::string before = [&] {
    std::ifstream in(counter);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  EXPECT_FALSE(writeFileAtomically(counter, std::string(64 * 1024, '9'), &error));
  EXPECT_NE(error.find("No space left on device"), std::string::npos) << error;
  std::ifstream in(counter);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), before);
  for (const auto& item : fs::directory_iterator(store.dir()))
    EXPECT_EQ(item.path().filename().string().find(".tmp."), std::string::npos) << item.path();
  // Space returns: seen by the next look, nothing more deleted.
  fs::remove(disk.dir() + "/filler-1");
  fs::remove(disk.dir() + "/filler-2");
  fs::remove(disk.dir() + "/filler-3");
  room = store.makeRoom(1u << 20, -1, &error);
  EXPECT_TRUE(room.enough);
  EXPECT_TRUE(room.removed.empty());
  EXPECT_EQ(addEntry(store, 1u << 20), 4);
}

TEST(OperatorPin, NoDefaultStoredHashedOnlyForTheServiceLockoutGrowsAndPersists) {
  TempDir dir("cb_kiosk_pin");
  double now = 1.7e9;
  const auto wall = [&] { return now; };
  OperatorPinGuard fresh(dir.str(), wall);
  EXPECT_FALSE(fresh.hasPin()) << "no default PIN";
  EXPECT_EQ(fresh.check("2468"), OperatorPinGuard::Result::kWrong);
  std::string error;
  EXPECT_FALSE(fresh.setPin("12a4", &error));
  EXPECT_FALSE(fresh.setPin("123", &error));
  ASSERT_TRUE(fresh.setPin("864213", &error)) << error;
  const std::string file = dir.str() + "/" + OperatorPinGuard::kPinFile;
  EXPECT_EQ(fs::status(file).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
  std::ifstream in(file);
  const std::string stored{std::istreambuf_iterator<char>(in), {}};
  EXPECT_EQ(stored.find("864213"), std::string::npos) << "hashed: " << stored;
  EXPECT_EQ(stored.rfind("$y$", 0), 0u) << "the hash alone, not the PIN's length: " << stored;
  // A restart reads it; two wrong PINs are free, the third locks for 60 s, the next 120 s.
  OperatorPinGuard guard(dir.str(), wall);
  ASSERT_TRUE(guard.hasPin());
  EXPECT_EQ(guard.check("111111"), OperatorPinGuard::Result::kWrong);
  EXPECT_EQ(guard.check("222222"), OperatorPinGuard::Result::kWrong);
  EXPECT_EQ(guard.check("333333"), OperatorPinGuard::Result::kLockedNow);
  EXPECT_EQ(guard.lastLockSeconds(), 60.0);
  EXPECT_EQ(guard.check("864213"), OperatorPinGuard::Result::kStillLocked) << "even the right one";
  now += 30.0;
  // Restarting the kiosk does not end the lock.
  OperatorPinGuard restarted(dir.str(), wall);
  EXPECT_NEAR(restarted.lockedForSeconds(), 30.0, 1e-3);
  now += 31.0;
  EXPECT_EQ(restarted.check("444444"), OperatorPinGuard::Result::kLockedNow);
  EXPECT_EQ(restarted.lastLockSeconds(), 120.0) << "each further wrong PIN doubles the lock";
  now += 121.0;
  EXPECT_EQ(OperatorPinGuard(dir.str(), wall).check("864213"), OperatorPinGuard::Result::kRight);
  OperatorPinGuard after(dir.str(), wall);
  EXPECT_EQ(after.failures(), 0);
  EXPECT_EQ(after.check("000000"), OperatorPinGuard::Result::kWrong) << "the right one reset it";
  // A damaged lockout file keeps the panel locked (for the longest lock), it does not unlock it.
  writeText(dir.str() + "/" + OperatorPinGuard::kLockoutFile, "garbage");
  OperatorPinGuard damaged(dir.str(), wall);
  EXPECT_NEAR(damaged.lockedForSeconds(), OperatorPinGuard::kLongestLockS, 1e-3);
  EXPECT_NE(damaged.problem().find("unreadable"), std::string::npos);
}

// A PIN file written before the PIN's length was left out ("<digits> <hash>") still works, and
// its stored length is ignored: a wrong length there neither refuses the right PIN nor makes a
// shorter one right.
TEST(OperatorPin, OldFilesWithTheLengthStillWorkAndTheLengthIsIgnored) {
  TempDir dir("cb_kiosk_pin_old");
  const std::string hash = hashOperatorPin("864213");
  ASSERT_EQ(hash.rfind("$", 0), 0u) << hash;
  for (const char* length : {"6", "4", "12"}) {
    writeText(dir.str() + "/" + OperatorPinGuard::kPinFile,
              std::string(length) + " " + hash + "\n");
    OperatorPinGuard guard(dir.str());
    ASSERT_TRUE(guard.hasPin()) << length << ": " << guard.problem();
    EXPECT_EQ(guard.problem(), "");
    EXPECT_EQ(guard.check("8642"), OperatorPinGuard::Result::kWrong) << length;
    EXPECT_EQ(guard.check("864213"), OperatorPinGuard::Result::kRight) << length;
  }
  for (const char* bad : {"", "6\n", "x $y$abc\n", "6 notahash\n"}) {
    writeText(dir.str() + "/" + OperatorPinGuard::kPinFile, bad);
    OperatorPinGuard guard(dir.str());
    EXPECT_FALSE(guard.hasPin()) << bad;
    EXPECT_NE(guard.problem().find("not a PIN record"), std::string::npos) << bad;
  }
}

// health.json and the metrics on a REAL disk filled to the last byte (a 1 MB tmpfs, needs
// root): the temporary-and-rename writer cannot make its new file, the spare copy's kept blocks
// take the new content, and the file a reader opens is whole, old or new.
TEST(ReservedFile, KeepsBeingReplacedOnADiskFullToTheLastByte) {
  test::SmallTmpfs disk(
      fs::temp_directory_path().string() + "/cb_kiosk_reserved_" + std::to_string(::getpid()),
      1u << 20);
  if (!disk.mounted()) GTEST_SKIP() << disk.why();
  const std::string path = disk.dir() + "/health.json";
  const auto json = [](int n) {
    return "{\"visits\":" + std::to_string(n) + ",\"storage\":\"" + std::string(400, 'x') + "\"}\n";
  };
  std::string error;
  ASSERT_TRUE(writeFileKeepingBlocks(path, json(1), &error)) << error;
  ASSERT_TRUE(writeFileKeepingBlocks(path, json(2), &error)) << error;  // makes the spare
  disk.fillLeaving(0, disk.dir() + "/runaway.log");
  ASSERT_EQ(disk.freeBytes(), 0u);
  EXPECT_FALSE(writeFileAtomically(path, json(99), &error)) << "the disk is really full";
  EXPECT_NE(error.find("No space left"), std::string::npos) << error;
  for (int n = 3; n < 8; ++n) {
    ASSERT_TRUE(writeFileKeepingBlocks(path, json(n), &error)) << n << ": " << error;
    EXPECT_EQ(slurp(path), json(n));
  }
  for (const auto& e : fs::directory_iterator(disk.dir()))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "left behind";
  // Content past the blocks it had needs a new one: refused, and the file keeps what it had.
  EXPECT_FALSE(writeFileKeepingBlocks(path, std::string(20000, 'y'), &error));
  EXPECT_EQ(slurp(path), json(7));
}

TEST(DataRetention, DeletesOnlyOldJournals) {
  TempDir dir("cb_kiosk_retention");
  const auto now = fs::file_time_type::clock::now();
  for (const char* name : {"old.cbj", "new.cbj", "old.txt"}) writeText(dir.str() + "/" + name, "x");
  fs::last_write_time(dir.str() + "/old.cbj", now - std::chrono::hours(24 * 40));
  fs::last_write_time(dir.str() + "/old.txt", now - std::chrono::hours(24 * 40));
  std::string error;
  const std::vector<std::string> deleted =
      deleteFilesOlderThan(dir.str(), ".cbj", 30.0, now, &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_EQ(deleted, (std::vector<std::string>{dir.str() + "/old.cbj"}));
  EXPECT_TRUE(fs::exists(dir.str() + "/new.cbj"));
  EXPECT_TRUE(fs::exists(dir.str() + "/old.txt"));
  EXPECT_TRUE(deleteFilesOlderThan(dir.str() + "/missing", ".cbj", 1.0, now, &error).empty());
}

TEST(OperatorLog, AppendsOneStampedLinePerAction) {
  TempDir dir("cb_kiosk_oplog");
  OperatorLog log(dir.str() + "/operator.log");
  std::string error;
  ASSERT_TRUE(log.write("panel-opened", &error)) << error;
  ASSERT_TRUE(log.write("set-idle-seconds 105", &error)) << error;
  const std::string text = slurp(log.path());
  ASSERT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
  EXPECT_EQ(text.substr(4, 1), "-");
  EXPECT_EQ(text.substr(19, 15), "Z panel-opened\n");
  EXPECT_NE(text.find("Z set-idle-seconds 105\n"), std::string::npos);
  OperatorLog nowhere(dir.str() + "/missing/operator.log");
  EXPECT_FALSE(nowhere.write("x", &error));
  EXPECT_NE(error.find("missing/operator.log"), std::string::npos);
}

TEST(AttractJournal, BundledFileIsWhatTheDocumentedCommandWrites) {
  TempDir dir("cb_kiosk_attract");
  std::string error;
  ASSERT_TRUE(writeAttractJournal(dir.str() + "/attract.cbj", &error)) << error;
  const std::string made = slurp(dir.str() + "/attract.cbj");
  EXPECT_EQ(made, slurp(kConfigDir + "/kiosk/attract.cbj"))
      << "regenerate: cloudbrush kiosk --make-attract-journal config/kiosk/attract.cbj";
  const JournalReadResult journal = readJournal(dir.str() + "/attract.cbj");
  EXPECT_TRUE(journal.error.empty()) << journal.error;
  size_t samples = 0;
  for (const JournalRecord& r : journal.records) samples += r.type == JournalRecordType::kPenSample;
  EXPECT_GT(samples, 500u);
}

}  // namespace
}  // namespace cb
