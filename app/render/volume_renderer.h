// The volume renderer (thesis ch. 4): keeps GPU copies of a Volume's density, its light volume
// (§4.5) and its occupancy pyramid (§4.4) in step with the Volume's dirty boxes, and ray casts
// them into any framebuffer.
//
//   VolumeRenderer r;
//   if (!r.init(&error)) ...                  // needs a current OpenGL 4.5 core context
//   r.sync(volume, light);                    // uploads only what changed since the last sync
//   r.render(camera, w, h, target_fbo, opts); // draws into target_fbo (0 = default framebuffer)
//
// The CPU stages (occupancy update, light sweep, packing) are free functions elsewhere
// (occupancy_pyramid.h, light_volume.h) so callers can time them separately; sync() reports
// their times in SyncStats.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/render/brick_pool.h"
#include "app/render/gl/gl.h"
#include "app/render/light_preview_texture.h"
#include "app/render/light_volume.h"
#include "app/render/occupancy_pyramid.h"
#include "app/render/reduced_light_sweep.h"
#include "app/render/render_style.h"
#include "app/render/render_target.h"
#include "app/render/screen_blur.h"
#include "app/render/sky_pass.h"
#include "app/render/sky_settings.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"
#include "app/volume/volume.h"

namespace cb {

struct RenderOptions {
  bool skip_empty_space = true;
  // Inside the rasterised ray bounds, also step hierarchically over the occupancy pyramid
  // (max-mip climbing). Lossless either way; measured slower on llvmpipe (its texelFetch on the
  // integer mip chain costs more than the samples it saves), so off by default.
  bool brick_stepping = false;
  // Render at (width·scale)×(height·scale) and upscale (bilinear) into the target: for a moving
  // camera; use 1 when it stops.
  float scale = 1.0f;
  // A frame cast at the volume's detail where that looks the same (volume_detail.h; no jitter or
  // depth): at rest no coarser than half per axis rather than a ray per pixel, moving no finer
  // than the volume needs. The painter's frames; off for exports and tests that compare casts.
  bool cast_at_volume_detail = false;
  float step_voxels = 1.0f;                         // ray step in voxels (the reference is 1)
  float extinction_per_voxel = 0.35f;               // σ: α = 1 − exp(−σ·density·step)
  float termination_transmittance = 0.01f;          // early ray termination threshold
  glm::vec4 background{0.47f, 0.62f, 0.82f, 1.0f};  // premultiplied; a = 0 for a transparent one
  bool collect_stats = false;  // per-pixel sample counts into RenderStats (atomics; a bit slower)
  bool finish = false;         // glFinish() and report the frame's wall time in RenderStats
  // How density and light become colour (render_style.h): the thesis's curve by default. The
  // iso-surface styles ignore extinction_per_voxel and termination_transmittance.
  RenderStyle style = RenderStyle::kThesis;
  // Each style's parameters (render_style_params.h, config/render.toml [style.NAME]).
  StyleParams style_params;
  // The sky behind the cloud (sky_settings.h); kind none keeps the flat `background`.
  SkySettings sky;
  // The view is moving (orbit, drag): styles may shade more simply (ink: the seed's two bands,
  // no bleeding) and, below scale 1, the ray steps as coarsely as the reduced image's pixels
  // (rayStepVoxels). Set it together with scale < 1; clear both when the view comes to rest.
  bool moving = false;
  // Re-render only this rectangle of the target (x, y, width, height in pixels, origin at the
  // bottom left like glScissor) and leave the rest of the target as it is; a zero width or
  // height means the whole frame (changed_region.h computes the rectangle a volume change
  // needs). At scale < 1 the rectangle is ray cast at the reduced size (grown by one pixel for
  // the bilinear upscale) and upscaled into R only. The previous frame must have come from this
  // renderer at the same size and style, because screen-space styles keep their ray-cast image
  // between frames: a style whose pass reads r = screenSpaceReach(style) pixels around each
  // pixel has R dilated by r ray cast, its first blur axis run over R dilated by r across that
  // axis, and only R finished, so every pixel of R reads only fresh pixels and equals a
  // full-frame render (tested). The ray bounds are rasterised inside the cast rectangle only.
  glm::ivec4 region{0};
  // The cast image's pixel centres moved by this many of its pixels (x right, y up): ray (i, j)
  // passes through (i + ½ + jitter.x, j + ½ + jitter.y). The interleaved casts of
  // temporal_reprojection.h cast every f-th pixel of a full frame as a 1/f-size image jittered
  // onto those pixels. (0, 0): the plain frame.
  glm::vec2 jitter{0.0f};
  // Also write each pixel's transmittance-weighted depth, Σ(T − T')·t / Σ(T − T') as a world
  // distance from the eye (kNoDepth where the ray gathers under kDepthMinOpacity), into
  // frameDepthTexture(). Needs skip_empty_space (the frame targets hold it).
  bool write_depth = false;
};

// The depth written where a ray meets (next to) nothing: reprojected as a direction (at infinity).
constexpr float kNoDepth = 1e30f;
// Below this opacity (1 − T) a ray's depth is kNoDepth: too thin to place.
constexpr float kDepthMinOpacity = 0.02f;

struct RenderStats {
  int width = 0, height = 0;  // the resolution actually ray cast
  long long pixels_cast =
      0;  // pixels of that image inside the cast rectangle (all without a region)
  bool has_samples = false;  // collect_stats was on
  uint64_t samples_total = 0;
  uint32_t samples_max = 0;
  double samples_mean = 0.0;  // per pixel
  int histogram_bin_width = 8;
  std::vector<uint32_t> histogram;  // pixels per bin of samples; the last bin is open-ended
  double frame_ms = 0.0;            // with `finish`: wall time of render() including glFinish
  std::string summary() const;      // a human-readable block (CLI --stats)
};

struct SyncStats {
  VoxelBox dirty;           // density box changed since the previous sync
  VoxelBox light_box;       // light volume voxels recomputed
  VoxelBox uploaded;        // voxels whose GPU copy was brought up to date (dirty ∪ light box)
  int slots_uploaded = 0;   // brick-pool slots re-packed and uploaded for them (brick_pool.h)
  int slots_unchanged = 0;  // re-packed but holding the same bytes: not uploaded
  // Every slot added, released or uploaded, with the voxels whose texels changed in it
  // (BrickPool::SlotChange; visibleChanges in changed_region.h picks a style's): a ray that
  // samples none of them renders as before the sync. Empty when nothing changed.
  std::vector<BrickPool::SlotChange> changes;
  // The light volume was swept anew everywhere: the light's direction or extinction changed,
  // or a drag's coarse preview began or was recomputed in full at its release. Every lit voxel
  // may differ, so `changes` lists only slots added or released (comparing every slot's texels
  // costs more than the frame) and no frame held is reused: the whole frame is cast anew.
  bool light_moved = false;
  bool pool_grew = false;  // the brick pool was reallocated to hold more slots
  // The volume had grown around the one synced before (Volume::Growth): what the renderer held
  // was shifted by the growth's offset instead of being rebuilt (growth_ms), then updated.
  bool followed_growth = false;
  double growth_ms = 0.0;
  double occupancy_ms = 0.0;  // updateOccupancy
  double light_ms = 0.0;      // sweepLightVolume
  double pack_ms = 0.0;       // packing density + transmittance into pool slots (RGBA8)
  double upload_ms = 0.0;     // glTextureSubImage3D calls (occupancy, pool slots, indirection)
};

// What the renderer holds on the GPU, in bytes (VolumeRenderer::gpuMemory).
struct RendererGpuMemory {
  size_t pool = 0;           // the brick pool texture (all its slots, free ones included)
  size_t indirection = 0;    // one RGBA8UI texel per brick
  size_t occupancy = 0;      // the R8UI occupancy mip chain
  size_t ray_bounds = 0;     // the occupied cells' faces (vertex buffer)
  size_t light_preview = 0;  // a light drag's coarse light (R8, at most 4 MB), once dragged
  size_t frame_targets = 0;  // ray-bounds, frame and stencil targets (current and spare size),
                             // the reduced-scale and style images: these follow the screen size
  size_t styles = 0;         // the physical style's noise cube and light table, once used
  size_t volume() const { return pool + indirection + occupancy + ray_bounds + light_preview; }
  size_t total() const { return volume() + frame_targets + styles; }
};

// The ray step render() uses, in voxels: options.step_voxels, and on a moving frame (moving,
// scale < 1) that step divided by the scale, at most kMaxMovingStepVoxels: a pixel of the reduced
// image is 1/scale pixels of the full one across, so the ray is sampled as coarsely along as
// across (opacity per step follows the step, Beer–Lambert, so the cloud keeps its density).
// The frame at rest is always cast at options.step_voxels.
constexpr float kMaxMovingStepVoxels = 2.0f;
float rayStepVoxels(const RenderOptions& options);
// Ray samples per brick-pool lookup at that step (shaders/volume_pool.glsl): as many as stay
// within the slot's apron (BrickPool::kApron voxels past the first), at most 4. A compile-time
// constant of the program (CB_CHUNK): llvmpipe runs every unrolled sample of a chunk, active or
// not, so a chunk longer than the step allows would cost samples it cannot take.
int chunkSamples(float step_voxels);

class VolumeRenderer {
 public:
  VolumeRenderer() = default;
  ~VolumeRenderer();
  VolumeRenderer(const VolumeRenderer&) = delete;
  VolumeRenderer& operator=(const VolumeRenderer&) = delete;

