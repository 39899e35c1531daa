// KMS in the loop: Debian's kernel in qemu (TCG) with a virtual display card, running
// kms_flip_probe — the display layer's own DRM code with dumb buffers. Proves the mode set,
// page flips with flip events and timestamps, and (via the qemu monitor's screendump) that the
// flipped buffer is what the card scans out.
#include <cstdlib>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "qemu_vm.h"

namespace cb::hil {
namespace {

struct KernelPaths {
  std::string cache, vmlinuz, moddir, error;
};

// The kernel via tests/hil/common/fetch_kernel.sh (cached; CB_HIL_CACHE overrides the place).
KernelPaths fetchKernel() {
  KernelPaths k;
  const char* env = std::getenv("CB_HIL_CACHE");
  const std::string cache = env && *env ? env : CB_HIL_CACHE;
  k.cache = cache;
  std::string out;
  const int status =
      runCommand("bash " CB_SOURCE_DIR "/tests/hil/common/fetch_kernel.sh '" + cache + "'", &out);
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("VMLINUZ=", 0) == 0) k.vmlinuz = line.substr(8);
    if (line.rfind("MODDIR=", 0) == 0) k.moddir = line.substr(7);
  }
  if (status != 0 || k.vmlinuz.empty() || k.moddir.empty())
    k.error = "fetch_kernel.sh into " + cache + " failed (status " + std::to_string(status) +
              "); it needs apt access to Debian's archive once";
  return k;
}

class KmsFlipTest : public testing::TestWithParam<const char*> {
 protected:
  static void SetUpTestSuite() {
    kernel_ = new KernelPaths(fetchKernel());
    if (!kernel_->error.empty()) return;
    initrd_ = new std::string(std::string(CB_KMS_WORK) + "/kms_flip.cpio.gz");
    std::string out;
    build_status_ =
        runCommand("bash " CB_SOURCE_DIR "/tests/hil/kms/make_kms_initramfs.sh '" + kernel_->cache +
                       "' '" + *initrd_ + "' '/bin/kms_flip_probe 30 60' '" CB_KMS_PROBE "' 2>&1",
                   &out);
    build_log_ = new std::string(out);
  }
  static void TearDownTestSuite() {
    delete kernel_;
    delete initrd_;
    delete build_log_;
  }
  static KernelPaths* kernel_;
  static std::string* initrd_;
  static std::string* build_log_;
  static int build_status_;
};
KernelPaths* KmsFlipTest::kernel_ = nullptr;
std::string* KmsFlipTest::initrd_ = nullptr;
std::string* KmsFlipTest::build_log_ = nullptr;
int KmsFlipTest::build_status_ = -1;

TEST_P(KmsFlipTest, SetsTheModeFlipsWithEventsAndScansOutTheBuffer) {
  ASSERT_TRUE(kernel_->error.empty()) << kernel_->error;
  ASSERT_EQ(build_status_, 0) << *build_log_;
  QemuVm vm(kernel_->vmlinuz, *initrd_, GetParam(), CB_KMS_WORK);
  ASSERT_TRUE(vm.started());
  const std::string showing = vm.waitForLine("KMS-PROBE SHOWING", "KMS-PROBE FAIL", 150);
  std::string console;
  for (const std::string& l : vm.lines()) console += l + "\n";
  ASSERT_NE(showing.find("SHOWING"), std::string::npos)
      << "the probe did not finish; console (" << vm.serialLog() << "):\n"
      << console;

  // Mode set on a connected connector, as master.
  int width = 0, height = 0, flips = 0;
  uint64_t last_ns = 0;
  bool modeset = false, output = false;
  for (const std::string& line : vm.lines()) {
    if (line.rfind("KMS-PROBE OUTPUT", 0) == 0) {
      output = true;
      EXPECT_NE(line.find("master=1"), std::string::npos) << line;
      ASSERT_EQ(std::sscanf(line.c_str() + line.find("mode="), "mode=%dx%d", &width, &height), 2);
    }
    if (line.rfind("KMS-PROBE MODESET ok", 0) == 0) modeset = true;
    unsigned long long t_ns = 0;
    unsigned seq = 0;
    int index = 0;
    if (std::sscanf(line.c_str(), "KMS-PROBE FLIP %d seq=%u t_ns=%llu", &index, &seq, &t_ns) == 3) {
      ++flips;
      EXPECT_EQ(index, flips);
      EXPECT_GT(t_ns, 0u) << "flip event without a timestamp";
      EXPECT_GE(t_ns, last_ns) << "flip timestamps must not go backwards";
      last_ns = t_ns;
    }
  }
  EXPECT_TRUE(output) << console;
  EXPECT_TRUE(modeset) << console;
  EXPECT_EQ(flips, 30) << console;
  EXPECT_GT(width, 0);
  EXPECT_GT(height, 0);

  // What the virtual card scans out is the last flipped buffer: the quadrant pattern.
  const std::string shot = std::string(CB_KMS_WORK) + "/screendump-" + GetParam() + ".ppm";
  std::remove(shot.c_str());
  std::string reply, error;
  ASSERT_TRUE(vm.monitor("screendump " + shot, &reply, &error)) << error;
  PpmImage image;
  ASSERT_TRUE(readPpm(shot, &image, &error)) << error << "\nmonitor: " << reply;
  EXPECT_EQ(image.width, width);
  EXPECT_EQ(image.height, height);
  struct Expect {
    int x, y;
    unsigned char r, g, b;
  };
  const Expect quadrants[] = {{width / 4, height / 4, 255, 0, 0},
                              {3 * width / 4, height / 4, 0, 255, 0},
                              {width / 4, 3 * height / 4, 0, 0, 255},
                              {3 * width / 4, 3 * height / 4, 255, 255, 255}};
  for (const Expect& q : quadrants) {
    const unsigned char* p = image.at(q.x, q.y);
    EXPECT_EQ(p[0], q.r) << "at " << q.x << "," << q.y;
    EXPECT_EQ(p[1], q.g) << "at " << q.x << "," << q.y;
    EXPECT_EQ(p[2], q.b) << "at " << q.x << "," << q.y;
  }
}

INSTANTIATE_TEST_SUITE_P(VirtualCards, KmsFlipTest,
                         testing::Values("bochs-display", "virtio-gpu-pci"),
                         [](const testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param) == "bochs-display" ? "bochs"
                                                                             : "virtio_gpu";
                         });

}  // namespace
}  // namespace cb::hil
