// Compiled in variants (the renderer prepends #defines): CB_SKIP (ray bounds), CB_BRICK_STEPPING
// (hierarchical stepping inside them), CB_STATS (sample statistics), CB_SURFACE (the style draws
// an iso-surface instead of compositing the volume), CB_LIGHT_PREVIEW (the light from a light
// drag's coarse grid, volume_pool.glsl). Variants rather than uniform branches,
// because llvmpipe runs untaken branches' straight-line code with all lanes masked.
//
// Ray casting of the density volume (thesis §4.3, Alg. 4) with lossless empty-space skipping
// over a max-mip occupancy pyramid (the role of the octree of §4.4). Linked after a shading
// stage (shaders/README.md) that defines, for a composited (volume) style,
//   CB_SHADE                                           the type of a sample's shade: float (a
//                                                      grey stage, tinted once per ray) or vec3
//   void styleBeginRay(vec3 dir)                       once per ray (world direction, unit)
//   float styleDensity(float density, vec3 texcoord)   the density actually composited
//   CB_SHADE shadeSample(float density, float transmittance)
//   vec3 styleEndRay(CB_SHADE shade, float transmittance)  the ray's colour before the background
// or, for an iso-surface style (CB_SURFACE), `vec4 shadeSurface(SurfaceSample s)` returning a
// premultiplied colour and coverage (surface_sample.glsl, linked first, defines the struct and
// the iso levels).
// The renderer prepends the #version line.
//
// One ray per pixel from the near plane (so a camera inside the box works) through the box from
// entry to exit, samples at t_k = t_enter + (k + ½)·step in voxel units. Compositing is
// front-to-back "over" with opacity α = 1 − exp(−σ·density·step) (Beer–Lambert over the step):
//   C += T·α·shade,  T *= 1 − α,  computed as T' = T·exp(−σ·density·step), C += (T − T')·shade.
// The thesis's blend (§4.5.2: C = S·F_d + (1 − F_d)·C_pre, α += F_d) is a back-to-front "over"
// applied in front-to-back order, so its result depends on the step count and order and its
// alpha exceeds 1; the standard operator here is order-correct and converges as step → 0.
// Rays stop once T < u_cutoff (early termination).
//
// Skipping (lossless, two levels):
//  1. Ray bounds: a pass before this one rasterises the boundary faces of the occupancy pyramid
//     (dilated by one voxel) and keeps, per pixel, the nearest entry face and the farthest exit
//     face of an occupied 4³-voxel cell (ray_bounds.*.glsl). The march covers only the samples
//     between them.
//     Pixels whose rays meet no occupied cell are not shaded at all: that pass also sets a
//     stencil, tested here before shading. When the eye is in or next to an occupied cell the
//     march starts at the near plane (and every pixel is cast).
//  2. Optional hierarchical stepping (CB_BRICK_STEPPING): at a sample in an empty level-0 cell the
//     ray climbs to the coarsest empty ancestor and jumps to the first sample index past it; in
//     an occupied cell it samples every index until the cell's exit.
// The sample positions t_enter + (k + ½)·step are the same with and without skipping, and empty
// cells hold only zero densities, so the image is the same.
// Stencil (which pixels to cast) is tested before shading, statistics atomics or not.
layout(early_fragment_tests) in;
layout(location = 0) out vec4 o_colour;
#if CB_DEPTH
// The ray's transmittance-weighted depth (CB_DEPTH, temporal reprojection): Σ(T − T')·t_k over
// Σ(T − T') = 1 − T, as a world distance from the eye; u_no_depth where 1 − T < u_depth_min.
layout(location = 1) out float o_depth;
uniform float u_no_depth;
uniform float u_depth_min;
#endif