  // Compiles the shaders; needs a current GL 4.5 core context. False with a message on failure.
  bool init(std::string* error);
  // Brings the GPU copies up to date with `volume` and `light`: only the voxels changed since the
  // last sync (Volume::dirtySince) are re-packed and uploaded; the occupancy is updated over the
  // dirty box; the light volume over the dirty box swept away from the light, or entirely when
  // the light changed. A volume grown around the synced one (Volume::growth(): made by
  // Volume::movedInto from the instance and generation last synced) keeps what was uploaded,
  // shifted by the growth's brick offset (pool indirection, light bricks, occupancy), and updates
  // what changed since as an edit; the result equals a fresh sync of it (sky_growth_test). Any
  // other Volume (by instanceId()) or new dims re-uploads everything; after replacing a volume's
  // contents without markDirty (never do that) call invalidate(). `detail`: how SyncStats::changes
  // lists a changed slot (BrickPool's ChangeDetail).
  SyncStats sync(const Volume& volume, const Light& light,
                 ChangeDetail detail = ChangeDetail::kTexels);
  // While the light is dragged: a light change is swept on a grid `divisor` times coarser per
  // axis (2: the thesis's 128³ for 256³; reduced_light_sweep.h) and read by the ray caster from
  // a small texture of its own, leaving the light volume and the pool as they were; 1, the
  // default, sweeps at full resolution. The first sync after the divisor returns to 1 brings the
  // light volume to the light then (a full sweep unless it is the light before the drag).
  // With LightPreviewOf::kLightMoves (the light drag) a sync that changes the volume, or a fresh
  // one, sweeps in full whatever the divisor. With kEveryChange (an animation's frames, each a
  // changed volume) the coarse light is swept anew for every changed volume too, and what the
  // frames changed is swept into the light volume at the first sync after the divisor returns
  // to 1; a fresh sync sweeps in full.
  enum class LightPreviewOf { kLightMoves, kEveryChange };
  void setLightPreviewDivisor(int divisor, LightPreviewOf of = LightPreviewOf::kLightMoves) {
    light_preview_divisor_ = divisor < 1 ? 1 : divisor;
    light_preview_of_ = of;
  }
  // True while frames read the light from the preview texture.
  bool lightIsPreview() const { return light_is_preview_; }
  // Ray casts the synced volume into `target_fbo` (width×height). With options.scale < 1 it
  // renders into an internal smaller target and blits it up. With skipping, only the boundary's
  // screen rectangle is bounded, cast and blitted; the rest of the target is cleared to the
  // background (with a sky under the cloud, the whole image is blitted).
  void render(const Camera& camera, int width, int height, GLuint target_fbo,
              const RenderOptions& options = {});
  // The scale render() casts `options` at: options.scale, or for a frame cast at the volume's
  // detail (RenderOptions::cast_at_volume_detail) detailCastScale of the synced volume's occupied
  // cells.
  float castScale(const Camera& camera, int height, const RenderOptions& options) const;
  // Compiles (and caches) every program render(…, options) will use, without drawing: call it
  // when a style is chosen so the first frame in that style does not pay llvmpipe's shader
  // compile (100–500 ms measured by `bench styles`). False with a message on failure.
  bool prepare(const RenderOptions& options, std::string* error);
  RenderStats lastStats() const { return stats_; }
  // Forgets what was uploaded: the next sync() re-uploads everything.
  void invalidate() {
    synced_volume_id_ = 0;
    synced_volume_ = nullptr;
  }
  const LightVolume& lightVolume() const { return light_volume_; }
  const OccupancyPyramid& occupancy() const { return occupancy_; }
  const BrickPool& brickPool() const { return pool_; }
  // For tests: BrickPool::enableSmooth before the first sync (render does it at the first frame
  // of a style that reads the companion).
  BrickPool& brickPool() { return pool_; }
  // The last frame's R32F depth (RenderOptions::write_depth) at the cast image's size; 0 before
  // a frame wrote one.
  GLuint frameDepthTexture() const { return depth_texture_; }
  // GL-side bytes, itemised (RendererGpuMemory); memoryBytes() is their total.
  RendererGpuMemory gpuMemory() const;
  size_t memoryBytes() const { return gpuMemory().total(); }

