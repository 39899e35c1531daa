#include "app/render/gl/display_kms_output.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>
#include <xf86drm.h>

namespace cb {
namespace {

std::string errnoText(int err) {
  return std::string(std::strerror(err));
}

// The CRTC that drives `connector`: the one its current encoder uses, else the first CRTC any of
// its encoders can drive (kmscube's find_crtc_for_connector).
uint32_t findCrtc(int fd, const drmModeRes* resources, const drmModeConnector* connector) {
  if (connector->encoder_id) {
    if (drmModeEncoder* encoder = drmModeGetEncoder(fd, connector->encoder_id)) {
      const uint32_t crtc = encoder->crtc_id;
      drmModeFreeEncoder(encoder);
      if (crtc) return crtc;
    }
  }
  for (int e = 0; e < connector->count_encoders; ++e) {
    drmModeEncoder* encoder = drmModeGetEncoder(fd, connector->encoders[e]);
    if (!encoder) continue;
    for (int c = 0; c < resources->count_crtcs; ++c) {
      if (encoder->possible_crtcs & (1u << c)) {
        const uint32_t crtc = resources->crtcs[c];
        drmModeFreeEncoder(encoder);
        return crtc;
      }
    }
    drmModeFreeEncoder(encoder);
  }
  return 0;
}

bool tryCard(const std::string& path, KmsOutput* out, std::string* error) {
  const int fd = open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) {
    *error = path + ": cannot open (" + errnoText(errno) + ")";
    return false;
  }
  // The first opener of a card becomes master; a compositor or X server already holding it
  // means KMS cannot take the display. Root may still take it explicitly.
  if (!drmIsMaster(fd) && drmSetMaster(fd) != 0) {
    *error = path + ": not DRM master (an X server or compositor holds the display)";
    close(fd);
    return false;
  }
  drmModeRes* resources = drmModeGetResources(fd);
  if (!resources) {
    *error = path + ": not a KMS device (drmModeGetResources: " + errnoText(errno) + ")";
    close(fd);
    return false;
  }
  drmModeConnector* chosen = nullptr;
  for (int i = 0; i < resources->count_connectors && !chosen; ++i) {
    drmModeConnector* connector = drmModeGetConnector(fd, resources->connectors[i]);
    if (connector && connector->connection == DRM_MODE_CONNECTED && connector->count_modes > 0)
      chosen = connector;
    else if (connector)
      drmModeFreeConnector(connector);
  }
  if (!chosen) {
    *error = path + ": no connected connector with a mode";
    drmModeFreeResources(resources);
    close(fd);
    return false;
  }
  // The preferred mode, else the largest (kmscube's choice).
  int best = 0, best_area = 0;
  for (int m = 0; m < chosen->count_modes; ++m) {
    const drmModeModeInfo& mode = chosen->modes[m];
    if (mode.type & DRM_MODE_TYPE_PREFERRED) {
      best = m;
      break;
    }
    const int area = mode.hdisplay * mode.vdisplay;
    if (area > best_area) {
      best_area = area;
      best = m;
    }
  }
  const uint32_t crtc = findCrtc(fd, resources, chosen);
  if (!crtc) {
    *error = path + ": no CRTC can drive connector " + std::to_string(chosen->connector_id);
    drmModeFreeConnector(chosen);
    drmModeFreeResources(resources);
    close(fd);
    return false;
  }
  out->fd = fd;
  out->device = path;
  out->connector_id = chosen->connector_id;
  out->crtc_id = crtc;
  out->mode = chosen->modes[best];
  const char* type_name = drmModeGetConnectorTypeName(chosen->connector_type);
  out->connector_name = std::string(type_name ? type_name : "connector") + "-" +
                        std::to_string(chosen->connector_type_id);
  out->saved_crtc = drmModeGetCrtc(fd, crtc);
  drmModeFreeConnector(chosen);
  drmModeFreeResources(resources);
  return true;
}

void onPageFlip(int, unsigned int sequence, unsigned int tv_sec, unsigned int tv_usec,
                void* user_data) {
  auto* event = static_cast<KmsFlipEvent*>(user_data);
  event->sequence = sequence;
  event->vblank_ns = uint64_t(tv_sec) * 1000000000ull + uint64_t(tv_usec) * 1000ull;
  event->received = true;
}

}  // namespace