uniform mat4 u_inv_view_proj;
uniform vec2 u_viewport;      // size of the image being rendered, pixels
uniform vec2 u_jitter;        // the ray passes through the pixel centre plus this (pixels)
uniform vec3 u_world_min;
uniform vec3 u_voxel_size;    // world units per voxel
uniform usampler3D u_occupancy;
uniform int u_brick;          // voxels per level-0 occupancy cell
uniform int u_levels;         // occupancy mip levels
uniform float u_step;         // voxels per ray step
uniform float u_sigma;        // extinction per voxel at density 1
uniform float u_cutoff;       // stop when transmittance falls below this
uniform vec4 u_background;    // premultiplied
// Ray bounds from the ray bounds pass (ray_bounds.*.glsl): per pixel the eye distances of the
// nearest and farthest occupied-cell faces; used only with CB_SKIP.
uniform sampler2D u_ray_bounds;
uniform vec3 u_eye;
uniform bool u_bounds_from_near_plane;  // the eye is in (or next to) an occupied cell

#if CB_STATS
layout(std430, binding = 0) buffer RayStatistics {
  uint total_samples;
  uint max_samples;
  uint pixels;
  uint histogram[64];  // bins of 8 samples; the last bin holds everything beyond
} ray_stats;
#endif

vec3 safeInverse(vec3 d) {
  const float tiny = 1e-12;
  return 1.0 / vec3(abs(d.x) < tiny ? tiny : d.x, abs(d.y) < tiny ? tiny : d.y,
                    abs(d.z) < tiny ? tiny : d.z);
}

// Ray parameter where the ray leaves the axis-aligned cell [lo, lo + size).
float cellExit(vec3 origin, vec3 inv_dir, vec3 lo, float size) {
  vec3 far_plane = lo + step(0.0, inv_dir) * size;
  vec3 t = (far_plane - origin) * inv_dir;
  return min(min(t.x, t.y), t.z);
}

