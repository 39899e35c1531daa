// Runs inside qemu on a virtual DRM card (bochs-display or virtio-gpu): proves mode set and page
// flips with flip events through the same DRM code the KMS display uses
// (app/render/gl/display_kms_output.cpp), with plain dumb buffers so no GPU driver is involved.
// Every result is a line starting "KMS-PROBE" on the serial console, read by kms_qemu_test.
//
//   kms_flip_probe [FLIPS] [HOLD_SECONDS]
//
// Ends showing a test pattern (quadrants red, green, blue, white from the top left, clockwise
// red→green on top, blue→white below) for HOLD_SECONDS so the host can take a screendump.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <drm_fourcc.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>
#include <xf86drm.h>

#include "app/render/gl/display_kms_output.h"

namespace {

struct DumbBuffer {
  uint32_t handle = 0, pitch = 0, fb_id = 0;
  uint64_t size = 0;
  uint32_t* pixels = nullptr;
};

bool createDumb(const cb::KmsOutput& out, uint32_t w, uint32_t h, DumbBuffer* buffer,
                std::string* error) {
  drm_mode_create_dumb create{};
  create.width = w;
  create.height = h;
  create.bpp = 32;
  if (drmIoctl(out.fd, DRM_IOCTL_MODE_CREATE_DUMB, &create) != 0) {
    *error = "DRM_IOCTL_MODE_CREATE_DUMB: " + std::string(std::strerror(errno));
    return false;
  }
  buffer->handle = create.handle;
  buffer->pitch = create.pitch;
  buffer->size = create.size;
  drm_mode_map_dumb map{};
  map.handle = create.handle;
  if (drmIoctl(out.fd, DRM_IOCTL_MODE_MAP_DUMB, &map) != 0) {
    *error = "DRM_IOCTL_MODE_MAP_DUMB: " + std::string(std::strerror(errno));
    return false;
  }
  void* p =
      mmap(nullptr, create.size, PROT_READ | PROT_WRITE, MAP_SHARED, out.fd, off_t(map.offset));
  if (p == MAP_FAILED) {
    *error = "mmap of the dumb buffer: " + std::string(std::strerror(errno));
    return false;
  }
  buffer->pixels = static_cast<uint32_t*>(p);
  return cb::addKmsFramebuffer(out, w, h, DRM_FORMAT_XRGB8888, buffer->handle, buffer->pitch,
                               &buffer->fb_id, error);
}

// Quadrants: red | green over blue | white (XRGB8888).
void fillQuadrants(const DumbBuffer& b, uint32_t w, uint32_t h) {
  for (uint32_t y = 0; y < h; ++y) {
    uint32_t* row = b.pixels + size_t(y) * (b.pitch / 4);
    for (uint32_t x = 0; x < w; ++x) {
      const bool right = x >= w / 2, bottom = y >= h / 2;
      row[x] = !bottom ? (right ? 0x0000ff00u : 0x00ff0000u) : (right ? 0x00ffffffu : 0x000000ffu);
    }
  }
}

void fillGrey(const DumbBuffer& b, uint32_t w, uint32_t h) {
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) b.pixels[size_t(y) * (b.pitch / 4) + x] = 0x00404040u;
}

int fail(const std::string& what) {
  std::printf("KMS-PROBE FAIL %s\n", what.c_str());
  std::fflush(stdout);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  const int flips = argc > 1 ? std::atoi(argv[1]) : 60;
  const int hold_seconds = argc > 2 ? std::atoi(argv[2]) : 20;
  cb::KmsOutput out;
  std::string error;
  if (!cb::openKmsOutput("", &out, &error)) return fail("open: " + error);
  const uint32_t w = out.mode.hdisplay, h = out.mode.vdisplay;
  std::printf("KMS-PROBE OUTPUT device=%s connector=%s crtc=%u mode=%ux%u@%u master=%d\n",
              out.device.c_str(), out.connector_name.c_str(), out.crtc_id, w, h, out.mode.vrefresh,
              drmIsMaster(out.fd));
  uint64_t monotonic = 0;
  drmGetCap(out.fd, DRM_CAP_TIMESTAMP_MONOTONIC, &monotonic);
  std::printf("KMS-PROBE CAP timestamp_monotonic=%d\n", int(monotonic));

  DumbBuffer pattern, grey;
  if (!createDumb(out, w, h, &pattern, &error) || !createDumb(out, w, h, &grey, &error))
    return fail("buffers: " + error);
  fillQuadrants(pattern, w, h);
  fillGrey(grey, w, h);
  if (!cb::setKmsMode(&out, pattern.fb_id, &error)) return fail("modeset: " + error);
  std::printf("KMS-PROBE MODESET ok fb=%u\n", pattern.fb_id);

  // Alternate grey and pattern; an even number of flips, so the last one shows the pattern.
  const int total = flips + (flips % 2);
  uint64_t first_ns = 0, last_ns = 0;
  uint32_t first_seq = 0, last_seq = 0;
  for (int i = 1; i <= total; ++i) {
    const uint32_t fb = (i % 2) ? grey.fb_id : pattern.fb_id;
    cb::KmsFlipEvent event;
    if (!cb::queueKmsPageFlip(out, fb, &event, &error))
      return fail("flip " + std::to_string(i) + ": " + error);
    if (!cb::waitKmsPageFlip(out, 2000, &event, &error))
      return fail("flip " + std::to_string(i) + ": " + error);
    if (event.vblank_ns == 0) return fail("flip " + std::to_string(i) + ": zero timestamp");
    if (last_ns && event.vblank_ns < last_ns)
      return fail("flip " + std::to_string(i) + ": timestamp went backwards");
    if (last_seq && event.sequence < last_seq)
      return fail("flip " + std::to_string(i) + ": sequence went backwards");
    if (i == 1) {
      first_ns = event.vblank_ns;
      first_seq = event.sequence;
    }
    last_ns = event.vblank_ns;
    last_seq = event.sequence;
    std::printf("KMS-PROBE FLIP %d seq=%u t_ns=%llu\n", i, event.sequence,
                static_cast<unsigned long long>(event.vblank_ns));
  }
  const double mean_ms = total > 1 ? double(last_ns - first_ns) / 1e6 / (total - 1) : 0.0;
  std::printf("KMS-PROBE FLIPS count=%d seq_first=%u seq_last=%u mean_interval_ms=%.3f\n", total,
              first_seq, last_seq, mean_ms);
  std::printf("KMS-PROBE SHOWING quadrants %ux%u\n", w, h);
  std::fflush(stdout);
  sleep(unsigned(hold_seconds));
  cb::closeKmsOutput(&out);
  std::printf("KMS-PROBE DONE\n");
  return 0;
}
