#version 450 core
// Temporal reprojection (app/render/temporal_reprojection.h; Schneider, "The real-time volumetric
// cloudscapes of Horizon Zero Dawn", SIGGRAPH 2015): a full frame from a cast of one pixel in
// f×f and the previous full frame.
//
// One invocation per quad of the cast: quad i holds the full pixels from cast pixel i (full
// pixel f·i + u_phase) up to, not including, cast pixel i + 1: an f×f block, written with image
// stores. What is the same for the block — its 2×2 cast pixels, their depths and (moving) the
// block's motion — is read and computed once, not once per full pixel (on llvmpipe the per-pixel
// fragment pass spent most of its time on those reads). The quads from −1 hold the pixels before
// the first cast pixel (their cast neighbours clamped to the image).
//
// Compiled once per case the CPU knows before the pass (CB_REPROJECT_MODE), so each program
// holds only its case's work:
//  0 fresh (no history): the cast image upsampled (bilinear between the 2×2 cast pixels
//    around p, their nearest depth), cast pixels as cast.
//  1 at rest (the same camera as the previous frame): cast pixels as cast, the others the
//    history texel for texel, never clamped, so after f² frames every pixel holds its own cast
//    (outside u_reject, pixels a volume change made stale: there the fresh upsample).
//  2 moving: the block's world point — the eye plus the ray through the block's centre times
//    the nearest depth of its 2×2 (transmittance-weighted depths, so a cloud's inside moves with
//    the cloud; the background: a direction, at infinity) — projected through the previous
//    camera gives the block's motion, and each pixel reads the history at its own place plus
//    that motion (the nearest texel) when that place is on the previous frame, outside u_reject
//    (pixels a volume change made stale), the 2×2 is all cloud or all background (a soft edge
//    against the sky is the fresh upsample: reprojected, its translucent rim drifts outward into
//    dots around the cast pixels), the point is in front of the previous camera, and the
//    history's depth there agrees with the point's distance from the previous eye within
//    u_depth_tolerance (else: disocclusion). The history is clamped to the colour range of the
//    2×2 cast pixels (it cannot hold what the fresh cast around it does not show: no ghost
//    trails), narrowed around their bilinear upsample (CB_CLAMP_SPREAD).
// A cast pixel's colour is its cast texel in every program (bilinear weights (1, 0, 0, 0)) and
// its depth its own.
layout(local_size_x = 8, local_size_y = 8) in;

// The clamp box's half-width around the fresh upsample, as a fraction of the 2×2's range: a
// history displaced by a rim's uncertain depth (up to the whole range at a soft edge, a band of
// dots around the cast pixels) shows at most this much of it. Looked at on 3°-a-frame orbits
// (1920×1080, 1 in 16 cast): 1 (the plain range) stippled the rim and set it ~6 pixels outward,
// 0.25 leaves a faint trace, 0.1 is smooth but keeps little of the history; the orbit error
// (temporal_reprojection_test, f = 4, 3° a frame) 1.52 → 1.15 mean with 0.25, 0.2° unchanged.
#define CB_CLAMP_SPREAD 0.25
#ifndef CB_REPROJECT_MODE
#define CB_REPROJECT_MODE 2
#endif

// The frame: its colour, and each pixel's depth (distance from the eye; ≥ u_no_depth · ½: none)
// for the next frame's history.
layout(rgba8, binding = 0) uniform writeonly image2D u_out_colour;
layout(r32f, binding = 1) uniform writeonly image2D u_out_depth;

uniform sampler2D u_cast;           // this frame's cast: texel i is full pixel f·i + u_phase
uniform sampler2D u_cast_depth;     // its depths
uniform sampler2D u_history;        // the previous frame's colour
uniform sampler2D u_history_depth;  // and its depths (from the previous eye)
uniform int u_factor;               // f
uniform ivec2 u_phase;
uniform ivec2 u_cast_last;  // the cast image's last texel (its size − 1)
uniform ivec2 u_size;       // full frame, pixels
uniform ivec4 u_reject;     // x, y, width, height: history there is stale
uniform float u_depth_tolerance;
uniform float u_no_depth;
// Moving: the world direction (unnormalised) through the bottom-left corner of the screen and
// its change across the width and the height; the previous camera.
uniform vec3 u_ray_origin;
uniform vec3 u_ray_dx;
uniform vec3 u_ray_dy;
uniform mat4 u_prev_view_proj;
uniform vec3 u_eye;
uniform vec3 u_prev_eye;