void main() {
  vec2 ndc = (gl_FragCoord.xy + u_jitter) / u_viewport * 2.0 - 1.0;
  vec4 near_h = u_inv_view_proj * vec4(ndc, -1.0, 1.0);
  vec4 far_h = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
  vec3 origin_world = near_h.xyz / near_h.w;
  vec3 dir_world = far_h.xyz / far_h.w - origin_world;

  // Voxel space: the box is [0, dims], voxel i covers [i, i+1).
  vec3 origin = (origin_world - u_world_min) / u_voxel_size;
  vec3 dir = normalize(dir_world / u_voxel_size);
  vec3 inv_dir = safeInverse(dir);
  vec3 ta = -origin * inv_dir;
  vec3 tb = (u_dims - origin) * inv_dir;
  vec3 tmin = min(ta, tb), tmax = max(ta, tb);
  float t_enter = max(max(max(tmin.x, tmin.y), tmin.z), 0.0);
  float t_exit = min(min(tmax.x, tmax.y), tmax.z);

  vec3 colour = vec3(0.0);
#if !CB_SURFACE
  CB_SHADE shade_sum = CB_SHADE(0.0);  // Σ T·α·shade
#endif
  float transmittance = 1.0;
#if CB_DEPTH && !CB_SURFACE
  float depth_sum = 0.0;  // Σ (T − T')·k, in samples
#endif
  uint samples = 0u;
  vec3 inv_dims = 1.0 / u_dims;
  ivec3 max_voxel = ivec3(u_dims) - 1;
  int k = 0;
  int n = int(ceil((t_exit - t_enter) / u_step));
#if CB_SKIP
  if (t_exit > t_enter) {
    // Narrow [k, n) to the samples between the nearest and farthest occupied faces. Sample
    // positions stay on the same grid t_enter + (k + ½)·step, so the image does not change.
    vec2 bounds = texelFetch(u_ray_bounds, ivec2(gl_FragCoord.xy), 0).rg;
    // r: nearest entry face, −g: farthest exit face of an occupied level-0 cell; 1e30 where none
    // was drawn.
    const float none = 1e29;
    const float kBoundsSlack = 1.0 / 64.0;  // samples
    // World distance from the eye -> ray parameter in voxel units from the near-plane origin.
    float voxels_per_world = length(normalize(dir_world) / u_voxel_size);
    float origin_offset = distance(origin_world, u_eye);
    if (!u_bounds_from_near_plane) {
      if (bounds.x >= none) {
        n = 0;  // the ray enters no occupied cell
      } else {
        // The first sample at or past the entry face: t_enter + (k + ½)·step ≥ t_near. Samples
        // before it lie in empty (dilated) cells and read density 0. kBoundsSlack keeps a sample
        // that float rounding of the two distances (≈ 1e-3 voxel) might put just past the face.
        float t_near = (bounds.x - origin_offset) * voxels_per_world;
        k = max(0, int(ceil((t_near - t_enter) / u_step - 0.5 - kBoundsSlack)));
      }
    }
    if (bounds.y < none) {
      // The exit keeps a margin of a sample or two past the face: narrowed like the entry it
      // changed images in dense_reference_test (the iso-surface styles read up to n for their
      // inner surface; why the thesis style's view from above changed was not looked into).
      float t_far = (-bounds.y - origin_offset) * voxels_per_world;
      n = min(n, int(ceil((t_far - t_enter) / u_step)) + 1);
    }
  }
#endif
#if CB_SURFACE
  // Iso-surface styles: march to the first sample at or above u_iso (refined linearly between
  // it and the sample before), then look u_inner_depth voxels further for the inner surface.
  bool hit = false;
  float previous_density = 0.0, hit_density = 0.0, max_density = 0.0;
  int hit_k = 0;
#else
  styleBeginRay(normalize(dir_world));
#endif
  if (t_exit > t_enter) {
    // Dense texture coordinate of sample k: base + k·delta (same positions for any start k, so
    // skipping does not move samples).
    vec3 base = (origin + (t_enter + 0.5 * u_step) * dir) * inv_dims;
    vec3 delta = dir * (u_step * inv_dims);
    // The same in fixed point (1/256 voxel, volume_pool.glsl): exactly base·dims·256 and
    // delta·dims·256 when dims are powers of two, so rounding sample k gives the position the
    // dense texture's filtering used.
    vec3 fixed_base = base * (u_dims * kFixed);
    vec3 fixed_delta = delta * (u_dims * kFixed);
#if !CB_SURFACE
    float neg_optical_depth_log2 = -u_sigma * u_step * 1.4426950408889634;
#endif
    // A do-while, not a while: llvmpipe runs a loop's body until no lane is active and tests at
    // the bottom, so a `while` costs every group of lanes one more whole body (a chunk of
    // samples, all masked) in which the test at the top stops the last lanes. Here the test
    // after the body stops them. (The `if` runs its body masked for lanes with nothing to cast;
    // it is there for other GPUs.) Measured: the fresh 1920x1080 cast 8-9 % faster.
    if (k < n) do {
      int k_end = n;
#if CB_SKIP && CB_BRICK_STEPPING
      {
        vec3 p = origin + (t_enter + (float(k) + 0.5) * u_step) * dir;
        ivec3 voxel = clamp(ivec3(floor(p)), ivec3(0), max_voxel);
        if (texelFetch(u_occupancy, voxel / u_brick, 0).r == 0u) {
          int level = 1;
          while (level < u_levels &&
                 texelFetch(u_occupancy, voxel / (u_brick << level), level).r == 0u)
            ++level;
          int size = u_brick << (level - 1);  // the coarsest empty cell around p
          float t_leave = cellExit(origin, inv_dir, vec3(voxel / size * size), float(size));
          k = max(int(ceil((t_leave - t_enter) / u_step - 0.5)), k + 1);
          continue;
        }
        float t_leave = cellExit(origin, inv_dir, vec3(voxel / u_brick * u_brick), float(u_brick));
        k_end = min(n, max(int(ceil((t_leave - t_enter) / u_step - 0.5)), k + 1));
      }
#endif
      // Samples go in chunks of CB_CHUNK (chunkSamples of the step), each read in the slot
      // of the cell holding the chunk's first corner (volume_pool.glsl): the slot's apron holds
      // the rest of the chunk. One slot lookup per chunk; the chunk is unrolled, so every ray of
      // a group llvmpipe shades in lockstep takes the same number of loop iterations as
      // without the pool.
      int chunk_end = min(k_end, k + CB_CHUNK);
      vec3 q = roundEven(fixed_base + float(k) * fixed_delta);
      PoolBrick pb =
          poolBrickAt(min(q, roundEven(fixed_base + float(chunk_end - 1) * fixed_delta)));
#if CB_SKIP
      if (pb.empty) {
        // Every sample of the chunk reads density 0: skipping them changes nothing (lossless).
#if CB_SURFACE
        previous_density = 0.0;
#endif
        k = chunk_end;
        continue;
      }
#endif
      // Per sample: one bilinear RGBA8 fetch and a lerp in z (volume_pool.glsl), one exp2, the
      // shading stage; no data-dependent branch (a zero density gives α = 0 and changes nothing)
      // because llvmpipe runs a branch's code for all lanes anyway. 1 − α =
      // 2^(−σ·step·log2(e)·density) is the Beer–Lambert transmittance of the step (§4.5.2
      // compositing, see the header); T − T' is T·α with two operations fewer (3 % of a frame).
      for (int i = 0; i < CB_CHUNK; ++i) {
#if CB_SURFACE
        if (k < chunk_end && !hit) {
          float d = sampleChunk(q, pb).r;
          ++samples;
          hit = d >= u_iso;
          hit_density = d;
          hit_k = k;
          if (!hit) {
            previous_density = d;
            max_density = max(max_density, d);
          }
          ++k;
          q = roundEven(fixed_base + float(k) * fixed_delta);
        }
#else
        // Straight-line code, no `if`: a sample past the chunk's end or after termination is
        // still read (inside the slot or clamped to it) but weighs nothing — its density is
        // multiplied by 0, so T' = T exactly and the shade and transmittance stay as they are.
        float live = float(k + i < chunk_end && transmittance >= u_cutoff);
        vec2 s = sampleChunk(roundEven(fixed_base + float(k + i) * fixed_delta), pb);
        samples += uint(live);
        float density = styleDensity(s.r, base + float(k + i) * delta) * live;
        float t_next = transmittance * exp2(neg_optical_depth_log2 * density);
#if CB_LIGHT_PREVIEW
        float light_t = previewTransmittance(base + float(k + i) * delta);
#else
        float light_t = s.g;
#endif
        shade_sum += (transmittance - t_next) * shadeSample(density, light_t);  // T·α·shade
#if CB_DEPTH
        depth_sum += (transmittance - t_next) * float(k + i);
#endif
        transmittance = t_next;
#endif
      }
#if !CB_SURFACE
      k = chunk_end;
#endif
#if CB_SURFACE
      if (hit) k = n;
#else
      if (transmittance < u_cutoff) k = n;  // early termination: leave the outer loop too
#endif
    } while (k < n);
  }
#if CB_SURFACE
  SurfaceSample surface;
  surface.hit = hit;
  surface.max_density = max_density;
  surface.view = -normalize(dir_world);
  surface.normal = surface.view;
  surface.light_transmittance = 1.0;
  surface.inner_max_density = 0.0;
  if (hit) {
    vec3 base = (origin + (t_enter + 0.5 * u_step) * dir) * inv_dims;
    vec3 delta = dir * (u_step * inv_dims);
    float rise = max(hit_density - previous_density, 1e-6);
    float f = clamp((u_iso - previous_density) / rise, 0.0, 1.0);  // between samples k−1 and k
    vec3 p = base + (float(hit_k) - 1.0 + f) * delta;
    // Central differences u_gradient_voxels apart (wider on finer grids, so the normal follows
    // the cloud's shape rather than its voxel-scale noise); the outward normal points down the
    // density gradient.
    vec3 h = u_gradient_voxels * inv_dims;
    vec3 gradient = vec3(sampleVolume(p + vec3(h.x, 0, 0)).r - sampleVolume(p - vec3(h.x, 0, 0)).r,
                         sampleVolume(p + vec3(0, h.y, 0)).r - sampleVolume(p - vec3(0, h.y, 0)).r,
                         sampleVolume(p + vec3(0, 0, h.z)).r - sampleVolume(p - vec3(0, 0, h.z)).r);
    vec3 g_world = gradient / u_voxel_size;
    surface.normal = dot(g_world, g_world) > 1e-12 ? -normalize(g_world) : surface.view;
#if CB_LIGHT_PREVIEW
    surface.light_transmittance = previewTransmittance(p);
#else
    surface.light_transmittance = sampleVolume(p).g;
#endif
    // Inner surface (seed 003 §5): the largest density within u_inner_depth voxels behind the
    // hit; it equals u_inner_iso where the ray grazes the inner surface (its silhouette). Read
    // smoothed over about 3 voxels (the pool's companion, volume_pool.glsl: the mean of the 8
    // voxels ±1 on each axis): the seed's inner surface is shrunken particles, a body, while a
    // painted cloud's edges hold single voxels of the scattered edge samples (thesis §6.6.2)
    // whose unfiltered contours at u_inner_iso drew broken rectangles and dots across the cloud
    // at 1920×1080.
    // Read in chunks of CB_CHUNK steps, one slot lookup each, as the march reads.
    int inner_end = min(n, hit_k + 1 + int(u_inner_depth / u_step));
    float inner = 0.0;
    vec3 fixed_base = base * (u_dims * kFixed), fixed_delta = delta * (u_dims * kFixed);
    int j = hit_k;
    do {  // a do-while, as the march (llvmpipe's extra masked body)
      int chunk_end = min(inner_end, j + CB_CHUNK);
      PoolBrick pb = poolBrickAt(min(roundEven(fixed_base + float(j) * fixed_delta),
                                     roundEven(fixed_base + float(chunk_end - 1) * fixed_delta)));
      for (int i = 0; i < CB_CHUNK; ++i) {
        // Straight-line code: a step past the chunk's end is read (clamped to the slot) and
        // weighs nothing.
        float d = poolFetchSmooth(
            clamp(roundEven(fixed_base + float(j + i) * fixed_delta) + pb.to_pool, pb.lo, pb.hi));
        inner = max(inner, j + i < chunk_end ? d : 0.0);
      }
      j = chunk_end;
    } while (j < inner_end);
    samples += uint(max(inner_end - hit_k, 1)) + 7u;
    surface.inner_max_density = inner;
  }
  vec4 shaded = shadeSurface(surface);
  colour = shaded.rgb;
  transmittance = 1.0 - shaded.a;
#else
  colour = styleEndRay(shade_sum, transmittance);
#endif
#if CB_STATS
  atomicAdd(ray_stats.total_samples, samples);
  atomicMax(ray_stats.max_samples, samples);
  atomicAdd(ray_stats.pixels, 1u);
  atomicAdd(ray_stats.histogram[min(samples / 8u, 63u)], 1u);
#endif
#if CB_DEPTH
  {
#if CB_SURFACE
    float weight = hit ? 1.0 : 0.0;
    float k_mean = float(hit_k);
#else
    float weight = 1.0 - transmittance;
    float k_mean = depth_sum / max(weight, 1e-6);
#endif
    vec3 at = u_world_min + (origin + (t_enter + (k_mean + 0.5) * u_step) * dir) * u_voxel_size;
    o_depth = weight >= u_depth_min ? distance(at, u_eye) : u_no_depth;
  }
#endif
  o_colour = vec4(colour + transmittance * u_background.rgb,
                  1.0 - transmittance + transmittance * u_background.a);
}
