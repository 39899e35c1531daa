// Every export format written onto a file system that fills up: the write fails with an error
// naming the file, the file a previous export left keeps its bytes, and no partial file (final
// or temporary) remains. Two real write failures: the process file-size limit (RLIMIT_FSIZE,
// write() returns EFBIG; runs everywhere) and, where this test may mount, a 256 KiB tmpfs that
// is full (write() returns ENOSPC).
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <string>

#include <sys/mount.h>
#include <sys/resource.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "app/core/atomic_file.h"
#include "app/study/render_export.h"
#include "app/study/volume_export.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A volume whose exports take `side`³ floats of varied (poorly compressible) density.
Volume noisyVolume(int side) {
  Volume v(glm::ivec3(side), glm::vec3(-1.0f), glm::vec3(1.0f));
  uint32_t x = 12345;
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        x = x * 1664525u + 1013904223u;
        v.set(i, j, k, 0.001f + float(x >> 8) / float(1u << 24));
      }
  return v;
}

ImageRgbaF noisyFrame(int side) {
  ImageRgbaF f;
  f.width = f.height = side;
  f.pixels.resize(size_t(side) * side * 4);
  uint32_t x = 777;
  for (float& p : f.pixels) {
    x = x * 1664525u + 1013904223u;
    p = float(x >> 8) / float(1u << 24);
  }
  return f;
}

// Exports a small volume and frame (they fit), then a large one (it does not) with `fill`
// making the disk full first; checks the second export's every file.
void checkExportsOnAFullDisk(const fs::path& dir, const std::function<void()>& fill) {
  exportVolume(noisyVolume(8), dir.string(), "cloud");
  exportRender(noisyFrame(8), dir.string(), "view");
  std::map<std::string, std::string> before;
  for (const auto& e : fs::directory_iterator(dir))
    before[e.path().filename().string()] = bytesOf(e.path());
  ASSERT_EQ(before.size(), volumeExportHasVdb() ? 4u : 3u);
  fill();
  const Volume big = noisyVolume(64);  // 1 MiB of floats: more than the disk has left
  try {
    exportVolume(big, dir.string(), "cloud");
    ADD_FAILURE() << "the volume export did not report the full disk";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "cloud").string()), std::string::npos) << e.what();
  }
  try {
    exportRender(noisyFrame(256), dir.string(), "view");
    ADD_FAILURE() << "the render export did not report the full disk";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "view").string()), std::string::npos) << e.what();
  }
  std::string error;
  EXPECT_FALSE(
      writeFileAtomically((dir / "session.json").string(), std::string(1 << 20, 'x'), &error));
  EXPECT_NE(error.find("session.json"), std::string::npos) << error;
  // Every file as it was, nothing else (no torn final file, no temporary left behind).
  std::map<std::string, std::string> after;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename() != "filler") after[e.path().filename().string()] = bytesOf(e.path());
  EXPECT_EQ(after.size(), before.size());
  for (const auto& [name, bytes] : before) {
    ASSERT_TRUE(after.count(name)) << name << " is gone";
    EXPECT_TRUE(after[name] == bytes) << name << " changed";
  }
}

TEST(ExportFullDisk, FileSizeLimitReachedMidExport) {
  const fs::path dir = fs::temp_directory_path() / ("cb_full_rlimit_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  rlimit saved{};
  getrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, SIG_IGN);  // write() fails with EFBIG instead of the signal killing us
  checkExportsOnAFullDisk(dir, [&] {
    rlimit limit = saved;
    limit.rlim_cur = 48 * 1024;  // the small exports are below, the large ones above
    setrlimit(RLIMIT_FSIZE, &limit);
  });
  setrlimit(RLIMIT_FSIZE, &saved);
  fs::remove_all(dir);
}

TEST(ExportFullDisk, FullTmpfs) {
  const fs::path dir = fs::temp_directory_path() / ("cb_full_tmpfs_" + std::to_string(getpid()));
  fs::create_directories(dir);
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=256k") != 0) {
    fs::remove_all(dir);
    GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno)
                 << "); the file-size-limit test made the same checks";
  }
  checkExportsOnAFullDisk(dir, [&] {
    // Fill what is left, so the next write fails with ENOSPC.
    std::ofstream filler(dir / "filler", std::ios::binary);
    const std::string block(4096, 'f');
    while (filler.write(block.data(), std::streamsize(block.size())) && filler.flush()) {
    }
  });
  ::umount(dir.c_str());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cb