void main() {
  ivec2 i0 = ivec2(gl_GlobalInvocationID.xy) - 1;
  ivec2 base = u_factor * i0 + u_phase;  // the full pixel of cast pixel i0
  if (any(greaterThanEqual(base, u_size))) return;
  ivec2 a = clamp(i0, ivec2(0), u_cast_last), b = clamp(i0 + 1, ivec2(0), u_cast_last);
  vec4 c00 = texelFetch(u_cast, a, 0), c10 = texelFetch(u_cast, ivec2(b.x, a.y), 0);
  vec4 c01 = texelFetch(u_cast, ivec2(a.x, b.y), 0), c11 = texelFetch(u_cast, b, 0);
  float own = texelFetch(u_cast_depth, a, 0).x;
  float d10 = texelFetch(u_cast_depth, ivec2(b.x, a.y), 0).x;
  float d01 = texelFetch(u_cast_depth, ivec2(a.x, b.y), 0).x;
  float d11 = texelFetch(u_cast_depth, b, 0).x;
  float nearest = min(min(own, d10), min(d01, d11));
#if CB_REPROJECT_MODE == 2
  float farthest = max(max(own, d10), max(d01, d11));
  bool far = nearest >= u_no_depth * 0.5;
  bool mixed = !far && farthest >= u_no_depth * 0.5;
  // The block's centre in full pixels: cast pixel i's centre is full pixel f·i + phase's.
  vec2 centre = float(u_factor) * (vec2(i0) + 0.5) + vec2(u_phase) + 0.5;
  vec2 uv = centre / vec2(u_size);
  vec3 dir = normalize(u_ray_origin + uv.x * u_ray_dx + uv.y * u_ray_dy);
  vec3 world = u_eye + dir * nearest;
  vec4 prev = u_prev_view_proj * (far ? vec4(dir, 0.0) : vec4(world, 1.0));
  vec2 motion = (prev.xy / max(prev.w, 1e-6) * 0.5 + 0.5) * vec2(u_size) - centre;
  float expected = far ? u_no_depth : distance(world, u_prev_eye);
  bool usable = prev.w > 1e-6 && !mixed;
  vec4 lo4 = min(min(c00, c10), min(c01, c11)), hi4 = max(max(c00, c10), max(c01, c11));
  vec4 spread = (hi4 - lo4) * CB_CLAMP_SPREAD;
#endif
  for (int y = 0; y < u_factor; ++y) {
    for (int x = 0; x < u_factor; ++x) {
      ivec2 p = base + ivec2(x, y);
      if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, u_size))) continue;
      // p's bilinear weights between the 2×2 (k/f exactly).
      vec2 f = vec2(x, y) / float(u_factor);
      bool cast_here = x == 0 && y == 0;
      vec4 fresh = mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
      float d = cast_here ? own : nearest;
      bool rejected = all(greaterThanEqual(p, u_reject.xy)) &&
                      all(lessThan(p, u_reject.xy + u_reject.zw));
#if CB_REPROJECT_MODE == 0
      vec4 colour = fresh;
      float depth = d;
#elif CB_REPROJECT_MODE == 1
      bool keep = !cast_here && !rejected;
      vec4 colour = keep ? texelFetch(u_history, p, 0) : fresh;
      float depth = keep ? texelFetch(u_history_depth, p, 0).x : d;
#else
      vec2 prev_px = vec2(p) + 0.5 + motion;
      bool on_screen =
          all(greaterThanEqual(prev_px, vec2(0.0))) && all(lessThan(prev_px, vec2(u_size)));
      ivec2 q = clamp(ivec2(prev_px), ivec2(0), u_size - 1);
      vec4 history = texelFetch(u_history, q, 0);
      float history_depth = texelFetch(u_history_depth, q, 0).x;
      bool history_far = history_depth >= u_no_depth * 0.5;
      bool keep = usable && on_screen && !rejected && far == history_far &&
                  (far || abs(history_depth - expected) <= u_depth_tolerance * expected);
      vec4 lo = max(lo4, fresh - spread), hi = min(hi4, fresh + spread);
      vec4 colour = cast_here ? c00 : (keep ? clamp(history, lo, hi) : fresh);
      float depth = cast_here || !keep ? d : (far ? u_no_depth : d + (history_depth - expected));
#endif
      imageStore(u_out_colour, p, colour);
      imageStore(u_out_depth, p, vec4(depth));
    }
  }
}
