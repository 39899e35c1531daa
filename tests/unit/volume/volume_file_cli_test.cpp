// The real binary on bad volume files: `cloudbrush render --volume BAD --out x.png` exits with a
// non-zero status and prints the reader's message (file, header field, problem) instead of
// aborting. HUGE.vol claims 100000^3 voxels; the 2048^3 one used to allocate 32 GiB and abort.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/command_run.h"

namespace {

using cb::test::CommandRun;

CommandRun run(const std::string& command) {
  return cb::test::runCommand(command);
}

std::string header(const std::string& dims) {
  return "{\"format\":\"cloudbrush-volume\",\"version\":1,\"dims\":" + dims +
         ",\"world_min\":[-1,-1,-1],\"world_max\":[1,1,1],\"type\":\"float32\","
         "\"endian\":\"little\",\"order\":\"x-fastest\"}\n";
}

std::string header2(const std::string& dims, const std::string& lo, const std::string& hi) {
  return "{\"format\":\"cloudbrush-volume\",\"version\":2,\"dims\":" + dims +
         ",\"world_min\":[-1,-1,-1],\"world_max\":[1,1,1],\"stored_min\":" + lo +
         ",\"stored_max\":" + hi +
         ",\"type\":\"float32\",\"endian\":\"little\",\"order\":\"x-fastest\"}\n";
}

class RenderBadVolume : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("cb_volume_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Writes `bytes` to dir/name and runs `cloudbrush render` on it.
  CommandRun render(const std::string& name, const std::string& bytes) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return run("cd '" + dir_.string() + "' && '" + CB_CLOUDBRUSH_BIN + "' render --volume " + name +
               " --out x.png");
  }

  std::filesystem::path dir_;
};

TEST_F(RenderBadVolume, HugeDimsExitNonZeroNamingFileAndField) {
  const CommandRun r =
      render("HUGE.vol", header("[100000,100000,100000]") + std::string(1234, '\0'));
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_GT(r.status, 0) << "did not exit normally (signal?): " << r.out;
  EXPECT_NE(r.out.find("cloudbrush render: volume file 'HUGE.vol': header field 'dims': "
                       "100000x100000x100000 voxels need 4000000000000000 bytes of float32 but "
                       "the file holds 1234 bytes after the header"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.png"));
}

TEST_F(RenderBadVolume, TheFormerAbortCaseExitsNonZero) {
  const CommandRun r = render("big.vol", header("[2048,2048,2048]") + std::string(1234, '\0'));
  EXPECT_GT(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("volume file 'big.vol': header field 'dims': 2048x2048x2048 voxels need "
                       "34359738368 bytes"),
            std::string::npos)
      << r.out;
}

TEST_F(RenderBadVolume, EveryBadHeaderExitsNonZeroWithItsField) {
  const std::string body(64 * 4, '\0');
  const struct {
    const char* file;
    std::string bytes;
    const char* message;
  } cases[] = {
      {"zero.vol", header("[4,0,4]") + body, "header field 'dims': 0 (y) is not a positive"},
      {"negative.vol", header("[-4,4,4]") + body, "header field 'dims': -4 (x) is not a positive"},
      {"overflow.vol", header("[4294967296,4294967296,4294967296]") + body,
       "header field 'dims': 4294967296x4294967296x4294967296 voxels of float32 need more bytes"},
      {"truncated.vol", header("[4,4,4]") + body.substr(8),
       "header field 'dims': 4x4x4 voxels need 256 bytes of float32 but the file holds 248"},
      {"trailing.vol", header("[4,4,4]") + body + "!",
       "header field 'dims': 4x4x4 voxels need 256 bytes of float32 but the file holds 257"},
      {"notjson.vol", "P6\n4 4\n255\n" + body, "header line: malformed JSON"},
      {"missing_field.vol", "{\"format\":\"cloudbrush-volume\",\"version\":1}\n" + body,
       "header field 'type' is missing"},
      {"box_outside.vol", header2("[4,4,4]", "[0,0,0]", "[4,8,4]") + body,
       "header field 'stored_max': 8 (y) lies outside dims 4x4x4"},
      {"box_bytes.vol", header2("[4,4,4]", "[0,0,0]", "[4,4,2]") + body,
       "header fields 'stored_min', 'stored_max': the stored box [0,0,0]..[4,4,2] (32 voxels) "
       "needs 128 bytes of float32 but the file holds 256"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const CommandRun r = render(c.file, c.bytes);
    EXPECT_GT(r.status, 0) << r.out;
    EXPECT_NE(r.out.find(std::string("volume file '") + c.file + "': " + c.message),
              std::string::npos)
        << r.out;
  }
}

}  // namespace