 private:
  // The ray-cast program variant for these options (compiled on first use, then cached).
  bool ensureProgram(const RenderOptions& options);
  // A fullscreen program of `fragment` with `defines` (compiled on first use, then cached).
  GLuint fullscreenProgram(const std::string& fragment, const std::string& defines);
  // The screen-space pass of ink and sketch: `image` (the plan's w×h ray-cast image) ->
  // target_fbo. With a partial plan the first blur axis is scissored to bleed_rect and the finish
  // to out_rect; the blur runs only over blur_rect.
  struct FramePlan;
  void finishScreenSpace(GLuint image, const FramePlan& plan, GLuint target_fbo,
                         const RenderOptions& options);
  bool blurAlongX(GLuint blur, GLuint image, int w, int h, glm::ivec4 rect,
                  const ScreenBlurWeights& weights, int radius);
  void drawCompose(GLuint program, GLuint image, GLuint bleed, glm::ivec4 rect, int width,
                   int height, const ScreenBlurWeights& weights, int radius);
  void ensurePhysicalTextures();
  // The sky hook: draws options.sky into the bound framebuffer and sets the blending that
  // composites what is drawn next over it (premultiplied "over"). False when the style shows
  // no sky (then nothing is drawn).
  bool drawSkyUnder(int w, int h, int width, int height, const RenderOptions& options);
  // Whether `volume` was grown around exactly what was last synced (see sync), and following it.
  bool followsGrowth(const Volume& volume) const;
  void followGrowth(const Volume& volume);
  // Parts of sync(): the light volume (returns the box whose light changed), the frame targets
  // given back for a new volume, the ray-bounds faces uploaded.
  VoxelBox syncLight(const Volume& volume, const Light& light, bool fresh, const VoxelBox& dirty,
                     LightByteChanges* light_bytes);
  void dropFrameTargets();
  void uploadRayBounds();
  // Makes the occupancy texture current (allocated at the pyramid's size, its stale cells
  // uploaded): only frames that step over it (RenderOptions::brick_stepping) read it.
  void ensureOccupancyTexture();
  void uploadOccupancy(const VoxelBox& cells);
  // Makes the frame targets of a w×h image current (keeping the previous size's as the spare).
  void useFrameTargets(int w, int h);
  // Into the targets useFrameTargets(w, h) made current.
  void drawRayBounds(const Camera& camera, const glm::mat4& view_proj, int w, int h);
  // Attaches a depth texture to the current frame targets (RenderOptions::write_depth).
  void ensureDepthTarget();
  // render()'s passes, in order, over one frame's plan (defined in volume_renderer.cpp).
  // The cast image's size and where it goes (making the reduced and style images): false with
  // a message on failure.
  bool ensureCastImages(int width, int height, GLuint target_fbo, const RenderOptions& options,
                        FramePlan* plan);
  void planFrame(const Camera& camera, const RenderOptions& options, FramePlan* plan);
  void bindCastTargets(const FramePlan& plan, const Camera& camera, const RenderOptions& options);
  void setCastUniforms(const FramePlan& plan, const Camera& camera, const RenderOptions& options);
  void setStyleUniforms(const RenderOptions& options, bool sky_under);
  void castRays(const FramePlan& plan, const RenderOptions& options);
  void updateFrameHistory(const FramePlan& plan, const RenderOptions& options);
  void finishFrame(const FramePlan& plan, GLuint target_fbo, const RenderOptions& options);
  void readSampleStats(int w, int h);

