// Saving a visitor's finished cloud into the kiosk's gallery: a new pseudonymous
// entry (app/kiosk/gallery_store.h) holding the study exporters' files — the volume as
// `cloud.vdb` + `cloud.cbvol` (app/study/volume_export.h) and its render from the visitor's last
// view as `render.exr` + `render.png` (app/study/render_export.h) — plus `thumbnail.png`
// (320 px wide), written into a temporary folder renamed into place (no half-written entry).
// The oldest entries are deleted first to keep the floor of free space (gallery.min_free_mb); when
// even then there is no room, nothing is written and the error says so. Then the quota,
// retention and floor are enforced. Uses the kiosk's renderer and GL
// context (the caller binds its framebuffer again).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "app/kiosk/gallery_store.h"
#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"
#include "app/volume/volume.h"

namespace cb {

struct GallerySave {
  long number = 0;
  std::string dir;
  std::vector<std::string> written;
  std::string note;  // e.g. why the .vdb was skipped
  GalleryCleanup cleanup;
};

// Render size: width × height (the display's). `now`: the time on the kiosk's clock
// (KioskScreen::fileTimeNow): the entry's files carry it as their modification time, and the
// store's retention (keep_days) is judged at it, so a simulated clock ages entries as it runs.
// False with *error naming the file or stage.
bool saveToGallery(GalleryStore& store, VolumeRenderer& renderer, const Volume& volume,
                   const Camera& camera, const Light& light, const RenderOptions& render, int width,
                   int height, std::filesystem::file_time_type now, GallerySave* save,
                   std::string* error);

// The same files without a gallery entry (the operator's "export the current cloud").
bool exportCloudFiles(VolumeRenderer& renderer, const Volume& volume, const Camera& camera,
                      const Light& light, const RenderOptions& render, int width, int height,
                      const std::string& dir, std::vector<std::string>* written, std::string* note,
                      std::string* error);

}  // namespace cb
