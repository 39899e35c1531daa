// The kiosk's files without a display: its settings (config/kiosk.toml), the visitor texts
// (config/kiosk/texts.toml: English complete, Chinese bundled, a missing key falling back to
// English with one log line), the gallery store (sequential pseudonymous numbers, quota
// oldest-first, retention), journal retention, the operator log, and the bundled attract journal
// being exactly what its documented command writes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/kiosk/data_retention.h"
#include "app/kiosk/gallery_store.h"
#include "app/kiosk/kiosk_config.h"
#include "app/kiosk/kiosk_texts.h"
#include "app/kiosk/operator_log.h"
#include "app/shell/attract_journal.h"
#include "drivers/core/journal.h"

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
  EXPECT_EQ(c.operator_pin, "2468");
  EXPECT_FALSE(c.gallery_enabled);
  EXPECT_EQ(c.gallery_quota_bytes, 2000ull << 20);
  EXPECT_EQ(c.journal_keep_days, 30.0);
  EXPECT_TRUE(fs::exists(kConfigDir + "/" + c.attract_journal));
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
  EXPECT_NE(error_of("[operator]\npin = \"12a4\"\n").find(path + ": operator.pin must be digits"),
            std::string::npos);
  EXPECT_NE(error_of("[operator]\npin = \"12\"\n").find("operator.pin must have 4 to 12"),
            std::string::npos);
  EXPECT_NE(error_of("[visitor]\nidle_seconds = \"long\"\n")
                .find(path + ":2: visitor.idle_seconds: expected a number"),
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

TEST(GalleryStore, SequentialNumbersQuotaOldestFirstAndRetention) {
  TempDir dir("cb_kiosk_gallery");
  GalleryStore store(dir.str() + "/gallery", 2500, 30.0);
  std::vector<long> numbers;
  for (int i = 0; i < 3; ++i) {
    long number = 0;
    std::string path, error;
    ASSERT_TRUE(store.allocate(&number, &path, &error)) << error;
    fill(path, 1000);
    numbers.push_back(number);
  }
  EXPECT_EQ(numbers, (std::vector<long>{1, 2, 3}));
  EXPECT_TRUE(fs::is_directory(dir.str() + "/gallery/000002"));
  std::string error;
  const auto now = fs::file_time_type::clock::now();
  GalleryCleanup cleanup = store.enforce(3, now, &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_EQ(cleanup.removed_for_quota, (std::vector<long>{1})) << "the oldest goes first";
  EXPECT_EQ(cleanup.bytes_after, 2000u);
  // Numbers are never reused, even when the newest entries are gone.
  fs::remove_all(dir.str() + "/gallery/000003");
  long number = 0;
  std::string path;
  ASSERT_TRUE(store.allocate(&number, &path, &error)) << error;
  EXPECT_EQ(number, 4);
  // Retention: an entry last written 31 days ago goes, a fresh one stays.
  fill(path, 10);
  fs::last_write_time(dir.str() + "/gallery/000002/cloud.bin", now - std::chrono::hours(24 * 31));
  fs::last_write_time(dir.str() + "/gallery/000002", now - std::chrono::hours(24 * 31));
  cleanup = store.enforce(-1, now, &error);
  EXPECT_EQ(cleanup.removed_for_age, (std::vector<long>{2}));
  ASSERT_EQ(store.entries().size(), 1u);
  EXPECT_EQ(store.entries()[0].number, 4);
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