  GLuint program_ = 0;                      // the variant in use
  std::map<std::string, GLuint> programs_;  // variants by shading file + defines
  GLuint vao_ = 0, occupancy_texture_ = 0, stats_buffer_ = 0;
  // The occupancy texture's size (level 0, levels) and the level-0 cells it lacks.
  glm::ivec3 occupancy_texture_dims_{0};
  int occupancy_texture_levels_ = 0;
  VoxelBox occupancy_texture_stale_;
  glm::ivec3 dims_{0};
  glm::vec3 world_min_{0.0f}, world_max_{0.0f};
  uint64_t synced_volume_id_ = 0;  // Volume::instanceId() last synced, 0: none
  // The volume last synced: read by the first render in a style that needs the pool's smoothed
  // companion (BrickPool::enableSmooth), which packs it then. Every caller syncs the volume it
  // renders just before rendering, so it is alive there.
  const Volume* synced_volume_ = nullptr;
  uint64_t synced_generation_ = 0;
  // After following a growth: the allocated bricks on the old edge, for the pool's update.
  std::vector<glm::ivec3> growth_edge_bricks_;
  Light synced_light_;
  BrickPool pool_;  // density and transmittance on the GPU (brick_pool.h)
  LightVolume light_volume_;
  ReducedLightSweep reduced_light_;
  LightPreviewTexture light_preview_;  // the drag's coarse light on the GPU
  Light preview_light_;                // the light it was swept for
  int light_preview_divisor_ = 1;
  LightPreviewOf light_preview_of_ = LightPreviewOf::kLightMoves;
  bool light_is_preview_ = false;
  VoxelBox light_unswept_;  // density changed under a preview: swept when the preview ends
  OccupancyPyramid occupancy_;
  RenderTarget low_res_;
  RenderTarget style_image_;  // the ray-cast image of a screen-space style without skipping
  RenderTarget bleed_;        // ink: the silhouette blurred along x
  // The physical style's fBm cube (detail_noise.h) and light table (physical_light_table.h),
  // made on its first frame.
  GLuint detail_noise_texture_ = 0, light_table_texture_ = 0;
  // Ray bounds pass: boundary faces of occupied cells at kRayBoundsLevel, rasterised into an
  // RG32F target (nearest, −farthest face distance per pixel).
  GLuint bounds_program_ = 0, bounds_vao_ = 0, bounds_vbo_ = 0;
  // The VBO holds the boundary's triangles (occupiedBoundaryFaces of kRayBoundsLevel).
  GLsizei bounds_vertices_ = 0;
  // The corners of the boundary's rectangles (boundaryCorners): every pixel the pass covers lies
  // in their projected rectangle, so the pass, the cast and the upscale are confined to it.
  std::vector<glm::vec3> bounds_corners_;
  size_t bounds_vbo_bytes_ = 0;
  // With skipping, one FBO holds the frame colour (attachment 0), the ray bounds (attachment 1)
  // and a stencil marking pixels whose rays meet occupied cells: only those are ray cast
  // (llvmpipe tests stencil before shading), then the colour is blitted to the target.
  GLuint bounds_fbo_ = 0, bounds_texture_ = 0, frame_texture_ = 0, stencil_buffer_ = 0;
  GLuint depth_texture_ = 0;  // attachment 2, made by the first frame that writes depth
  int bounds_w_ = 0, bounds_h_ = 0;
  struct FrameTargets {
    GLuint fbo = 0, bounds = 0, frame = 0, stencil = 0, depth = 0;
    int w = 0, h = 0;
  };
  FrameTargets spare_targets_;  // the previous size's (see drawRayBounds)
  // What the frame colour of a size's targets holds (for re-casting only changed pixels): the
  // image key (camera, size, program, shading inputs) it was cast with, and the pool slots'
  // changes since (sync appends; each with its changed voxels). `valid` is false when the colour is
  // not a whole frame of `key` (never cast, another key, too many boxes): then only the rectangle
  // path is exact.
  struct FrameHistory {
    std::string key;
    std::vector<BrickPool::SlotChange> pending;
    bool valid = false;
  };
  FrameHistory history_, spare_history_;  // of the current and the spare targets
  // Changes beyond this many make a mask cost more than the rectangle saves (first merged to
  // one per slot, then given up).
  static constexpr size_t kMaxMaskBoxes = 2048;
  GLuint mask_vao_ = 0, mask_vbo_ = 0;  // the changed slots' boxes as triangles (stencil mask)
  size_t mask_vbo_bytes_ = 0;
  std::string imageKey(const glm::mat4& view_proj, int w, int h, const RenderOptions& options,
                       const glm::vec4& background) const;
  // The pixel rectangle of a w×h image holding every box of `boxes` grown by `reach` voxels
  // (into `rect` if given); false when a box reaches the near plane (then no mask is drawn).
  bool projectedRect(const std::vector<VoxelBox>& boxes, float reach, const glm::mat4& view_proj,
                     int w, int h, glm::ivec4* rect) const;
  // The same for voxel-space points.
  bool projectedPointsRect(const std::vector<glm::vec3>& points, const glm::mat4& view_proj, int w,
                           int h, glm::ivec4* rect) const;
  // Stencil bit 2 on every pixel whose ray passes through a box of `boxes` (voxel space, grown
  // by `reach` voxels), inside the current scissor.
  void drawChangedMask(const std::vector<VoxelBox>& boxes, float reach, const glm::mat4& view_proj);
  static void deleteTargets(FrameTargets* targets);
  bool eye_near_occupied_ = false;
  RenderStats stats_;
  std::string error_;
  SkyPass sky_;
  Camera frame_camera_;  // the camera of the frame being rendered (for the sky)
};

}  // namespace cb
