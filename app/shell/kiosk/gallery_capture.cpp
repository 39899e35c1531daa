#include "app/shell/kiosk/gallery_capture.h"

#include <algorithm>
#include <cstdio>
#include <exception>

#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/study/render_export.h"
#include "app/study/volume_export.h"

namespace cb {
namespace {

bool renderInto(VolumeRenderer& renderer, const Camera& camera, const RenderOptions& render,
                RenderTarget* target, int width, int height, RenderTarget::Format format,
                std::string* error) {
  if (!target->create(width, height, format, error)) return false;
  RenderOptions options = render;
  options.scale = 1.0f;
  options.moving = false;
  options.collect_stats = false;
  options.finish = true;
  renderer.render(camera, width, height, target->fbo(), options);
  return true;
}

std::string megabytes(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", double(bytes) / 1048576.0);
  return text;
}

}  // namespace

bool exportCloudFiles(VolumeRenderer& renderer, const Volume& volume, const Camera& camera,
                      const Light& light, const RenderOptions& render, int width, int height,
                      const std::string& dir, std::vector<std::string>* written, std::string* note,
                      std::string* error) {
  try {
    const VolumeExport exported = exportVolume(volume, dir, "cloud");
    written->insert(written->end(), exported.written.begin(), exported.written.end());
    *note = exported.note;
    renderer.sync(volume, light);
    RenderTarget frame, thumb;
    if (!renderInto(renderer, camera, render, &frame, width, height, RenderTarget::Format::kRgba32F,
                    error))
      return false;
    for (const std::string& path : exportRender(frame.readRgbaF(), dir, "render"))
      written->push_back(path);
    const int thumb_w = 320, thumb_h = std::max(1, 320 * height / std::max(1, width));
    if (!renderInto(renderer, camera, render, &thumb, thumb_w, thumb_h,
                    RenderTarget::Format::kRgba8, error))
      return false;
    writePng(dir + "/thumbnail.png", thumb.readRgba8());
    written->push_back(dir + "/thumbnail.png");
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  return true;
}

bool saveToGallery(GalleryStore& store, VolumeRenderer& renderer, const Volume& volume,
                   const Camera& camera, const Light& light, const RenderOptions& render, int width,
                   int height, std::filesystem::file_time_type now, GallerySave* save,
                   std::string* error) {
  // Room first: the oldest entries go until the floor of free space plus one entry (as large as
  // the newest) is there; without it nothing is written (the floor is the journals' and logs').
  // The entry's size is taken before the room is made (makeRoom may delete the entries it is
  // measured from).
  std::string room_error;
  const uint64_t entry_bytes = store.typicalEntryBytes();
  const GalleryRoom room = store.makeRoom(entry_bytes, -1, &room_error);
  save->cleanup.removed_for_space = room.removed;
  if (!room.enough && room.free_bytes) {
    *error = store.dir() + ": disk full: " + megabytes(*room.free_bytes) + " free, " +
             megabytes(store.minFreeBytes()) + " kept free (gallery.min_free_mb)" +
             (entry_bytes ? " + " + megabytes(entry_bytes) + " for the entry" : "");
    return false;
  }
  GalleryWrite write;
  if (!store.begin(&write, error)) return false;
  std::vector<std::string> written;
  if (!exportCloudFiles(renderer, volume, camera, light, render, width, height, write.temp_dir,
                        &written, &save->note, error)) {
    store.abandon(write);
    return false;
  }
  if (!store.commit(write, error)) return false;
  save->number = write.number;
  save->dir = write.final_dir;
  std::error_code ec;
  for (const std::string& path : written) {
    save->written.push_back(write.final_dir + path.substr(write.temp_dir.size()));
    std::filesystem::last_write_time(save->written.back(), now, ec);  // the kiosk clock's time
  }
  std::filesystem::last_write_time(write.final_dir, now, ec);
  std::string cleanup_error;
  const GalleryCleanup cleanup = store.enforce(save->number, now, &cleanup_error);
  save->cleanup.removed_for_age = cleanup.removed_for_age;
  save->cleanup.removed_for_quota = cleanup.removed_for_quota;
  save->cleanup.removed_for_space.insert(save->cleanup.removed_for_space.end(),
                                         cleanup.removed_for_space.begin(),
                                         cleanup.removed_for_space.end());
  save->cleanup.bytes_after = cleanup.bytes_after;
  if (!cleanup_error.empty()) {
    *error = "gallery cleanup: " + cleanup_error;
    return false;
  }
  return true;
}

}  // namespace cb
