// Full-resolution frames while the view moves, at a fraction of a full cast's cost: temporal
// reprojection (Schneider, "The real-time volumetric cloudscapes of Horizon Zero Dawn",
// SIGGRAPH 2015; Hillaire, "Physically based sky, atmosphere and cloud rendering in Frostbite",
// 2016). Each frame ray casts one pixel in f×f of the full frame — a fixed interleaved pattern,
// phase by phase (reprojectionPhase) — as a 1/f-size image jittered onto those pixels
// (RenderOptions::jitter), with each ray's transmittance-weighted depth (write_depth), and
// reprojects the rest from the previous full frame through the camera's motion
// (shaders/reproject.comp.glsl, one invocation per cast quad: history rejected on disocclusion,
// off-screen, in a changed region and at a cloud's soft edge against the sky, clamped to the
// fresh pixels' range while moving). While the camera moves the cast steps as the
// half-resolution moving frame does.
//
//   TemporalReprojection tr;
//   tr.init(&error);
//   renderer.sync(volume, light);
//   tr.noteChanges(region) / tr.invalidate();   // volume region changed / light or style changed
//   tr.render(renderer, camera, w, h, fbo, options);  // every frame while moving
//
// At rest the same camera's frames converge: f² of them after the frame that moved onto it,
// every pixel is its own cast at the full frame's step, equal to a full cast bit for bit
// (temporal_reprojection_test).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "app/render/gl/gl.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"

namespace cb {

struct ReprojectionStats {
  int factor = 0;             // f: one pixel in f×f cast
  glm::ivec2 phase{0};        // which pixel of each f×f block was cast
  bool history_used = false;  // the previous frame was reprojected
  double frame_ms = 0.0;      // with RenderOptions::finish: wall time including glFinish
  // With RenderOptions::finish, the parts of frame_ms, each to a glFinish: the 1/f cast, the
  // reprojection pass over the full frame, the copy into the target.
  double cast_ms = 0.0, reproject_ms = 0.0, copy_ms = 0.0;
  long long pixels_cast = 0;  // of the cast image (its stencil's pixels)
};

// The cast pixel of each f×f block on frame n (f = 2 or 4): an ordered-dither (Bayer) sequence,
// so consecutive frames cast pixels far apart and f² frames cast every pixel once.
glm::ivec2 reprojectionPhase(int factor, long frame);

// The painter's f for a width×height frame: 4 (one pixel in 16 cast, as Nubis) from 1920×1080
// up, 2 below. At 1920×1080 f = 2 cast a quarter of the pixels at the resting step (1 voxel):
// 2× the samples of the half-resolution orbit (step 2), measured 353 against 180 ms of process
// CPU a frame at the painter's starting view (`bench scale`, loaded machine).
int reprojectionFactor(int width, int height);

class TemporalReprojection {
 public:
  TemporalReprojection() = default;
  ~TemporalReprojection();
  TemporalReprojection(const TemporalReprojection&) = delete;
  TemporalReprojection& operator=(const TemporalReprojection&) = delete;

  bool init(std::string* error);
  // Whether a width×height frame in `style` can be reprojected with one pixel in f×f cast: f
  // divides both sides, and the style has no screen-space pass (ink and sketch filter their
  // whole cast image).
  static bool supports(int width, int height, int factor, RenderStyle style);
  // One frame into target_fbo (width×height): cast one pixel in f×f with `options` (scale,
  // region and jitter are the reprojection's; skip_empty_space must be on), reproject the rest.
  void render(VolumeRenderer& renderer, const Camera& camera, int width, int height,
              GLuint target_fbo, const RenderOptions& options, int factor);
  // The pixels (x, y, width, height; bottom-left origin) a sync changed: their history is not
  // reprojected next frame (changed_region.h's rectangle; the whole frame: invalidate).
  void noteChanges(glm::ivec4 rect);
  // Forgets the history (the light, the style or the volume changed everywhere).
  void invalidate() { history_valid_ = false; }
  ReprojectionStats lastStats() const { return stats_; }
  // The frame just rendered (RGBA8, width×height).
  GLuint frameTexture() const { return frames_[current_].colour; }

 private:
  struct Frame {
    GLuint fbo = 0, colour = 0, depth = 0;  // the frame's colour (fbo: for the copy) and depths
  };
  void ensureTargets(int width, int height, int factor);
  void releaseTargets();
  // The moving case's uniforms: the rays through the screen and the previous camera.
  void setMotionUniforms(GLuint program, const Camera& camera, const glm::mat4& view_proj);

  // shaders/reproject.comp.glsl once per case (CB_REPROJECT_MODE): no history, at rest, moving.
  enum Mode { kFresh = 0, kAtRest = 1, kMoving = 2, kModes = 3 };
  GLuint programs_[kModes] = {0, 0, 0};
  Frame frames_[2];  // the previous full frame and the one being made (ping-pong)
  int current_ = 0;
  RenderTarget cast_;  // the 1/f-size cast image
  int width_ = 0, height_ = 0, factor_ = 0;
  long frame_ = 0;
  bool history_valid_ = false;
  glm::mat4 prev_view_proj_{1.0f};
  glm::vec3 prev_eye_{0.0f};
  glm::ivec4 reject_{0};
  ReprojectionStats stats_;
};

}  // namespace cb
