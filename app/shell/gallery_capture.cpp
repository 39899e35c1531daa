#include "app/shell/gallery_capture.h"

#include <algorithm>
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
                   int height, GallerySave* save, std::string* error) {
  if (!store.allocate(&save->number, &save->dir, error)) return false;
  if (!exportCloudFiles(renderer, volume, camera, light, render, width, height, save->dir,
                        &save->written, &save->note, error))
    return false;
  std::string cleanup_error;
  save->cleanup =
      store.enforce(save->number, std::filesystem::file_time_type::clock::now(), &cleanup_error);
  if (!cleanup_error.empty()) {
    *error = "gallery cleanup: " + cleanup_error;
    return false;
  }
  return true;
}

}  // namespace cb
