// The headless EGL choice (app/render/gl/egl_device_choice.h) over made-up client extensions and
// device lists: an NVIDIA machine (devices, no surfaceless), Mesa on a GPU, Mesa without one
// (this machine: llvmpipe), nothing at all, and the CLOUDBRUSH_EGL_DEVICE override.
#include "app/render/gl/egl_device_choice.h"

#include <gtest/gtest.h>

namespace cb {
namespace {

const std::string kMesaClient =
    "EGL_EXT_client_extensions EGL_EXT_device_base EGL_EXT_device_enumeration "
    "EGL_EXT_device_query EGL_EXT_platform_base EGL_KHR_client_get_all_proc_addresses "
    "EGL_EXT_platform_device EGL_KHR_platform_gbm EGL_MESA_platform_gbm "
    "EGL_KHR_platform_x11 EGL_EXT_platform_x11 EGL_MESA_platform_surfaceless";
const std::string kNvidiaClient =
    "EGL_EXT_platform_base EGL_EXT_device_base EGL_EXT_device_enumeration EGL_EXT_device_query "
    "EGL_KHR_client_get_all_proc_addresses EGL_EXT_client_extensions EGL_KHR_debug "
    "EGL_EXT_platform_device EGL_EXT_platform_x11 EGL_KHR_platform_x11";

const EglDeviceInfo kSoftware{"EGL_MESA_device_software", "", ""};
const EglDeviceInfo kNvidia{"EGL_NV_device_cuda EGL_EXT_device_drm EGL_EXT_device_drm_render_node",
                            "/dev/dri/card1", "/dev/dri/renderD129"};
const EglDeviceInfo kDrmOnly{"EGL_EXT_device_drm", "/dev/dri/card0", ""};
const EglDeviceInfo kAmd{"EGL_EXT_device_drm EGL_EXT_device_drm_render_node", "/dev/dri/card0",
                         "/dev/dri/renderD128"};

TEST(HeadlessEglChoice, ExtensionsAreWholeWords) {
  EXPECT_TRUE(hasEglExtension("A EGL_EXT_platform_device B", "EGL_EXT_platform_device"));
  EXPECT_FALSE(hasEglExtension("EGL_EXT_platform_device_x", "EGL_EXT_platform_device"));
  EXPECT_FALSE(hasEglExtension("", "EGL_EXT_platform_device"));
}

TEST(HeadlessEglChoice, NvidiaWithoutSurfacelessTakesItsDevice) {
  const HeadlessEglChoice c = chooseHeadlessEgl(kNvidiaClient, {kNvidia}, "");
  ASSERT_EQ(c.kind, HeadlessEglChoice::Kind::kDevice);
  EXPECT_EQ(c.device, 0);
  EXPECT_EQ(c.description, "EGL device 0 (/dev/dri/renderD129)");
  EXPECT_EQ(c.passed_over, "");
}

TEST(HeadlessEglChoice, AHardwareDeviceBeforeSurfacelessAndRenderNodesFirst) {
  // Mesa lists its software device too; a device with a render node wins over one without.
  const HeadlessEglChoice c = chooseHeadlessEgl(kMesaClient, {kSoftware, kDrmOnly, kAmd}, "");
  ASSERT_EQ(c.kind, HeadlessEglChoice::Kind::kDevice);
  EXPECT_EQ(c.device, 2);
  EXPECT_EQ(c.description, "EGL device 2 (/dev/dri/renderD128)");
  const HeadlessEglChoice first = chooseHeadlessEgl(kMesaClient, {kDrmOnly, kSoftware}, "");
  EXPECT_EQ(first.device, 0);
  EXPECT_EQ(first.description, "EGL device 0 (/dev/dri/card0)");
}

TEST(HeadlessEglChoice, MesaWithoutAGpuKeepsSurfaceless) {
  // This machine: llvmpipe, listed as a software device; surfaceless as before.
  const HeadlessEglChoice c = chooseHeadlessEgl(kMesaClient, {kSoftware}, "");
  ASSERT_EQ(c.kind, HeadlessEglChoice::Kind::kSurfaceless);
  EXPECT_EQ(c.passed_over, "no hardware EGL device");
}

TEST(HeadlessEglChoice, ASoftwareDeviceWhenThereIsNoSurfaceless) {
  const HeadlessEglChoice c = chooseHeadlessEgl(kNvidiaClient, {kSoftware}, "");
  ASSERT_EQ(c.kind, HeadlessEglChoice::Kind::kDevice);
  EXPECT_EQ(c.description, "EGL device 0 (software)");
  EXPECT_EQ(c.passed_over, "no hardware EGL device; no EGL_MESA_platform_surfaceless");
}

TEST(HeadlessEglChoice, DevicesAreIgnoredWithoutThePlatformExtension) {
  const HeadlessEglChoice c = chooseHeadlessEgl("EGL_MESA_platform_surfaceless", {kAmd}, "");
  ASSERT_EQ(c.kind, HeadlessEglChoice::Kind::kSurfaceless);
  EXPECT_EQ(c.passed_over, "no EGL_EXT_platform_device");
}

TEST(HeadlessEglChoice, NothingSaysWhy) {
  const HeadlessEglChoice c = chooseHeadlessEgl("EGL_EXT_client_extensions", {}, "");
  EXPECT_EQ(c.kind, HeadlessEglChoice::Kind::kNone);
  EXPECT_NE(c.passed_over.find("no EGL_EXT_platform_device"), std::string::npos);
  EXPECT_NE(c.passed_over.find("no EGL_MESA_platform_surfaceless"), std::string::npos);
  EXPECT_NE(c.passed_over.find("no EGL device at all"), std::string::npos);
}

TEST(HeadlessEglChoice, TheOverrideChoosesAndABadOneIsSaid) {
  const std::vector<EglDeviceInfo> devices{kSoftware, kAmd};
  EXPECT_EQ(chooseHeadlessEgl(kMesaClient, devices, "surfaceless").kind,
            HeadlessEglChoice::Kind::kSurfaceless);
  const HeadlessEglChoice zero = chooseHeadlessEgl(kMesaClient, devices, "0");
  ASSERT_EQ(zero.kind, HeadlessEglChoice::Kind::kDevice);
  EXPECT_EQ(zero.device, 0);
  const HeadlessEglChoice bad = chooseHeadlessEgl(kMesaClient, devices, "7");
  ASSERT_EQ(bad.kind, HeadlessEglChoice::Kind::kDevice);
  EXPECT_EQ(bad.device, 1);  // the automatic choice
  EXPECT_NE(bad.passed_over.find("CLOUDBRUSH_EGL_DEVICE=7 names no available device"),
            std::string::npos);
  // Surfaceless asked for where there is none: the automatic choice, said.
  const HeadlessEglChoice none = chooseHeadlessEgl(kNvidiaClient, {kNvidia}, "surfaceless");
  EXPECT_EQ(none.kind, HeadlessEglChoice::Kind::kDevice);
  EXPECT_FALSE(none.passed_over.empty());
}

}  // namespace
}  // namespace cb