bool openKmsOutput(const std::string& device, KmsOutput* out, std::string* error) {
  if (!device.empty()) return tryCard(device, out, error);
  std::string reasons;
  for (int i = 0; i < 16; ++i) {
    const std::string path = "/dev/dri/card" + std::to_string(i);
    if (access(path.c_str(), F_OK) != 0) continue;
    std::string why;
    if (tryCard(path, out, &why)) return true;
    reasons += (reasons.empty() ? "" : "; ") + why;
  }
  *error = reasons.empty() ? "no /dev/dri/card* device" : reasons;
  return false;
}

void closeKmsOutput(KmsOutput* out) {
  if (out->fd < 0) return;
  if (out->saved_crtc) {
    const drmModeCrtc* c = out->saved_crtc;
    if (out->mode_set && c->buffer_id)
      drmModeSetCrtc(out->fd, c->crtc_id, c->buffer_id, c->x, c->y, &out->connector_id, 1,
                     const_cast<drmModeModeInfo*>(&c->mode));
    drmModeFreeCrtc(out->saved_crtc);
  }
  close(out->fd);
  *out = KmsOutput{};
}

bool setKmsMode(KmsOutput* out, uint32_t fb_id, std::string* error) {
  if (drmModeSetCrtc(out->fd, out->crtc_id, fb_id, 0, 0, &out->connector_id, 1, &out->mode) != 0) {
    *error = out->device + ": drmModeSetCrtc " + out->mode.name + " on CRTC " +
             std::to_string(out->crtc_id) + " failed (" + errnoText(errno) + ")";
    return false;
  }
  out->mode_set = true;
  return true;
}

bool queueKmsPageFlip(const KmsOutput& out, uint32_t fb_id, KmsFlipEvent* pending,
                      std::string* error) {
  *pending = KmsFlipEvent{};
  if (drmModePageFlip(out.fd, out.crtc_id, fb_id, DRM_MODE_PAGE_FLIP_EVENT, pending) != 0) {
    *error = out.device + ": drmModePageFlip failed (" + errnoText(errno) + ")";
    return false;
  }
  return true;
}

bool waitKmsPageFlip(const KmsOutput& out, int timeout_ms, KmsFlipEvent* pending,
                     std::string* error) {
  drmEventContext context{};
  context.version = 2;
  context.page_flip_handler = onPageFlip;
  while (!pending->received) {
    pollfd pfd{out.fd, POLLIN, 0};
    const int ready = poll(&pfd, 1, timeout_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) {
      *error = out.device + ": no page-flip event within " + std::to_string(timeout_ms) + " ms";
      return false;
    }
    // Calls onPageFlip with the user data given to drmModePageFlip, i.e. `pending`.
    if (drmHandleEvent(out.fd, &context) != 0) {
      *error = out.device + ": drmHandleEvent failed (" + errnoText(errno) + ")";
      return false;
    }
  }
  return true;
}

bool addKmsFramebuffer(const KmsOutput& out, uint32_t width, uint32_t height, uint32_t format,
                       uint32_t handle, uint32_t pitch, uint32_t* fb_id, std::string* error) {
  const uint32_t handles[4] = {handle, 0, 0, 0};
  const uint32_t pitches[4] = {pitch, 0, 0, 0};
  const uint32_t offsets[4] = {0, 0, 0, 0};
  if (drmModeAddFB2(out.fd, width, height, format, handles, pitches, offsets, fb_id, 0) != 0) {
    *error = out.device + ": drmModeAddFB2 " + std::to_string(width) + "x" +
             std::to_string(height) + " failed (" + errnoText(errno) + ")";
    return false;
  }
  return true;
}

std::optional<double> kmsModeRefreshHz(const drmModeModeInfo& mode, std::string* why_unknown) {
  double pixels = double(mode.htotal) * double(mode.vtotal);
  if (mode.flags & DRM_MODE_FLAG_INTERLACE) pixels /= 2.0;
  if (mode.flags & DRM_MODE_FLAG_DBLSCAN) pixels *= 2.0;
  if (mode.vscan > 1) pixels *= mode.vscan;
  if (pixels > 0.0 && mode.clock > 0) return double(mode.clock) * 1000.0 / pixels;
  if (mode.vrefresh > 0) return double(mode.vrefresh);
  if (why_unknown) *why_unknown = "the mode reports no timing (no pixel clock, totals or vrefresh)";
  return std::nullopt;
}

}  // namespace cb
