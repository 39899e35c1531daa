// The painter's frames while the view moves (PaintScreen::renderMoving): the orbit, a drag
// turning the view, a morph or the wind at full resolution by temporal reprojection
// (app/render/temporal_reprojection.h) where it applies and the painter's MovingPathChooser
// (moving_frames.h) picks it, the reduced scale where not. The frame at rest is a full cast
// either way.
#include <string>

#include "app/render/changed_region.h"
#include "app/shell/painter/paint_screen.h"

namespace cb {
namespace {

// What a reprojected history's colours depend on besides the camera and the voxels: the volume
// instance, the style, its parameters and the light. A change of any of them starts it anew.
std::string shadingKey(const RenderOptions& o, const Light& light, const Volume& volume) {
  std::string key;
  const auto add = [&key](const void* p, size_t n) { key.append(static_cast<const char*>(p), n); };
  const uint64_t id = volume.instanceId();
  add(&id, sizeof id);
  const int style = int(o.style);
  add(&style, sizeof style);
  const float floats[] = {o.step_voxels,     o.extinction_per_voxel, o.termination_transmittance,
                          o.background.r,    o.background.g,         o.background.b,
                          o.background.a,    light.direction.x,      light.direction.y,
                          light.direction.z, light.colour.r,         light.colour.g,
                          light.colour.b,    light.extinction};
  add(floats, sizeof floats);
  // The styles reprojected (no screen-space pass): thesis, physical, cartoon. Both parameter
  // structs are 4-byte fields without padding.
  add(&o.style_params.physical, sizeof o.style_params.physical);
  add(&o.style_params.cartoon, sizeof o.style_params.cartoon);
  const int sky = int(o.sky.kind);
  add(&sky, sizeof sky);
  return key;
}

}  // namespace

bool PaintScreen::renderMoving(long frame, int width, int height, RenderOptions options,
                               const SyncStats& sync, GLuint target) {
  const int factor = reprojectionFactor(width, height);
  const int kind = animationPlaying() ? 1 : 0;
  const bool applies = moving_path_[kind].reprojectNext() && !reprojection_failed_ &&
                       options.skip_empty_space &&
                       TemporalReprojection::supports(width, height, factor, options.style);
  if (applies && !reprojection_) {
    reprojection_ = std::make_unique<TemporalReprojection>();
    std::string error;
    if (!reprojection_->init(&error)) {
      say("full resolution while moving unavailable (reduced instead): " + error);
      reprojection_.reset();
      reprojection_failed_ = true;
    }
  }
  if (!applies || !reprojection_) {
    renderer_.render(shownCamera(), width, height, target, options);
    moving_frame_drawn_ = MovingFrameDrawn{kind, false};
    return false;
  }
  const Volume& volume = shownVolume();
  const std::string key = shadingKey(options, shownLight(), volume);
  const Camera camera = shownCamera();
  if (key != reprojection_key_ ||
      (frame != reprojection_frame_ + 1 && volume.generation() != reprojection_generation_)) {
    // Other shading, or the volume changed by syncs this history did not see.
    reprojection_->invalidate();
    reprojection_key_ = key;
  } else if (!sync.changes.empty()) {
    // The pixels this frame's sync changed (a morph or the wind): their history is stale.
    const ScreenRegion changed =
        changedScreenRegion(camera, width, height, volume, sync, options.style);
    if (changed.whole_frame)
      reprojection_->invalidate();
    else
      reprojection_->noteChanges(changed.rect);
  }
  // At full resolution and the frame at rest's program (the reprojection casts at the moving
  // step while the camera moves, at this step while it rests): once the view stops, the
  // painter's full cast differs from the last moving frame only by that step, as the
  // half-resolution moving frame does.
  options.scale = 1.0f;
  options.moving = false;
  options.cast_at_volume_detail = false;  // the interleaved casts are a ray per pixel
  options.region = glm::ivec4(0);
  reprojection_->render(renderer_, camera, width, height, target, options, factor);
  reprojection_frame_ = frame;
  reprojection_generation_ = volume.generation();
  moving_frame_drawn_ = MovingFrameDrawn{kind, true};
  return true;
}

}  // namespace cb
