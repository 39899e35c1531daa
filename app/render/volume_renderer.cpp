#include "app/render/volume_renderer.h"

#include "app/render/changed_region.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "app/core/parallel_for.h"
#include "app/render/detail_noise.h"
#include "app/render/physical_light_table.h"
#include "app/render/screen_blur.h"
#include "app/render/shader_program.h"
#include "app/render/sky_function.h"
#include "app/render/volume_detail.h"

namespace cb {
namespace {

constexpr int kHistogramBins = 64;
// Style parameters shared by the iso-surface styles (shade_{ink,cartoon,sketch}.glsl).
constexpr float kIsoDensity = 0.3f;        // the outer surface (seed 003's threshold T)
constexpr float kInnerIsoDensity = 0.75f;  // the inner detail surface (seed 003 §5)
// Physical style: the fBm cube spans this many voxels (its finest octave: ~1 voxel per cell)
// (its erosion κ_e is a style parameter, PhysicalStyleParams::erosion).
constexpr float kDetailNoisePeriodVoxels = 32.0f;
// Occupancy level whose cells are rasterised for the ray bounds (level 0: 4-voxel bricks).
constexpr int kRayBoundsLevel = 0;

// The variant of style_compose.frag.glsl: ink or sketch, with or without the blur (bleed) of
// that radius, the ray-cast image at the output's size or upscaled (full_scale).
std::string composeDefines(bool ink, bool bleed, bool over_sky, bool full_scale, int radius) {
  return std::string("#define CB_COMPOSE_INK ") + (ink ? "1" : "0") +
         "\n#define CB_COMPOSE_SKETCH " + (ink ? "0" : "1") + "\n#define CB_BLEED " +
         (bleed ? "1" : "0") + "\n#define CB_OVER_SKY " + (over_sky ? "1" : "0") +
         "\n#define CB_FULL_SCALE " + (full_scale ? "1" : "0") + "\n" + screenBlurDefine(radius);
}

// The blur's weights (screen_blur.h) as a screen-space pass's uniforms.
void setBlurWeights(GLuint program, const ScreenBlurWeights& weights, int radius) {
  glUniform1fv(glGetUniformLocation(program, "u_weight"), radius + 1, weights.data());
}

// The overlap of rectangles (x, y, width, height); empty (zero size) when they do not meet.
glm::ivec4 intersectRects(glm::ivec4 a, glm::ivec4 b) {
  const glm::ivec2 lo = glm::max(glm::ivec2(a.x, a.y), glm::ivec2(b.x, b.y));
  const glm::ivec2 hi =
      glm::min(glm::ivec2(a.x + a.z, a.y + a.w), glm::ivec2(b.x + b.z, b.y + b.w));
  return glm::ivec4(lo, glm::max(hi - lo, glm::ivec2(0)));
}

// `outer` less `inner` (inside it, or empty) as up to four rectangles: the rows below and above
// inner across outer's width, then the columns left and right of it.
std::vector<glm::ivec4> rectMinus(glm::ivec4 outer, glm::ivec4 inner) {
  if (inner.z <= 0 || inner.w <= 0) return {outer};
  const int x0 = outer.x, x1 = outer.x + outer.z, y0 = outer.y, y1 = outer.y + outer.w;
  const int ix0 = inner.x, ix1 = inner.x + inner.z, iy0 = inner.y, iy1 = inner.y + inner.w;
  std::vector<glm::ivec4> parts = {{x0, y0, x1 - x0, iy0 - y0},
                                   {x0, iy1, x1 - x0, y1 - iy1},
                                   {x0, iy0, ix0 - x0, iy1 - iy0},
                                   {ix1, iy0, x1 - ix1, iy1 - iy0}};
  std::erase_if(parts, [](const glm::ivec4& r) { return r.z <= 0 || r.w <= 0; });
  return parts;
}

// The rectangle (x, y, width, height) from lo to hi, clipped to a cw×ch image.
glm::ivec4 clipRect(glm::ivec2 lo, glm::ivec2 hi, int cw, int ch) {
  lo = glm::max(lo, glm::ivec2(0));
  hi = glm::min(hi, glm::ivec2(cw, ch));
  return glm::ivec4(lo, glm::max(hi - lo, glm::ivec2(0)));
}

// Clip space moved so that pixel (i, j) of a w×h image is cast through (i + ½ + j.x, j + ½ + j.y)
// (RenderOptions::jitter): NDC moves by −2·jitter/size, proportionally to w_clip.
glm::mat4 jitterMatrix(glm::vec2 jitter, int w, int h) {
  glm::mat4 m(1.0f);
  m[3][0] = -2.0f * jitter.x / float(w);
  m[3][1] = -2.0f * jitter.y / float(h);
  return m;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Merges the changes of each slot into one (the bounding boxes of its blocks' boxes).
void coalescePerSlot(std::vector<BrickPool::SlotChange>* changes) {
  auto order = [](const BrickPool::SlotChange& a, const BrickPool::SlotChange& b) {
    return std::tie(a.brick.z, a.brick.y, a.brick.x) < std::tie(b.brick.z, b.brick.y, b.brick.x);
  };
  std::stable_sort(changes->begin(), changes->end(), order);
  std::vector<BrickPool::SlotChange> merged;
  for (const BrickPool::SlotChange& c : *changes) {
    if (!merged.empty() && merged.back().brick == c.brick) {
      merged.back().bytes = merged.back().bytes.unite(c.bytes);
      merged.back().weighted = merged.back().weighted.unite(c.weighted);
    } else {
      merged.push_back(c);
    }
  }
  *changes = std::move(merged);
}

}  // namespace

void VolumeRenderer::deleteTargets(FrameTargets* t) {
  if (t->fbo) glDeleteFramebuffers(1, &t->fbo);
  if (t->bounds) glDeleteTextures(1, &t->bounds);
  if (t->frame) glDeleteTextures(1, &t->frame);
  if (t->stencil) glDeleteRenderbuffers(1, &t->stencil);
  if (t->depth) glDeleteTextures(1, &t->depth);
  *t = FrameTargets{};
}

std::string RenderStats::summary() const {
  char buf[256];
  std::string s;
  std::snprintf(buf, sizeof buf, "ray casting %dx%d", width, height);
  s += buf;
  if (frame_ms > 0.0) {
    std::snprintf(buf, sizeof buf, ", %.1f ms", frame_ms);
    s += buf;
  }
  s += "\n";
  if (!has_samples) return s;
  std::snprintf(buf, sizeof buf,
                "samples: total %llu, per pixel mean %.2f, max %u\n"
                "histogram (samples per pixel: pixels):\n",
                (unsigned long long)samples_total, samples_mean, samples_max);
  s += buf;
  for (size_t i = 0; i < histogram.size(); ++i) {
    if (!histogram[i]) continue;
    int lo = int(i) * histogram_bin_width;
    if (i + 1 == histogram.size())
      std::snprintf(buf, sizeof buf, "  %4d+     : %u\n", lo, histogram[i]);
    else
      std::snprintf(buf, sizeof buf, "  %4d-%-4d : %u\n", lo, lo + histogram_bin_width - 1,
                    histogram[i]);
    s += buf;
  }
  return s;
}

VolumeRenderer::~VolumeRenderer() {
  for (auto& [key, p] : programs_) glDeleteProgram(p);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (occupancy_texture_) glDeleteTextures(1, &occupancy_texture_);
  if (stats_buffer_) glDeleteBuffers(1, &stats_buffer_);
  if (bounds_program_) glDeleteProgram(bounds_program_);
  if (bounds_vao_) glDeleteVertexArrays(1, &bounds_vao_);
  if (bounds_vbo_) glDeleteBuffers(1, &bounds_vbo_);
  if (mask_vao_) glDeleteVertexArrays(1, &mask_vao_);
  if (mask_vbo_) glDeleteBuffers(1, &mask_vbo_);
  FrameTargets current{
      bounds_fbo_, bounds_texture_, frame_texture_, stencil_buffer_, depth_texture_, 0, 0};
  deleteTargets(&current);
  deleteTargets(&spare_targets_);
  if (detail_noise_texture_) glDeleteTextures(1, &detail_noise_texture_);
  if (light_table_texture_) glDeleteTextures(1, &light_table_texture_);
}

bool VolumeRenderer::init(std::string* error) {
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &stats_buffer_);
  glNamedBufferStorage(stats_buffer_, sizeof(uint32_t) * (3 + kHistogramBins), nullptr,
                       GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
  if (!ensureProgram(RenderOptions{})) {
    *error = error_;
    return false;
  }
  bounds_program_ = linkProgram({"ray_bounds.vert.glsl"}, {"ray_bounds.frag.glsl"}, error);
  if (!bounds_program_) return false;
  // The ray-bounds faces and the changed-slot boxes: voxel-space vec3 triangles.
  for (auto [vao, vbo] :
       {std::pair{&bounds_vao_, &bounds_vbo_}, std::pair{&mask_vao_, &mask_vbo_}}) {
    glCreateBuffers(1, vbo);
    glCreateVertexArrays(1, vao);
    glVertexArrayVertexBuffer(*vao, 0, *vbo, 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(*vao, 0);
    glVertexArrayAttribFormat(*vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(*vao, 0, 0);
  }
  return true;
}

bool VolumeRenderer::ensureProgram(const RenderOptions& options) {
  const bool surface = drawsIsoSurface(options.style);
  const std::string defines =
      std::string("#define CB_SKIP ") + (options.skip_empty_space ? "1" : "0") +
      "\n#define CB_BRICK_STEPPING " + (options.brick_stepping ? "1" : "0") +
      "\n#define CB_STATS " + (options.collect_stats ? "1" : "0") + "\n#define CB_SURFACE " +
      (surface ? "1" : "0") + "\n#define CB_MOVING " + (options.moving ? "1" : "0") +
      "\n#define CB_CHUNK " + std::to_string(chunkSamples(rayStepVoxels(options))) +
      "\n#define CB_DEPTH " + (options.write_depth && options.skip_empty_space ? "1" : "0") +
      "\n#define CB_LIGHT_PREVIEW " + (light_is_preview_ ? "1" : "0") + "\n";
  const std::string stage = shadingStageFile(options.style);
  const std::string key = stage + "\n" + defines;
  auto it = programs_.find(key);
  if (it != programs_.end()) {
    program_ = it->second;
    return true;
  }
  std::vector<std::string> fragment_files{"volume_pool.glsl"};
  if (surface) fragment_files.push_back("surface_sample.glsl");
  fragment_files.push_back(stage);
  fragment_files.push_back("raycast.frag.glsl");
  GLuint p = linkProgram({"fullscreen.vert.glsl"}, fragment_files, &error_, defines);
  if (!p) return false;
  programs_[key] = p;
  program_ = p;
  return true;
}

bool VolumeRenderer::prepare(const RenderOptions& options, std::string* error) {
  bool ok = ensureProgram(options);
  if (ok && hasScreenSpacePass(options.style)) {
    const bool ink = renderStyleRow(options.style).screen_pass == ScreenPass::kInkWash;
    const bool bleed = !options.moving;
    const bool over_sky = SkyPass::shows(options.sky, options.style, options.style_params);
    const bool full_scale = options.scale >= 1.0f;
    const int radius = screenSpaceReach(options.style, options.style_params);
    // The still frame draws the pixels away from the cloud with the unblurred variant.
    ok = fullscreenProgram("style_compose.frag.glsl",
                           composeDefines(ink, bleed, over_sky, full_scale, radius)) != 0 &&
         fullscreenProgram("style_compose.frag.glsl",
                           composeDefines(ink, false, over_sky, full_scale, radius)) != 0 &&
         (!bleed || fullscreenProgram("ink_bleed.frag.glsl", screenBlurDefine(radius)) != 0);
  }
  if (ok && !sky_.prepare(options.sky, options.style, &error_)) ok = false;
  if (!ok) *error = error_;
  return ok;
}

GLuint VolumeRenderer::fullscreenProgram(const std::string& fragment, const std::string& defines) {
  const std::string key = fragment + "\n" + defines;
  auto it = programs_.find(key);
  if (it != programs_.end()) return it->second;
  GLuint p = linkProgram({"fullscreen.vert.glsl"}, {fragment}, &error_, defines);
  if (p) programs_[key] = p;
  return p;
}

void VolumeRenderer::ensurePhysicalTextures() {
  if (detail_noise_texture_) return;
  const std::array<glm::vec4, 256> table = physicalLightTable();
  glCreateTextures(GL_TEXTURE_1D, 1, &light_table_texture_);
  glTextureStorage1D(light_table_texture_, 1, GL_RGBA32F, GLsizei(table.size()));
  glTextureSubImage1D(light_table_texture_, 0, 0, GLsizei(table.size()), GL_RGBA, GL_FLOAT,
                      table.data());
  const DetailNoise noise = makeDetailNoise();
  glCreateTextures(GL_TEXTURE_3D, 1, &detail_noise_texture_);
  glTextureStorage3D(detail_noise_texture_, 1, GL_R8, noise.size, noise.size, noise.size);
  glTextureParameteri(detail_noise_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(detail_noise_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTextureParameteri(detail_noise_texture_, wrap, GL_REPEAT);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(detail_noise_texture_, 0, 0, 0, 0, noise.size, noise.size, noise.size, GL_RED,
                      GL_UNSIGNED_BYTE, noise.texels.data());
}

bool VolumeRenderer::drawSkyUnder(int w, int h, int width, int height,
                                  const RenderOptions& options) {
  if (!SkyPass::shows(options.sky, options.style, options.style_params)) return false;
  std::string err;
  if (!sky_.draw(frame_camera_, w, h, width, height, options.sky, options.style, synced_light_,
                 &err)) {
    std::fprintf(stderr, "cloudbrush: render: sky: %s\n", err.c_str());
    return false;
  }
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // C = C_src + (1 − α_src)·C_sky
  return true;
}

void VolumeRenderer::ensureOccupancyTexture() {
  const glm::ivec3 d0 = occupancy_.level_dims.empty() ? glm::ivec3(0) : occupancy_.level_dims[0];
  if (d0 == glm::ivec3(0)) return;
  if (!occupancy_texture_ || occupancy_texture_dims_ != d0 ||
      occupancy_texture_levels_ != occupancy_.levelCount()) {
    if (occupancy_texture_) glDeleteTextures(1, &occupancy_texture_);
    glCreateTextures(GL_TEXTURE_3D, 1, &occupancy_texture_);
    glTextureStorage3D(occupancy_texture_, occupancy_.levelCount(), GL_R8UI, d0.x, d0.y, d0.z);
    glTextureParameteri(occupancy_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(occupancy_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    occupancy_texture_dims_ = d0;
    occupancy_texture_levels_ = occupancy_.levelCount();
    occupancy_texture_stale_ = {glm::ivec3(0), d0};
  }
  uploadOccupancy(occupancy_texture_stale_);
  occupancy_texture_stale_ = {};
  for (GLenum p : {GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
                   GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES})
    glPixelStorei(p, 0);
}

void VolumeRenderer::uploadOccupancy(const VoxelBox& cells) {
  if (cells.empty()) return;
  VoxelBox region = cells;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int m = 0; m < occupancy_.levelCount(); ++m) {
    if (m > 0) region = {region.lo / 2, glm::min((region.hi + 1) / 2, occupancy_.level_dims[m])};
    const glm::ivec3 d = occupancy_.level_dims[size_t(m)];
    glPixelStorei(GL_UNPACK_ROW_LENGTH, d.x);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, d.y);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, region.lo.x);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, region.lo.y);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, region.lo.z);
    glm::ivec3 size = region.hi - region.lo;
    glTextureSubImage3D(occupancy_texture_, m, region.lo.x, region.lo.y, region.lo.z, size.x,
                        size.y, size.z, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                        occupancy_.levels[size_t(m)].data());
  }
}

bool VolumeRenderer::followsGrowth(const Volume& volume) const {
  const Volume::Growth& g = volume.growth();
  if (synced_volume_id_ == 0 || g.from_instance != synced_volume_id_ ||
      g.from_generation != synced_generation_ || g.from_dims != dims_ || light_is_preview_)
    return false;
  // The grown volume places the synced one's voxels where they were in the world (a check of
  // the record against the boxes: the same voxel size, the old box at the offset).
  const glm::vec3 voxel = (world_max_ - world_min_) / glm::vec3(dims_);
  const glm::vec3 at = volume.voxelToWorld(glm::vec3(g.brick_offset * Volume::kBrickSize));
  const glm::vec3 extent = volume.worldMax() - volume.worldMin();
  const float tolerance = 1e-4f * std::max({extent.x, extent.y, extent.z});
  return glm::all(glm::lessThanEqual(glm::abs(volume.voxelSize() - voxel), 1e-6f * voxel)) &&
         glm::all(glm::lessThanEqual(glm::abs(at - world_min_), glm::vec3(tolerance)));
}

void VolumeRenderer::followGrowth(const Volume& volume) {
  const Volume::Growth& g = volume.growth();
  const glm::ivec3 voxel_offset = g.brick_offset * Volume::kBrickSize;
  occupancy_ = shiftOccupancy(occupancy_, volume, voxel_offset);
  shiftLightVolume(light_volume_, dims_, volume, g.brick_offset);
  pool_.followGrowth(volume.brickDims(), g.brick_offset);
  growth_edge_bricks_ = growthEdgeBricks(volume);
  dims_ = volume.dims();
  world_min_ = volume.worldMin();
  world_max_ = volume.worldMax();
  // The frames held were cast in the old box's voxel coordinates: cast anew (the targets stay).
  history_ = FrameHistory{};
  spare_history_ = FrameHistory{};
  synced_volume_id_ = volume.instanceId();
  synced_generation_ = g.generation;
}

// The light brought up to date with the volume and the light: while the light is dragged over
// a volume that stayed the same (or, previewing every change, while an animation changes it), a
// coarse sweep into the preview texture (the light volume keeps the light before, and the pool
// the light volume's; what changed meanwhile is remembered); else the light volume's sweep of
// what changed, and of what a preview left unswept. Returns the box whose light changed in the
// light volume.
VoxelBox VolumeRenderer::syncLight(const Volume& volume, const Light& light, bool fresh,
                                   const VoxelBox& dirty, LightByteChanges* light_bytes) {
  if (fresh) {
    light_volume_ = LightVolume{};
    light_preview_.release();
    light_unswept_ = {};
  }
  const bool moved = !light_volume_.matches(volume, light);
  const bool preview = light_preview_divisor_ > 1 && !fresh &&
                       (light_preview_of_ == LightPreviewOf::kEveryChange
                            ? moved || light_is_preview_ || !dirty.empty()
                            : moved && dirty.empty());
  if (preview) {
    const bool same = light_is_preview_ && dirty.empty() &&
                      preview_light_.direction == light.direction &&
                      preview_light_.extinction == light.extinction;
    if (!same) light_preview_.upload(reduced_light_.sweep(volume, light, light_preview_divisor_));
    light_unswept_ = light_unswept_.unite(dirty);
    light_is_preview_ = true;
    preview_light_ = light;
    return {};
  }
  light_is_preview_ = false;
  light_bytes->all = true;
  const VoxelBox swept = dirty.unite(light_unswept_);
  light_unswept_ = {};
  return sweepLightVolume(light_volume_, volume, light, swept, light_bytes);
}

void VolumeRenderer::dropFrameTargets() {
  // The frame targets hold frames of the volume before: given back, so that what the renderer
  // holds follows the sizes this volume is drawn at, not every size drawn before (a kiosk
  // resets to the attract loop after each visit; soak in tests/unit/kiosk/kiosk_soak.cpp).
  FrameTargets current{
      bounds_fbo_, bounds_texture_, frame_texture_, stencil_buffer_, depth_texture_, 0, 0};
  deleteTargets(&current);
  deleteTargets(&spare_targets_);
  bounds_fbo_ = bounds_texture_ = frame_texture_ = stencil_buffer_ = depth_texture_ = 0;
  bounds_w_ = bounds_h_ = 0;
}

// The ray-bounds faces of the occupied cells, uploaded.
void VolumeRenderer::uploadRayBounds() {
  // One boundary, drawn once without culling: its front faces are where rays enter occupied
  // cells and its back faces where they leave (ray_bounds.frag.glsl tells them apart).
  // llvmpipe's bounds pass is bound by triangle count, so the faces are merged into
  // rectangles (occupiedBoundaryFaces).
  // The rectangles' corners are kept to bound the boundary's projection (boundsRect).
  const int level = std::min(kRayBoundsLevel, occupancy_.levelCount() - 1);
  const std::vector<BoundaryRect> rects = occupiedBoundaryRects(occupancy_, level);
  const float cell = float(occupancy_.cellSize(level));
  const std::vector<glm::vec3> faces = boundaryTriangles(rects, cell);
  bounds_corners_ = boundaryCorners(rects, cell);
  bounds_vertices_ = GLsizei(faces.size());
  bounds_vbo_bytes_ = std::max<size_t>(1, faces.size()) * sizeof(glm::vec3);
  glNamedBufferData(bounds_vbo_, GLsizeiptr(bounds_vbo_bytes_),
                    faces.empty() ? nullptr : faces.data(), GL_STATIC_DRAW);
}

SyncStats VolumeRenderer::sync(const Volume& volume, const Light& light, ChangeDetail detail) {
  SyncStats st;
  // A volume grown around the synced one (Volume::Growth): what the renderer holds is shifted by
  // the growth's brick offset, and only what changed since is brought up to date.
  auto t0 = std::chrono::steady_clock::now();
  st.followed_growth = followsGrowth(volume);
  if (st.followed_growth) followGrowth(volume);
  st.growth_ms = msSince(t0);
  // A different volume (instance ids are unique per construction and assignment, so a new volume
  // at a reused address is recognised) or new dims/placement: upload everything.
  const bool fresh = synced_volume_id_ != volume.instanceId() || volume.dims() != dims_ ||
                     volume.worldMin() != world_min_ || volume.worldMax() != world_max_;
  st.dirty = fresh ? volume.bounds() : volume.dirtySince(synced_generation_);

  t0 = std::chrono::steady_clock::now();
  VoxelBox occupancy_cells;
  if (fresh) {
    occupancy_ = buildOccupancy(volume);
    occupancy_cells = {glm::ivec3(0), occupancy_.level_dims[0]};
  } else if (st.followed_growth) {
    updateOccupancy(occupancy_, volume, st.dirty);
    occupancy_cells = {glm::ivec3(0), occupancy_.level_dims[0]};  // a new texture
  } else {
    // An edit inside cloud that is already occupied leaves the pyramid as it was: then neither
    // the occupancy texture nor the ray-bounds faces (a scan of all cells and a buffer upload of
    // megabytes for the cumulus) need redoing.
    bool changed = false;
    occupancy_cells = updateOccupancy(occupancy_, volume, st.dirty, &changed);
    if (!changed) occupancy_cells = {};
  }
  st.occupancy_ms = msSince(t0);

  t0 = std::chrono::steady_clock::now();
  const bool was_preview = light_is_preview_;
  LightByteChanges light_bytes;  // which bricks' 8-bit light changed (else: the light box)
  st.light_box = syncLight(volume, light, fresh, st.dirty, &light_bytes);
  st.light_ms = msSince(t0);
  st.light_moved =
      !fresh && (synced_light_.direction != light.direction ||
                 synced_light_.extinction != light.extinction || was_preview != light_is_preview_);

  st.uploaded = st.dirty.unite(st.light_box);
  if (fresh) {
    dims_ = volume.dims();
    world_min_ = volume.worldMin();
    world_max_ = volume.worldMax();
  }
  // The pool follows the bricks that changed (or every allocated brick when fresh), and after a
  // growth the bricks along the old edge.
  std::vector<glm::ivec3> changed_bricks =
      fresh ? std::vector<glm::ivec3>{} : volume.changedBricksSince(synced_generation_);
  // The density changed within st.dirty, so the pool re-packs only the slots reading it; the old
  // edge's slots after a growth changed beyond it (they read the grown sky): every slot around
  // a changed brick then.
  const VoxelBox* density_box = &st.dirty;
  if (!fresh && !growth_edge_bricks_.empty()) {
    changed_bricks.insert(changed_bricks.end(), growth_edge_bricks_.begin(),
                          growth_edge_bricks_.end());
    density_box = nullptr;
  }
  growth_edge_bricks_.clear();
  // Texel by texel changes are listed only when the light stayed: after it moved no frame held
  // is reused (its image key names the light), so they are dropped, not compared.
  const BrickPool::UpdateStats pool =
      pool_.update(volume, light_volume_, fresh, changed_bricks, st.light_box, &light_bytes,
                   st.light_moved ? nullptr : &st.changes, density_box, detail);
  for (FrameHistory* history : {&history_, &spare_history_}) {
    if (fresh || st.light_moved) *history = FrameHistory{};
    if (!history->valid) continue;
    history->pending.insert(history->pending.end(), st.changes.begin(), st.changes.end());
    // Too many boxes: one per slot (its blocks' bounding boxes) before giving the mask up.
    if (history->pending.size() > kMaxMaskBoxes) coalescePerSlot(&history->pending);
    if (history->pending.size() > kMaxMaskBoxes) *history = FrameHistory{};
  }
  if (fresh) dropFrameTargets();
  st.slots_uploaded = pool.slots_uploaded;
  st.slots_unchanged = pool.slots_unchanged;
  st.pool_grew = pool.grew;
  st.pack_ms = pool.pack_ms;

  t0 = std::chrono::steady_clock::now();
  // The occupancy texture is read only by brick stepping (off by default): it is brought up to
  // date when a frame steps (ensureOccupancyTexture), not here.
  occupancy_texture_stale_ = occupancy_texture_stale_.unite(occupancy_cells);
  if (!occupancy_cells.empty()) uploadRayBounds();
  for (GLenum p : {GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
                   GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES})
    glPixelStorei(p, 0);
  glFinish();  // the upload is complete when sync returns (so its time is honest)
  st.upload_ms = pool.upload_ms + msSince(t0);

  synced_volume_id_ = volume.instanceId();
  synced_volume_ = &volume;
  synced_generation_ = volume.generation();
  synced_light_ = light;
  return st;
}

RendererGpuMemory VolumeRenderer::gpuMemory() const {
  RendererGpuMemory m;
  m.pool = pool_.poolBytes();
  m.indirection = pool_.indirectionBytes();
  if (occupancy_texture_)
    for (const OccupancyCells& level : occupancy_.levels) m.occupancy += level.size();
  m.ray_bounds = bounds_vbo_bytes_;
  m.light_preview = light_preview_.bytes();
  // RG32F bounds + RGBA8 frame + 24/8 depth-stencil per pixel, for the current and spare size.
  constexpr size_t kTargetBytesPerPixel = 8 + 4 + 4;
  m.frame_targets = (size_t(bounds_w_) * size_t(bounds_h_) +
                     size_t(spare_targets_.w) * size_t(spare_targets_.h)) *
                    kTargetBytesPerPixel;
  if (depth_texture_) m.frame_targets += size_t(bounds_w_) * size_t(bounds_h_) * 4;
  if (spare_targets_.depth)
    m.frame_targets += size_t(spare_targets_.w) * size_t(spare_targets_.h) * 4;
  for (const RenderTarget* t : {&low_res_, &style_image_, &bleed_})
    m.frame_targets += size_t(t->width()) * size_t(t->height()) *
                       (t->format() == RenderTarget::Format::kRgba8 ? 4 : 16);
  if (detail_noise_texture_) {
    GLint size = 0;
    glGetTextureLevelParameteriv(detail_noise_texture_, 0, GL_TEXTURE_WIDTH, &size);
    m.styles = size_t(size) * size_t(size) * size_t(size) + 256 * sizeof(glm::vec4);
  }
  return m;
}

void VolumeRenderer::useFrameTargets(int w, int h) {
  if (bounds_w_ != w || bounds_h_ != h) {
    // The painter alternates two sizes (a pen-up frame at the moving scale, then the full one):
    // the previous size's targets are kept as the spare instead of being reallocated.
    FrameTargets current{bounds_fbo_,    bounds_texture_, frame_texture_, stencil_buffer_,
                         depth_texture_, bounds_w_,       bounds_h_};
    std::swap(current, spare_targets_);
    std::swap(history_, spare_history_);
    depth_texture_ = 0;
    if (current.w == w && current.h == h) {
      bounds_fbo_ = current.fbo;
      bounds_texture_ = current.bounds;
      frame_texture_ = current.frame;
      stencil_buffer_ = current.stencil;
      depth_texture_ = current.depth;
      bounds_w_ = w;
      bounds_h_ = h;
    } else {
      deleteTargets(&current);
      history_ = FrameHistory{};  // new targets hold no frame
      glCreateTextures(GL_TEXTURE_2D, 1, &bounds_texture_);
      glTextureStorage2D(bounds_texture_, 1, GL_RG32F, w, h);
      glTextureParameteri(bounds_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(bounds_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glCreateTextures(GL_TEXTURE_2D, 1, &frame_texture_);
      glTextureStorage2D(frame_texture_, 1, GL_RGBA8, w, h);
      glCreateRenderbuffers(1, &stencil_buffer_);
      glNamedRenderbufferStorage(stencil_buffer_, GL_DEPTH24_STENCIL8, w, h);
      glCreateFramebuffers(1, &bounds_fbo_);
      glNamedFramebufferTexture(bounds_fbo_, GL_COLOR_ATTACHMENT0, frame_texture_, 0);
      glNamedFramebufferTexture(bounds_fbo_, GL_COLOR_ATTACHMENT1, bounds_texture_, 0);
      glNamedFramebufferRenderbuffer(bounds_fbo_, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                     stencil_buffer_);
      bounds_w_ = w;
      bounds_h_ = h;
    }
  }
}

void VolumeRenderer::ensureDepthTarget() {
  if (depth_texture_) return;
  glCreateTextures(GL_TEXTURE_2D, 1, &depth_texture_);
  glTextureStorage2D(depth_texture_, 1, GL_R32F, bounds_w_, bounds_h_);
  glTextureParameteri(depth_texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(depth_texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glNamedFramebufferTexture(bounds_fbo_, GL_COLOR_ATTACHMENT2, depth_texture_, 0);
}

void VolumeRenderer::drawRayBounds(const Camera& camera, const glm::mat4& view_proj, int w, int h) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, bounds_fbo_);
  const GLenum bounds_only = GL_COLOR_ATTACHMENT1;  // fragment output 0 -> the bounds texture
  glDrawBuffers(1, &bounds_only);
  glViewport(0, 0, w, h);
  const float nothing[4] = {1e30f, 1e30f, 0.0f, 0.0f};
  glClearBufferfv(GL_COLOR, 0, nothing);
  glStencilMask(0xFF);
  const GLint zero = 0;
  glClearBufferiv(GL_STENCIL, 0, &zero);
  if (bounds_vertices_ > 0) {
    // Every covered pixel gets stencil 1.
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(bounds_program_);
    glUniformMatrix4fv(glGetUniformLocation(bounds_program_, "u_view_proj"), 1, GL_FALSE,
                       glm::value_ptr(view_proj));
    glUniform3fv(glGetUniformLocation(bounds_program_, "u_world_min"), 1,
                 glm::value_ptr(world_min_));
    glm::vec3 voxel = (world_max_ - world_min_) / glm::vec3(dims_);
    glUniform3fv(glGetUniformLocation(bounds_program_, "u_voxel_size"), 1, glm::value_ptr(voxel));
    glUniform3fv(glGetUniformLocation(bounds_program_, "u_eye"), 1, glm::value_ptr(camera.eye));
    glBindVertexArray(bounds_vao_);
    glDrawArrays(GL_TRIANGLES, 0, bounds_vertices_);  // entries and exits, both faces
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_STENCIL_TEST);
  }
}

int chunkSamples(float step_voxels) {
  return std::clamp(1 + int(float(BrickPool::kApron) / step_voxels), 1, 4);
}

float rayStepVoxels(const RenderOptions& options) {
  const float step = std::max(options.step_voxels, 0.05f);
  const float scale = std::clamp(options.scale, 0.05f, 1.0f);
  if (!options.moving || scale >= 1.0f) return step;
  return std::max(step, std::min(step / scale, kMaxMovingStepVoxels));
}

std::string VolumeRenderer::imageKey(const glm::mat4& view_proj, int w, int h,
                                     const RenderOptions& options,
                                     const glm::vec4& background) const {
  std::string key;
  const auto add = [&key](const void* p, size_t n) { key.append(static_cast<const char*>(p), n); };
  add(&view_proj, sizeof view_proj);
  const int ints[] = {w, h, int(program_), int(options.style)};
  add(ints, sizeof ints);
  const PhysicalStyleParams& ph = options.style_params.physical;
  const CartoonStyleParams& ca = options.style_params.cartoon;
  const float floats[] = {rayStepVoxels(options),
                          options.extinction_per_voxel,
                          options.termination_transmittance,
                          background.r,
                          background.g,
                          background.b,
                          background.a,
                          synced_light_.colour.r,
                          synced_light_.colour.g,
                          synced_light_.colour.b,
                          synced_light_.direction.x,
                          synced_light_.direction.y,
                          synced_light_.direction.z,
                          ph.reflection,
                          ph.scattering,
                          ph.forward_g,
                          ph.back_g,
                          ph.forward_weight,
                          float(ph.octaves),
                          ph.ambient,
                          ph.exposure,
                          ph.erosion,
                          ca.band_thresholds.x,
                          ca.band_thresholds.y,
                          ca.band_thresholds.z,
                          ca.outline_width,
                          options.style_params.sketch.outline_width};
  add(floats, sizeof floats);
  return key;
}

namespace {

// The 8 corners of `box` grown by `reach` voxels, in voxel space.
std::array<glm::vec3, 8> grownCorners(const VoxelBox& box, float reach) {
  const glm::vec3 lo = glm::vec3(box.lo) - reach, hi = glm::vec3(box.hi) + reach;
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[size_t(i)] = {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
  return c;
}

}  // namespace

bool VolumeRenderer::projectedRect(const std::vector<VoxelBox>& boxes, float reach,
                                   const glm::mat4& view_proj, int w, int h,
                                   glm::ivec4* rect) const {
  std::vector<glm::vec3> corners;
  corners.reserve(boxes.size() * 8);
  for (const VoxelBox& box : boxes)
    for (const glm::vec3& c : grownCorners(box, reach)) corners.push_back(c);
  return projectedPointsRect(corners, view_proj, w, h, rect);
}

bool VolumeRenderer::projectedPointsRect(const std::vector<glm::vec3>& points,
                                         const glm::mat4& view_proj, int w, int h,
                                         glm::ivec4* rect) const {
  if (points.empty()) {
    if (rect) *rect = glm::ivec4(0);
    return true;
  }
  const glm::vec3 voxel = (world_max_ - world_min_) / glm::vec3(dims_);
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : points) {
    const glm::vec4 clip = view_proj * glm::vec4(world_min_ + p * voxel, 1.0f);
    if (clip.w <= 1e-4f || clip.z < -clip.w) return false;  // at or behind the near plane
    const glm::vec2 px = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(w, h);
    lo = glm::min(lo, px);
    hi = glm::max(hi, px);
  }
  const glm::ivec2 a = glm::max(glm::ivec2(glm::floor(lo)) - 1, glm::ivec2(0));
  const glm::ivec2 b = glm::min(glm::ivec2(glm::ceil(hi)) + 1, glm::ivec2(w, h));
  if (rect) *rect = glm::ivec4(a, glm::max(b - a, glm::ivec2(0)));
  return true;
}

void VolumeRenderer::drawChangedMask(const std::vector<VoxelBox>& boxes, float reach,
                                     const glm::mat4& view_proj) {
  // Every face of every grown box: a pixel whose centre ray passes through a box is inside its
  // projected outline (no box reaches the near plane: projectedRect checked).
  static constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                       {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  std::vector<glm::vec3> vertices;
  vertices.reserve(boxes.size() * 36);
  for (const VoxelBox& box : boxes) {
    const std::array<glm::vec3, 8> c = grownCorners(box, reach);
    for (const auto& f : kFaces)
      for (int i : {0, 1, 2, 0, 2, 3}) vertices.push_back(c[size_t(f[i])]);
  }
  const size_t bytes = vertices.size() * sizeof(glm::vec3);
  if (bytes > mask_vbo_bytes_) {
    glNamedBufferData(mask_vbo_, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
    mask_vbo_bytes_ = bytes;
  }
  glNamedBufferSubData(mask_vbo_, 0, GLsizeiptr(bytes), vertices.data());
  glUseProgram(bounds_program_);  // its uniforms are this frame's (drawRayBounds set them)
  glUniformMatrix4fv(glGetUniformLocation(bounds_program_, "u_view_proj"), 1, GL_FALSE,
                     glm::value_ptr(view_proj));
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_STENCIL_TEST);
  glStencilMask(2);
  glStencilFunc(GL_ALWAYS, 2, 2);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glBindVertexArray(mask_vao_);
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(vertices.size()));
  glStencilMask(0xFF);
  glDisable(GL_STENCIL_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

// A frame's plan: the sizes, the rectangles and what the frame colour can be trusted with,
// decided before any pixel is drawn (render's first half); its passes read it.
struct VolumeRenderer::FramePlan {
  int width = 0, height = 0;  // the target
  int w = 0, h = 0;           // the ray-cast image (options.scale of the target)
  bool reduced = false;       // w×h is smaller than the target (upscaled by the blit)
  // A screen-space style casts into an image of its own (ink amounts, not colours) and its pass
  // draws the target; the ray cast then sees a transparent black background.
  bool screen_space = false;
  // With a sky the ray cast writes the cloud alone (premultiplied, α = 1 − T), blended over it.
  bool sky_under = false;
  bool skip = false;     // options.skip_empty_space
  bool partial = false;  // options.region (partial re-rendering)
  bool masked = false;   // re-cast only the changed pixels (a stencil mask)
  glm::vec4 background{0.0f};
  GLuint draw_fbo = 0;  // without skipping: where the ray cast writes
  // The ray bounds and the projected rectangles move with the jitter; the rays are cast through
  // the unmoved camera at the pixel centres plus the jitter (u_jitter), which for a power-of-two
  // fraction of a frame is exactly the full frame's pixel position scaled by a power of two, so
  // such a pixel's ray is the full frame's bit for bit.
  glm::mat4 plain_view_proj{1.0f}, view_proj{1.0f};
  // Rectangles as (x, y, width, height). out_rect: the target pixels rewritten. image_rect: the
  // ray-cast image's pixels they read — the same at full size; at a reduced one, the rectangle
  // scaled down and grown by a pixel for the bilinear upscale's neighbours. cast_rect: grown by
  // the style's screen-space reach; bleed_rect: by the first blur axis (x) only.
  glm::ivec4 out_rect{0}, image_rect{0}, cast_rect{0}, bleed_rect{0};
  // bounds_rect: the pixels the ray-bounds pass can cover. frame_rect: what this frame touches;
  // pass_rect: where the ray bounds and the cast run (their intersection).
  glm::ivec4 bounds_rect{0}, frame_rect{0}, pass_rect{0};
  // blur_rect: the pixels a screen-space style's blur can change (see finishScreenSpace).
  glm::ivec4 blur_rect{0};
  std::string key;  // the image key (FrameHistory), with skipping
  float read_reach = 0.0f;
  std::vector<VoxelBox> pending;  // the changes the style's image shows
};

float VolumeRenderer::castScale(const Camera& camera, int height,
                                const RenderOptions& options) const {
  const bool smooth_sky =
      options.sky.kind == SkyKind::kNone || options.sky.kind == SkyKind::kColour;
  const bool still = options.scale >= 1.0f && !options.moving;
  if (!options.cast_at_volume_detail || !(still || options.moving) ||
      options.jitter != glm::vec2(0.0f) || options.write_depth || !smooth_sky ||
      !renderStyleRow(options.style).reprojects || dims_.x <= 0)
    return options.scale;
  const glm::vec3 voxel = (world_max_ - world_min_) / glm::vec3(dims_);
  const float detail = volumeDetailScale(camera, height, bounds_corners_, world_min_, voxel, 0.0f);
  return detailCastScale(options.scale, options.moving, detail);
}

void VolumeRenderer::render(const Camera& camera, int width, int height, GLuint target_fbo,
                            const RenderOptions& requested) {
  auto t0 = std::chrono::steady_clock::now();
  RenderOptions options = requested;
  options.scale = castScale(camera, height, requested);
  stats_ = RenderStats{};
  if (!ensureProgram(options)) {
    std::fprintf(stderr, "cloudbrush: render: %s\n", error_.c_str());
    return;
  }
  // The iso-surface styles' inner-surface search reads the pool's smoothed companion, made at
  // their first frame (the other styles never pay its bytes).
  if (drawsIsoSurface(options.style) && !pool_.smoothEnabled() && synced_volume_)
    pool_.enableSmooth(*synced_volume_);
  FramePlan plan;
  if (!ensureCastImages(width, height, target_fbo, options, &plan)) return;
  frame_camera_ = camera;
  stats_.width = plan.w;
  stats_.height = plan.h;
  if (options.collect_stats) {
    std::vector<uint32_t> zero(3 + kHistogramBins, 0u);
    glNamedBufferSubData(stats_buffer_, 0, GLsizeiptr(zero.size() * 4), zero.data());
  }
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  planFrame(camera, options, &plan);
  bindCastTargets(plan, camera, options);
  glUseProgram(program_);
  setCastUniforms(plan, camera, options);
  setStyleUniforms(options, plan.sky_under);
  castRays(plan, options);
  if (plan.skip) updateFrameHistory(plan, options);
  glDisable(GL_BLEND);
  finishFrame(plan, target_fbo, options);
  glDisable(GL_SCISSOR_TEST);
  if (options.collect_stats) readSampleStats(plan.w, plan.h);
  if (options.finish) {
    glFinish();
    stats_.frame_ms = msSince(t0);
  }
}

bool VolumeRenderer::ensureCastImages(int width, int height, GLuint target_fbo,
                                      const RenderOptions& options, FramePlan* plan) {
  FramePlan& p = *plan;
  p.width = width;
  p.height = height;
  const float scale = std::clamp(options.scale, 0.05f, 1.0f);
  p.w = std::max(1, int(std::lround(width * scale)));
  p.h = std::max(1, int(std::lround(height * scale)));
  p.reduced = p.w != width || p.h != height;
  std::string err;
  if (p.reduced && !options.skip_empty_space &&
      (low_res_.width() != p.w || low_res_.height() != p.h) &&
      !low_res_.create(p.w, p.h, RenderTarget::Format::kRgba8, &err)) {
    std::fprintf(stderr, "cloudbrush: render: %s\n", err.c_str());
    return false;
  }
  p.screen_space = hasScreenSpacePass(options.style);
  if (p.screen_space && !options.skip_empty_space &&
      (style_image_.width() != p.w || style_image_.height() != p.h) &&
      !style_image_.create(p.w, p.h, RenderTarget::Format::kRgba8, &err)) {
    std::fprintf(stderr, "cloudbrush: render: %s\n", err.c_str());
    return false;
  }
  p.draw_fbo = p.screen_space ? style_image_.fbo() : p.reduced ? low_res_.fbo() : target_fbo;
  p.sky_under = !p.screen_space && SkyPass::shows(options.sky, options.style, options.style_params);
  p.background = p.screen_space || p.sky_under ? glm::vec4(0.0f) : options.background;
  return true;
}

void VolumeRenderer::planFrame(const Camera& camera, const RenderOptions& options,
                               FramePlan* plan) {
  FramePlan& p = *plan;
  const int w = p.w, h = p.h;
  p.plain_view_proj = camera.projection(float(p.width) / float(p.height)) * camera.view();
  p.view_proj = jitterMatrix(options.jitter, w, h) * p.plain_view_proj;
  p.skip = options.skip_empty_space;
  p.partial = options.region.z > 0 && options.region.w > 0;
  auto grow = [&](glm::ivec4 r, int gx, int gy) {
    return clipRect(glm::ivec2(r.x - gx, r.y - gy), glm::ivec2(r.x + r.z + gx, r.y + r.w + gy), w,
                    h);
  };
  p.out_rect =
      clipRect(glm::ivec2(options.region.x, options.region.y),
               glm::ivec2(options.region.x + options.region.z, options.region.y + options.region.w),
               p.width, p.height);
  p.image_rect = p.out_rect;
  if (p.reduced) {
    const glm::vec2 s(float(w) / float(p.width), float(h) / float(p.height));
    const glm::ivec4& o = p.out_rect;
    const glm::ivec2 lo = glm::ivec2(glm::floor(glm::vec2(o.x, o.y) * s)) - 1;
    const glm::ivec2 hi = glm::ivec2(glm::ceil(glm::vec2(o.x + o.z, o.y + o.w) * s)) + 1;
    p.image_rect = clipRect(lo, hi, w, h);
  }
  const int reach = screenSpaceReach(options.style, options.style_params);
  p.cast_rect = grow(p.image_rect, reach, reach);
  p.bleed_rect = grow(p.image_rect, 0, reach);  // the first blur axis is x
  stats_.pixels_cast = p.partial ? (long long)p.cast_rect.z * p.cast_rect.w : (long long)w * h;
  // Re-cast only the changed pixels (a stencil mask of the pool slots changed since this size's
  // targets last held a whole frame of the same image key; every other pixel of the frame colour
  // is what a whole cast would write again), when that frame colour can be trusted.
  if (p.skip) p.key = imageKey(p.view_proj, w, h, options, p.background);
  if (p.skip) useFrameTargets(w, h);
  p.read_reach = readReachVoxels(options.style, (world_max_ - world_min_) / glm::vec3(dims_));
  p.pending = visibleChanges(history_.pending, options.style);
  p.masked = p.partial && p.skip && !p.screen_space && !p.sky_under && history_.valid &&
             history_.key == p.key && !history_.pending.empty() &&
             projectedRect(p.pending, p.read_reach, p.view_proj, w, h, nullptr);
  // The projected rectangle of the boundary's corners (all pixels when the eye is in or next to
  // an occupied cell, or when the masked re-cast must also reach pixels an erase emptied). Only
  // these are ray cast; the rest of the frame is the background.
  p.bounds_rect = glm::ivec4(0, 0, w, h);
  if (p.skip) {
    const int level = std::min(kRayBoundsLevel, occupancy_.levelCount() - 1);
    const glm::vec3 eye_voxel =
        (camera.eye - world_min_) / ((world_max_ - world_min_) / glm::vec3(dims_));
    eye_near_occupied_ = occupiedNear(occupancy_, level, eye_voxel);
    if (eye_near_occupied_ || p.masked ||
        !projectedPointsRect(bounds_corners_, p.view_proj, w, h, &p.bounds_rect))
      p.bounds_rect = glm::ivec4(0, 0, w, h);
  }
  p.frame_rect = p.partial ? p.cast_rect : glm::ivec4(0, 0, w, h);
  const glm::ivec4 &f = p.frame_rect, &b = p.bounds_rect;
  p.pass_rect = clipRect(
      glm::max(glm::ivec2(f), glm::ivec2(b)),
      glm::min(glm::ivec2(f) + glm::ivec2(f.z, f.w), glm::ivec2(b) + glm::ivec2(b.z, b.w)), w, h);
  // Where the blur runs (finishScreenSpace): within its reach of the boundary's projection, the
  // cast image's only pixels that are not the background; at a reduced scale, everywhere.
  p.blur_rect = p.skip && !p.reduced ? grow(p.bounds_rect, reach, reach)
                                     : glm::ivec4(0, 0, p.width, p.height);
}

void VolumeRenderer::bindCastTargets(const FramePlan& p, const Camera& camera,
                                     const RenderOptions& options) {
  // Everything below (ray bounds, clears, the cast, the blit) stays inside frame_rect; the ray
  // bounds and the cast inside pass_rect.
  glEnable(GL_SCISSOR_TEST);
  glScissor(p.pass_rect.x, p.pass_rect.y, p.pass_rect.z, p.pass_rect.w);
  if (p.skip) {
    drawRayBounds(camera, p.view_proj, p.w, p.h);  // costs per triangle, and per scissored pixel
    glScissor(p.frame_rect.x, p.frame_rect.y, p.frame_rect.z, p.frame_rect.w);
    // Ray cast only the pixels whose rays meet occupied cells; the rest is background. (With the
    // eye in or next to an occupied cell every pixel is cast from the near plane.)
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, bounds_fbo_);
    const GLenum colour_only = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &colour_only);
    if (p.masked) {
      // The changed pixels get stencil bit 2 and are all cast (an unoccupied one casts no sample
      // and writes the background); the frame colour keeps every other pixel.
      drawChangedMask(p.pending, p.read_reach, p.view_proj);
    } else {
      glClearBufferfv(GL_COLOR, 0, glm::value_ptr(p.background));
    }
  } else {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, p.draw_fbo);
  }
  glViewport(0, 0, p.w, p.h);
  if (p.sky_under) drawSkyUnder(p.w, p.h, p.width, p.height, options);
  if (p.masked) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 2, 2);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  } else if (p.skip && !eye_near_occupied_) {
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 1, 1);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  }
  if (p.skip && options.write_depth) {
    // Output 1 -> the depth texture, cleared to "no depth" where this frame casts.
    ensureDepthTarget();
    const GLenum colour_and_depth[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT2};
    glDrawBuffers(2, colour_and_depth);
    if (!p.masked) {
      const float none[4] = {kNoDepth, 0.0f, 0.0f, 0.0f};
      glClearBufferfv(GL_COLOR, 1, none);
    }
    glDisablei(GL_BLEND, 1);
  }
}

void VolumeRenderer::setCastUniforms(const FramePlan& p, const Camera& camera,
                                     const RenderOptions& options) {
  glm::mat4 inv = glm::inverse(p.plain_view_proj);
  auto loc = [&](const char* name) { return glGetUniformLocation(program_, name); };
  glUniformMatrix4fv(loc("u_inv_view_proj"), 1, GL_FALSE, glm::value_ptr(inv));
  glUniform2fv(loc("u_jitter"), 1, glm::value_ptr(options.jitter));
  glUniform2f(loc("u_viewport"), float(p.w), float(p.h));
  glUniform3fv(loc("u_world_min"), 1, glm::value_ptr(world_min_));
  glm::vec3 voxel = (world_max_ - world_min_) / glm::vec3(dims_);
  glUniform3fv(loc("u_voxel_size"), 1, glm::value_ptr(voxel));
  glUniform3f(loc("u_dims"), float(dims_.x), float(dims_.y), float(dims_.z));
  glUniform1i(loc("u_pool"), 0);
  glUniform1i(loc("u_pool_smooth"), 6);
  glUniform1i(loc("u_bricks"), 5);
  const glm::ivec3 brick_max = pool_.brickDims() - 1;
  glUniform3fv(loc("u_inv_brick_dims"), 1, glm::value_ptr(1.0f / glm::vec3(pool_.brickDims())));
  glUniform3i(loc("u_brick_max"), brick_max.x, brick_max.y, brick_max.z);
  glUniform3fv(loc("u_inv_pool_fixed"), 1,
               glm::value_ptr(1.0f / (glm::vec3(pool_.poolTexels()) * 256.0f)));
  glUniform1i(loc("u_occupancy"), 1);
  glUniform1i(loc("u_brick"), occupancy_.brick);
  glUniform1i(loc("u_levels"), occupancy_.levelCount());
  const float step = rayStepVoxels(options);
  glUniform1f(loc("u_step"), step);
  glUniform1f(loc("u_sigma"), options.extinction_per_voxel);
  glUniform1f(loc("u_cutoff"), options.termination_transmittance);
  glUniform4fv(loc("u_background"), 1, glm::value_ptr(p.background));
  glUniform1i(loc("u_ray_bounds"), 2);
  glUniform3fv(loc("u_eye"), 1, glm::value_ptr(camera.eye));
  glUniform1i(loc("u_bounds_from_near_plane"), eye_near_occupied_ ? 1 : 0);
  glUniform1f(loc("u_no_depth"), kNoDepth);
  glUniform1f(loc("u_depth_min"), kDepthMinOpacity);
  if (options.skip_empty_space) glBindTextureUnit(2, bounds_texture_);
  glUniform3fv(loc("u_light_colour"), 1, glm::value_ptr(synced_light_.colour));
  if (light_is_preview_) light_preview_.bind(program_, 7, dims_);
}

// The shading stages' uniforms: set for every stage (a stage that does not declare one ignores
// it: location −1), from the style's row and parameters (render_style.h).
void VolumeRenderer::setStyleUniforms(const RenderOptions& options, bool sky_under) {
  auto loc = [&](const char* name) { return glGetUniformLocation(program_, name); };
  const RenderStyleRow& row = renderStyleRow(options.style);
  glUniform3fv(loc("u_light_dir"), 1, glm::value_ptr(synced_light_.direction));
  glUniform3fv(
      loc("u_sky_colour"), 1,
      glm::value_ptr(sky_under ? skyAmbientColour(options.sky) : glm::vec3(options.background)));
  glUniform1f(loc("u_iso"), kIsoDensity);
  glUniform1f(loc("u_inner_iso"), kInnerIsoDensity);
  // Normals and the inner surface at the thesis box's world distances (render_style.h).
  const IsoSurfaceReach iso_reach = isoSurfaceReach((world_max_ - world_min_) / glm::vec3(dims_));
  glUniform1f(loc("u_gradient_voxels"), iso_reach.gradient_voxels);
  glUniform1f(loc("u_inner_depth"), iso_reach.inner_depth_voxels);
  // Each style's parameters (render_style_params.h).
  const StyleParams& sp = options.style_params;
  const PhysicalStyleParams& ph = sp.physical;
  glUniform1f(loc("u_reflection"), ph.reflection);
  glUniform1f(loc("u_scattering"), ph.scattering);
  glUniform3f(loc("u_phase_lobes"), ph.forward_g, ph.back_g, ph.forward_weight);
  glUniform1i(loc("u_octaves"), std::clamp(ph.octaves, 1, 3));
  glUniform1f(loc("u_ambient"), ph.ambient);
  glUniform1f(loc("u_exposure"), ph.exposure);
  glUniform1f(loc("u_ink_wash"), sp.ink.wash);
  glUniform1f(loc("u_ink_line_width"), sp.ink.line_width);
  glUniform3fv(loc("u_cel_thresholds"), 1, glm::value_ptr(sp.cartoon.band_thresholds));
  if (row.outline_width) glUniform1f(loc("u_outline_width"), row.outline_width(sp));
  if (row.light_table) {
    ensurePhysicalTextures();
    glUniform1i(loc("u_detail_noise"), 3);
    glUniform1i(loc("u_light_table"), 4);
    glBindTextureUnit(4, light_table_texture_);
    glUniform3fv(loc("u_noise_repeat"), 1,
                 glm::value_ptr(glm::vec3(dims_) / kDetailNoisePeriodVoxels));
    glUniform1f(loc("u_erosion"), ph.erosion);
    glBindTextureUnit(3, detail_noise_texture_);
  }
}

void VolumeRenderer::castRays(const FramePlan& p, const RenderOptions& options) {
  glBindTextureUnit(0, pool_.poolTexture());
  glBindTextureUnit(6, pool_.smoothTexture());
  glBindTextureUnit(5, pool_.indirectionTexture());
  if (options.skip_empty_space && options.brick_stepping) ensureOccupancyTexture();
  glBindTextureUnit(1, occupancy_texture_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, stats_buffer_);
  glBindVertexArray(vao_);
  GLuint cast_query = 0;
  if (p.masked) {
    glCreateQueries(GL_SAMPLES_PASSED, 1, &cast_query);
    glBeginQuery(GL_SAMPLES_PASSED, cast_query);
  }
  glScissor(p.pass_rect.x, p.pass_rect.y, p.pass_rect.z, p.pass_rect.w);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (p.masked) {
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 cast = 0;
    glGetQueryObjectui64v(cast_query, GL_QUERY_RESULT, &cast);
    glDeleteQueries(1, &cast_query);
    stats_.pixels_cast = (long long)cast;
  }
  glDisable(GL_STENCIL_TEST);
}

// What the frame colour of these targets now holds (FrameHistory).
void VolumeRenderer::updateFrameHistory(const FramePlan& p, const RenderOptions& options) {
  if (p.screen_space || p.sky_under) {
    history_ = FrameHistory{};
  } else if (!p.partial) {
    history_ = FrameHistory{p.key, {}, true};
  } else if (p.masked) {
    // Boxes seen whole inside the rectangle are done; the others' pixels outside it are not
    // (the region holds every pixel the latest change alters, not those of older ones).
    const glm::ivec4& c = p.cast_rect;
    std::erase_if(history_.pending, [&](const BrickPool::SlotChange& change) {
      const VoxelBox box = visibleChange(change, options.style);
      if (box.empty()) return true;  // nothing this image shows
      glm::ivec4 r;
      return projectedRect({box}, p.read_reach, p.view_proj, p.w, p.h, &r) && r.x >= c.x &&
             r.y >= c.y && r.x + r.z <= c.x + c.z && r.y + r.w <= c.y + c.w;
    });
  } else if (history_.key != p.key) {
    history_.valid = false;  // a rectangle of another image over the old frame
  }  // else: the rectangle is fresh; the pending boxes outside it are still to do
}

// The paper styles' screen-space pass from the ray-cast image to the target. The blur (first
// axis here into bleed_, second in the compose pass) runs only over blur_rect, the cast pixels
// within the blur's reach of the boundary's projection (FramePlan): beyond it the image is the
// cleared background, whose blur is the background again, so the compose pass draws those
// pixels with its unblurred variant, bit for bit the same output at a fraction of the reads.
void VolumeRenderer::finishScreenSpace(GLuint image, const FramePlan& p, GLuint target_fbo,
                                       const RenderOptions& options) {
  const int w = p.w, h = p.h, width = p.width, height = p.height;
  const bool ink = renderStyleRow(options.style).screen_pass == ScreenPass::kInkWash;
  const bool bleed = !options.moving;
  const float sigma = screenBlurSigma(options.style, options.style_params);
  const int radius = inkBleedRadius(sigma);
  const bool over_sky = SkyPass::shows(options.sky, options.style, options.style_params);
  const bool full_scale = w == width && h == height;
  GLuint compose = fullscreenProgram("style_compose.frag.glsl",
                                     composeDefines(ink, bleed, over_sky, full_scale, radius));
  GLuint plain = fullscreenProgram("style_compose.frag.glsl",
                                   composeDefines(ink, false, over_sky, full_scale, radius));
  GLuint blur = bleed ? fullscreenProgram("ink_bleed.frag.glsl", screenBlurDefine(radius)) : 0;
  if (!compose || !plain || (bleed && !blur)) {
    std::fprintf(stderr, "cloudbrush: render: %s\n", error_.c_str());
    return;
  }
  glTextureParameteri(image, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(image, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(image, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(image, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindVertexArray(vao_);
  const ScreenBlurWeights weights = screenBlurWeights(sigma, radius);
  const glm::ivec4 whole_image(0, 0, w, h), whole_target(0, 0, width, height);
  if (bleed) {
    // First axis of the blur over the rows the compose pass's taps read around blur_rect.
    const glm::ivec4& b = p.blur_rect;
    const glm::ivec4 rows = intersectRects(glm::ivec4(b.x, b.y - radius, b.z, b.w + 2 * radius),
                                           p.partial ? p.bleed_rect : whole_image);
    if (!blurAlongX(blur, image, w, h, rows, weights, radius)) return;
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_fbo);
  glViewport(0, 0, width, height);
  glEnable(GL_SCISSOR_TEST);
  const glm::ivec4 out = p.partial ? p.out_rect : whole_target;
  glScissor(out.x, out.y, out.z, out.w);
  if (over_sky) drawSkyUnder(width, height, width, height, options);
  const glm::ivec4 blurred = bleed ? intersectRects(out, p.blur_rect) : glm::ivec4(0);
  for (const glm::ivec4& r : rectMinus(out, blurred))
    drawCompose(plain, image, image, r, width, height, weights, -1);
  if (blurred.z > 0 && blurred.w > 0)
    drawCompose(compose, image, bleed_.texture(), blurred, width, height, weights, radius);
  glDisable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
}

// The blur's first axis from `image` into bleed_ (made w×h), over `rect`; false on failure.
bool VolumeRenderer::blurAlongX(GLuint blur, GLuint image, int w, int h, glm::ivec4 rect,
                                const ScreenBlurWeights& weights, int radius) {
  if (bleed_.width() != w || bleed_.height() != h) {
    std::string err;
    if (!bleed_.create(w, h, RenderTarget::Format::kRgba8, &err)) {
      std::fprintf(stderr, "cloudbrush: render: %s\n", err.c_str());
      return false;
    }
    glTextureParameteri(bleed_.texture(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(bleed_.texture(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(bleed_.texture(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(bleed_.texture(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  if (rect.z <= 0 || rect.w <= 0) return true;
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, bleed_.fbo());
  glViewport(0, 0, w, h);
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect.x, rect.y, rect.z, rect.w);
  glUseProgram(blur);
  glUniform1i(glGetUniformLocation(blur, "u_image"), 0);
  glUniform2i(glGetUniformLocation(blur, "u_axis"), 1, 0);
  setBlurWeights(blur, weights, radius);
  glBindTextureUnit(0, image);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  return true;
}

// One compose program over the target's rectangle `rect` (radius < 0: a variant without the blur).
void VolumeRenderer::drawCompose(GLuint program, GLuint image, GLuint bleed, glm::ivec4 rect,
                                 int width, int height, const ScreenBlurWeights& weights,
                                 int radius) {
  if (rect.z <= 0 || rect.w <= 0) return;
  glScissor(rect.x, rect.y, rect.z, rect.w);
  glUseProgram(program);
  if (radius >= 0) setBlurWeights(program, weights, radius);
  glUniform1i(glGetUniformLocation(program, "u_image"), 0);
  glUniform1i(glGetUniformLocation(program, "u_bleed"), 1);
  glUniform2f(glGetUniformLocation(program, "u_output_size"), float(width), float(height));
  glBindTextureUnit(0, image);
  glBindTextureUnit(1, bleed);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// The cast image to the target: the style's screen-space pass, or the blit (an upscale at a
// reduced size).
void VolumeRenderer::finishFrame(const FramePlan& p, GLuint target_fbo,
                                 const RenderOptions& options) {
  const int w = p.w, h = p.h, width = p.width, height = p.height;
  glScissor(p.out_rect.x, p.out_rect.y, p.out_rect.z, p.out_rect.w);  // the blit, too
  if (!p.partial) glDisable(GL_SCISSOR_TEST);
  if (p.screen_space) {
    finishScreenSpace(p.skip ? frame_texture_ : style_image_.texture(), p, target_fbo, options);
  } else if (p.skip) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, bounds_fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_fbo);
    if (p.reduced && !p.sky_under && p.bounds_rect != glm::ivec4(0, 0, w, h)) {
      // Outside bounds_rect the image is the background, and so is every target pixel whose
      // bilinear footprint lies there: cleared (a memset per tile for llvmpipe), not filtered.
      // (At full size the blit is a plain copy, cheaper whole than a clear and a smaller copy:
      // 0.9 against 2.2 ms at 1920×1080.)
      // The blit keeps its whole-image mapping and is scissored to the target pixels whose
      // footprint (2 texels per axis) may meet bounds_rect.
      glClearBufferfv(GL_COLOR, 0, glm::value_ptr(p.background));
      const glm::vec2 k(float(width) / float(w), float(height) / float(h));
      const glm::ivec4& b = p.bounds_rect;
      const glm::ivec2 lo = glm::ivec2(glm::floor(glm::vec2(b.x - 1, b.y - 1) * k));
      const glm::ivec2 hi = glm::ivec2(glm::ceil(glm::vec2(b.x + b.z + 1, b.y + b.w + 1) * k));
      const glm::ivec4 out = p.partial ? p.out_rect : glm::ivec4(0, 0, width, height);
      const glm::ivec4 blit_rect =
          clipRect(glm::max(lo, glm::ivec2(out)),
                   glm::min(hi, glm::ivec2(out) + glm::ivec2(out.z, out.w)), width, height);
      glEnable(GL_SCISSOR_TEST);
      glScissor(blit_rect.x, blit_rect.y, blit_rect.z, blit_rect.w);
    }
    glBlitFramebuffer(0, 0, w, h, 0, 0, width, height, GL_COLOR_BUFFER_BIT,
                      p.reduced ? GL_LINEAR : GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  } else if (p.reduced) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, low_res_.fbo());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_fbo);
    glBlitFramebuffer(0, 0, w, h, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  }
}

void VolumeRenderer::readSampleStats(int w, int h) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> raw(3 + kHistogramBins);
  glGetNamedBufferSubData(stats_buffer_, 0, GLsizeiptr(raw.size() * 4), raw.data());
  stats_.has_samples = true;
  stats_.samples_total = raw[0];
  stats_.samples_max = raw[1];
  stats_.histogram.assign(raw.begin() + 3, raw.end());
  // Pixels the stencil kept from ray casting took no samples.
  const uint64_t pixels = uint64_t(w) * uint64_t(h);
  if (raw[2] < pixels) stats_.histogram[0] += uint32_t(pixels - raw[2]);
  stats_.samples_mean = double(raw[0]) / double(pixels);
}

}  // namespace cb
