// The real product on KMS in qemu (label slow, ≈ 4–5 min): `cloudbrush paint --display kms`
// with EGL on GBM and Mesa's llvmpipe inside the guest (the initramfs carries Mesa's libraries,
// ≈ 90 MB compressed). Proves the GBM/KMS display end to end: the mode set and page flips of
// EGL frames, and a qemu screendump that shows the bundled cloud — compared pixel by pixel with
// the same frame rendered headlessly on the host. The card's mode is 640x400 (bochs-display
// xres/yres): a quarter of 1280x800's pixels, so the full-resolution still frame stays well
// inside the limit under TCG on a slow or shared machine.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "app/render/image_io.h"
#include "qemu_vm.h"

namespace cb::hil {
namespace {

std::string fetchModdirAndKernel(std::string* vmlinuz, std::string* cache_dir) {
  const char* env = std::getenv("CB_HIL_CACHE");
  const std::string cache = env && *env ? env : CB_HIL_CACHE;
  *cache_dir = cache;
  std::string out, moddir;
  runCommand("bash " CB_SOURCE_DIR "/tests/hil/common/fetch_kernel.sh '" + cache + "'", &out);
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("VMLINUZ=", 0) == 0) *vmlinuz = line.substr(8);
    if (line.rfind("MODDIR=", 0) == 0) moddir = line.substr(7);
  }
  return moddir;
}

TEST(KmsEgl, CloudbrushShowsTheBundledCloudOnAVirtualCard) {
  std::string vmlinuz, cache;
  const std::string moddir = fetchModdirAndKernel(&vmlinuz, &cache);
  ASSERT_FALSE(moddir.empty()) << "fetch_kernel.sh failed (needs apt access once)";
  const std::string work = CB_KMS_WORK;
  const std::string initrd = work + "/kms_egl.cpio.gz";
  // First a few orbiting frames (mode set, then EGL frames by page flip), then a still frame at
  // full resolution that stays on screen for the screendump. No pen backend: with one (the
  // default finds /dev/input and waits for a pen there) a still camera shows the painting view,
  // which never prints the full-resolution frame's statistics this test waits for.
  const std::string guest_command =
      "cloudbrush paint --display kms --backend none --grid 64 --frames 3; "
      "cloudbrush paint --display kms --backend none --grid 64 --orbit 0 --stats";
  std::string log;
  ASSERT_EQ(
      runCommand("CB_KMS_WITH_LIBS=1 bash " CB_SOURCE_DIR "/tests/hil/kms/make_kms_initramfs.sh '" +
                     cache + "' '" + initrd + "' '" + guest_command + "' '" + CB_CLOUDBRUSH_BIN +
                     "' 2>&1",
                 &log),
      0)
      << log;

  // The same frame on the host: reference camera, 64³ cloud, the card's 640x400.
  const std::string host_dir = work + "/host-render";
  std::filesystem::remove_all(host_dir);
  std::string host_out;
  ASSERT_EQ(runCommand("env -u DISPLAY LIBGL_ALWAYS_SOFTWARE=1 '" CB_CLOUDBRUSH_BIN
                       "' paint --display surfaceless --size 640x400 --grid 64 --out-dir '" +
                           host_dir + "'",
                       &host_out),
            0);
  const ImageRgba8 reference = readPng(host_dir + "/cloudbrush-cumulus.png");

  QemuVm vm(vmlinuz, initrd, "bochs-display,xres=640,yres=400", work);
  ASSERT_TRUE(vm.started());
  const auto boot = std::chrono::steady_clock::now();
  const std::string still = vm.waitForLine("ray casting 640x400", "cloudbrush paint:", 540);
  std::printf("the still frame reported %.0f s after qemu started (limit 540 s)\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - boot).count());
  std::string console;
  for (const std::string& l : vm.lines()) console += l + "\n";
  ASSERT_NE(still.find("ray casting"), std::string::npos) << console;

  // The orbiting run: EGL frames reached the screen by page flip, with flip events.
  EXPECT_NE(console.find("cloudbrush: kms display 640x400"), std::string::npos) << console;
  EXPECT_NE(console.find("cloudbrush: 3 frames in"), std::string::npos) << console;
  EXPECT_NE(console.find("cloudbrush: last page flip: vblank sequence"), std::string::npos)
      << console;

  // The statistics are printed while the frame is drawn, before it is presented (the first
  // present sets the mode): screendumps until the frame is on the card, at most 60 s.
  const std::string shot = work + "/screendump-egl.ppm";
  std::string reply, error;
  PpmImage image;
  for (int tries = 0; tries < 30; ++tries) {
    std::remove(shot.c_str());
    ASSERT_TRUE(vm.monitor("screendump " + shot, &reply, &error)) << error;
    ASSERT_TRUE(readPpm(shot, &image, &error)) << error;
    if (image.width == reference.width && image.at(image.width / 2, image.height / 2)[0] > 0) break;
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
  ASSERT_EQ(image.width, reference.width);
  ASSERT_EQ(image.height, reference.height);
  double total_error = 0.0;
  long far_off = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int d = std::abs(int(image.at(x, y)[c]) - int(reference.at(x, y)[c]));
        total_error += d;
        far_off += d > 8;
      }
    }
  }
  const double samples = double(image.width) * image.height * 3;
  std::printf(
      "KMS screendump vs host render: mean abs error %.3f/255, %.4f%% of channels off by > 8\n",
      total_error / samples, 100.0 * double(far_off) / samples);
  // llvmpipe in the guest runs 128-bit vectors (TCG), the host 256-bit: tiny rounding
  // differences are allowed, a different picture is not.
  EXPECT_LT(total_error / samples, 1.0) << "mean abs error per channel (of 255)";
  EXPECT_LT(double(far_off) / samples, 0.005) << "share of channels off by more than 8";
  // And it is the cloud: bright middle, sky corners.
  EXPECT_GT(int(image.at(image.width / 2, image.height / 2)[0]), 200);
  EXPECT_GT(int(image.at(2, 2)[2]), int(image.at(2, 2)[0]) + 30);
}

}  // namespace
}  // namespace cb::hil
