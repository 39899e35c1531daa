#include "app/render/temporal_reprojection.h"

#include <chrono>
#include <cstdio>

#include <glm/gtc/type_ptr.hpp>

#include "app/render/shader_program.h"

namespace cb {
namespace {

// A cast pixel's history is kept while its depth and the reprojected point's distance from the
// previous eye differ by at most this fraction: a cloud's weighted depth moves smoothly with the
// view, a disocclusion (another cloud part, the background) jumps by far more.
constexpr float kDepthTolerance = 0.1f;

}  // namespace

int reprojectionFactor(int width, int height) {
  return double(width) * double(height) >= 1920.0 * 1080.0 ? 4 : 2;
}

glm::ivec2 reprojectionPhase(int factor, long frame) {
  // Bayer order of a 2×2 block: (0,0), (1,1), (1,0), (0,1); the 4×4 order nests it.
  static constexpr int kBayer2[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  if (factor <= 1) return glm::ivec2(0);
  const long n = frame % long(factor * factor);
  if (factor == 2) return {kBayer2[n][0], kBayer2[n][1]};
  // f = 4: the coarse 2×2 step moves every frame, the fine one every 4 frames.
  const int* coarse = kBayer2[n % 4];
  const int* fine = kBayer2[(n / 4) % 4];
  return {coarse[0] * 2 + fine[0], coarse[1] * 2 + fine[1]};
}

TemporalReprojection::~TemporalReprojection() {
  releaseTargets();
  for (GLuint program : programs_)
    if (program) glDeleteProgram(program);
}

bool TemporalReprojection::init(std::string* error) {
  for (int mode = 0; mode < kModes; ++mode) {
    programs_[mode] = linkComputeProgram(
        {"reproject.comp.glsl"}, error, "#define CB_REPROJECT_MODE " + std::to_string(mode) + "\n");
    if (!programs_[mode]) return false;
  }
  return true;
}

bool TemporalReprojection::supports(int width, int height, int factor, RenderStyle style) {
  return (factor == 2 || factor == 4) && width % factor == 0 && height % factor == 0 &&
         renderStyleRow(style).reprojects;
}

void TemporalReprojection::releaseTargets() {
  for (Frame& f : frames_) {
    if (f.fbo) glDeleteFramebuffers(1, &f.fbo);
    if (f.colour) glDeleteTextures(1, &f.colour);
    if (f.depth) glDeleteTextures(1, &f.depth);
    f = Frame{};
  }
  cast_.release();
  width_ = height_ = factor_ = 0;
  history_valid_ = false;
}

void TemporalReprojection::ensureTargets(int width, int height, int factor) {
  if (width == width_ && height == height_ && factor == factor_) return;
  releaseTargets();
  for (Frame& f : frames_) {
    // The shown colour (copied into the target) and each pixel's depth: the next frame's
    // history (shaders/reproject.comp.glsl), read texel for texel.
    glCreateTextures(GL_TEXTURE_2D, 1, &f.colour);
    glTextureStorage2D(f.colour, 1, GL_RGBA8, width, height);
    glCreateTextures(GL_TEXTURE_2D, 1, &f.depth);
    glTextureStorage2D(f.depth, 1, GL_R32F, width, height);
    for (GLuint t : {f.colour, f.depth}) {
      glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glCreateFramebuffers(1, &f.fbo);
    glNamedFramebufferTexture(f.fbo, GL_COLOR_ATTACHMENT0, f.colour, 0);  // the copy's source
  }
  std::string error;
  if (!cast_.create(width / factor, height / factor, RenderTarget::Format::kRgba8, &error))
    std::fprintf(stderr, "cloudbrush: reprojection: %s\n", error.c_str());
  width_ = width;
  height_ = height;
  factor_ = factor;
  history_valid_ = false;
}

void TemporalReprojection::noteChanges(glm::ivec4 rect) {
  if (rect.z <= 0 || rect.w <= 0) return;
  if (reject_.z <= 0 || reject_.w <= 0) {
    reject_ = rect;
    return;
  }
  const glm::ivec2 lo = glm::min(glm::ivec2(reject_), glm::ivec2(rect));
  const glm::ivec2 hi = glm::max(glm::ivec2(reject_) + glm::ivec2(reject_.z, reject_.w),
                                 glm::ivec2(rect) + glm::ivec2(rect.z, rect.w));
  reject_ = glm::ivec4(lo, hi - lo);
}

void TemporalReprojection::setMotionUniforms(GLuint program, const Camera& camera,
                                             const glm::mat4& view_proj) {
  auto loc = [&](const char* name) { return glGetUniformLocation(program, name); };
  // Directions through the screen's corners on the far plane, minus the eye: linear in the
  // screen position, so the shader interpolates them.
  const glm::mat4 inv = glm::inverse(view_proj);
  const auto corner = [&](float x, float y) {
    const glm::vec4 h = inv * glm::vec4(x, y, 1.0f, 1.0f);
    return glm::vec3(h) / h.w - camera.eye;
  };
  const glm::vec3 c00 = corner(-1, -1), c10 = corner(1, -1), c01 = corner(-1, 1);
  glUniform3fv(loc("u_ray_origin"), 1, glm::value_ptr(c00));
  glUniform3fv(loc("u_ray_dx"), 1, glm::value_ptr(c10 - c00));
  glUniform3fv(loc("u_ray_dy"), 1, glm::value_ptr(c01 - c00));
  glUniformMatrix4fv(loc("u_prev_view_proj"), 1, GL_FALSE, glm::value_ptr(prev_view_proj_));
  glUniform3fv(loc("u_eye"), 1, glm::value_ptr(camera.eye));
  glUniform3fv(loc("u_prev_eye"), 1, glm::value_ptr(prev_eye_));
}

void TemporalReprojection::render(VolumeRenderer& renderer, const Camera& camera, int width,
                                  int height, GLuint target_fbo, const RenderOptions& options,
                                  int factor) {
  const auto t0 = std::chrono::steady_clock::now();
  ensureTargets(width, height, factor);
  stats_ = ReprojectionStats{};
  stats_.factor = factor;
  const glm::ivec2 phase = reprojectionPhase(factor, frame_++);
  stats_.phase = phase;
  // The cast: pixel i of the 1/f image is full pixel f·i + phase, whose centre lies
  // (phase + ½)/f − ½ of a cast pixel from the cast pixel's centre.
  const glm::mat4 view_proj = camera.projection(float(width) / float(height)) * camera.view();
  const bool camera_moved = view_proj != prev_view_proj_ || camera.eye != prev_eye_;
  const bool still = history_valid_ && !camera_moved;
  RenderOptions cast = options;
  // While the camera moves, the ray steps as the half-resolution moving frame's does
  // (rayStepVoxels at scale ½: twice the step, at most kMaxMovingStepVoxels; opacity per step
  // follows the step, so the cloud keeps its density): half the samples. At rest the cast is
  // the full frame's own step, so the frames converge to the full cast.
  if (camera_moved) {
    RenderOptions moving = options;
    moving.scale = 0.5f;
    moving.moving = true;
    cast.step_voxels = rayStepVoxels(moving);
  }
  cast.scale = 1.0f;
  cast.region = glm::ivec4(0);
  cast.jitter = (glm::vec2(phase) + 0.5f) / float(factor) - 0.5f;
  cast.write_depth = true;
  cast.skip_empty_space = true;
  cast.finish = false;
  renderer.render(camera, width / factor, height / factor, cast_.fbo(), cast);
  stats_.pixels_cast = renderer.lastStats().pixels_cast;
  using Ms = std::chrono::duration<double, std::milli>;
  const auto stage = [&](double* ms, std::chrono::steady_clock::time_point* from) {
    if (!options.finish) return;
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    *ms = Ms(now - *from).count();
    *from = now;
  };
  auto stage_start = t0;
  stage(&stats_.cast_ms, &stage_start);

  const int mode = !history_valid_ ? kFresh : still ? kAtRest : kMoving;
  const int previous = current_;
  current_ = 1 - current_;
  const GLuint program = programs_[mode];
  glUseProgram(program);
  auto loc = [&](const char* name) { return glGetUniformLocation(program, name); };
  glUniform1i(loc("u_cast"), 0);
  glUniform1i(loc("u_cast_depth"), 1);
  glUniform1i(loc("u_history"), 2);
  glUniform1i(loc("u_history_depth"), 3);
  glUniform1i(loc("u_factor"), factor);
  glUniform2i(loc("u_phase"), phase.x, phase.y);
  const glm::ivec2 cast_size(width / factor, height / factor);
  glUniform2i(loc("u_cast_last"), cast_size.x - 1, cast_size.y - 1);
  glUniform2i(loc("u_size"), width, height);
  glUniform4i(loc("u_reject"), reject_.x, reject_.y, reject_.z, reject_.w);
  glUniform1f(loc("u_depth_tolerance"), kDepthTolerance);
  glUniform1f(loc("u_no_depth"), kNoDepth);
  if (mode == kMoving) setMotionUniforms(program, camera, view_proj);
  glBindTextureUnit(0, cast_.texture());
  glBindTextureUnit(1, renderer.frameDepthTexture());
  glBindTextureUnit(2, frames_[previous].colour);
  glBindTextureUnit(3, frames_[previous].depth);
  glBindImageTexture(0, frames_[current_].colour, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glBindImageTexture(1, frames_[current_].depth, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  // One invocation per cast quad, from −1 (the pixels before the first cast pixel) to the last.
  constexpr int kGroup = 8;  // shaders/reproject.comp.glsl's local size
  glDispatchCompute(GLuint((cast_size.x + kGroup) / kGroup),
                    GLuint((cast_size.y + kGroup) / kGroup), 1);
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  stats_.history_used = history_valid_;
  stage(&stats_.reproject_ms, &stage_start);

  glBindFramebuffer(GL_READ_FRAMEBUFFER, frames_[current_].fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_fbo);
  glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);

  prev_view_proj_ = view_proj;
  prev_eye_ = camera.eye;
  history_valid_ = true;
  reject_ = glm::ivec4(0);
  if (options.finish) {
    stage(&stats_.copy_ms, &stage_start);
    stats_.frame_ms = Ms(std::chrono::steady_clock::now() - t0).count();
  }
}

}  // namespace cb
