// The DRM side of the KMS platform, with no EGL in it (kmscube's drm-common/drm-legacy):
// find a card we are master of with a connected connector, pick its CRTC and preferred mode,
// set the mode, queue page flips with DRM_MODE_PAGE_FLIP_EVENT and wait for their events
// (vblank sequence + CLOCK_MONOTONIC timestamp). Also used by the KMS test in qemu with plain
// dumb buffers (tests/hil/kms), so a failure there points here rather than at EGL.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <xf86drmMode.h>

namespace cb {

struct KmsOutput {
  int fd = -1;
  std::string device;  // e.g. /dev/dri/card0
  uint32_t connector_id = 0;
  uint32_t crtc_id = 0;
  drmModeModeInfo mode{};
  std::string connector_name;         // e.g. "Virtual-1"
  drmModeCrtc* saved_crtc = nullptr;  // restored by closeKmsOutput
  bool mode_set = false;
};

// Opens `device` (empty: /dev/dri/card0 .. card15 in turn), makes sure this process is DRM
// master, and picks the first connected connector with a mode, its preferred mode and a CRTC its
// encoders can drive. On failure the error names the device and the reason.
bool openKmsOutput(const std::string& device, KmsOutput* out, std::string* error);
// Restores the CRTC as found and closes the card.
void closeKmsOutput(KmsOutput* out);

// drmModeSetCrtc of framebuffer `fb_id` on the output's CRTC/connector/mode.
bool setKmsMode(KmsOutput* out, uint32_t fb_id, std::string* error);
struct KmsFlipEvent {
  bool received = false;
  uint32_t sequence = 0;   // vblank counter of the CRTC when the flip happened
  uint64_t vblank_ns = 0;  // vblank timestamp (CLOCK_MONOTONIC, see DRM_CAP_TIMESTAMP_MONOTONIC)
};
// drmModePageFlip with DRM_MODE_PAGE_FLIP_EVENT; `pending` receives the event and must live
// until waitKmsPageFlip returns.
bool queueKmsPageFlip(const KmsOutput& out, uint32_t fb_id, KmsFlipEvent* pending,
                      std::string* error);
// Waits up to `timeout_ms` for the event of the flip queued with `pending`.
bool waitKmsPageFlip(const KmsOutput& out, int timeout_ms, KmsFlipEvent* pending,
                     std::string* error);

// Framebuffer object for a buffer of the given format, handle and pitch (drmModeAddFB2).
bool addKmsFramebuffer(const KmsOutput& out, uint32_t width, uint32_t height, uint32_t format,
                       uint32_t handle, uint32_t pitch, uint32_t* fb_id, std::string* error);

// A mode's vertical refresh rate (Hz; session.json's refresh_hz): the pixel clock (kHz) over the
// pixels of a whole frame (htotal × vtotal), halved for double scan, multiplied for vscan and
// doubled for interlace (the field rate), as the kernel's drm_mode_vrefresh() computes it, but
// unrounded; the mode's integer vrefresh when it has no clock or totals. Null with *why_unknown
// when it has neither.
std::optional<double> kmsModeRefreshHz(const drmModeModeInfo& mode, std::string* why_unknown);

}  // namespace cb
