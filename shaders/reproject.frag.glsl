#version 450 core
// Temporal reprojection (app/render/temporal_reprojection.h; Schneider, "The real-time volumetric
// cloudscapes of Horizon Zero Dawn", SIGGRAPH 2015): a full frame from a cast of one pixel in
// f×f and the previous full frame.
//
// Compiled three times, one program per case the CPU knows before the pass (CB_REPROJECT_MODE):
// llvmpipe runs a fragment shader's branches for every pixel of its 8-wide group, so each
// program holds only its case's work, as straight-line code with selects; the moving case's
// per-pixel arithmetic (a ray, a matrix, a distance) is done once per cast quad instead.
//  0 fresh (no history): the cast image upsampled (bilinear between the 2×2 cast pixels
//    around p, their nearest depth), cast pixels as cast.
//  1 at rest (the same camera as the previous frame): cast pixels as cast, the others the
//    history texel for texel, never clamped, so after f² frames every pixel holds its own cast
//    (outside u_reject, pixels a volume change made stale: there the fresh upsample).
//  2 moving: a pixel not cast this frame is moved by the motion of the 2×2 cast pixels around
//    it (shaders/reproject_motion.frag.glsl: their nearest depth's world point through the
//    previous camera, once per quad) and reads the history there (the nearest texel) when that
//    place is on the previous frame, outside u_reject (pixels a volume change made stale), the
//    quad is all cloud or all background (a soft edge against the sky is the fresh upsample:
//    reprojected, its translucent rim drifts outward into dots around the cast pixels), and the
//    history's depth there agrees with the expected one within u_depth_tolerance (else:
//    disocclusion). The history is clamped to the colour range of the 2×2 cast pixels (it
//    cannot hold what the fresh cast around it does not show: no ghost trails), narrowed
//    around their bilinear upsample (CB_CLAMP_SPREAD).
// A cast pixel's colour is its cast texel in every program: the bilinear weights of the 2×2
// are exactly (1, 0, 0, 0) there, and its depth is the gathered texel of its own.
layout(location = 0) out vec4 o_colour;
// The frame again with its depths, for the next frame's history: colour (unpackUnorm4x8) and
// depth (floatBitsToUint) in one texel, so a pixel's history is one fetch.
layout(location = 1) out uvec2 o_history;

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

uniform sampler2D u_cast;        // this frame's cast: texel i is full pixel f·i + u_phase
uniform sampler2D u_cast_depth;  // its depths (world distance from the eye; ≥ u_no_depth: none)
uniform usampler2D u_history;    // the previous frame's o_history (depths from the previous eye)
uniform int u_factor;            // f
uniform ivec2 u_phase;
uniform ivec2 u_cast_last;  // the cast image's last texel (its size − 1)
uniform vec2 u_size;        // full frame, pixels
uniform sampler2D u_motion;  // per 2×2 quad of the cast (shaders/reproject_motion.frag.glsl)
uniform ivec4 u_reject;  // x, y, width, height: history there is stale
uniform float u_depth_tolerance;
uniform float u_no_depth;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  // The 2×2 cast pixels around p's centre and p's bilinear weights between them; a cast pixel
  // sits exactly on its texel (weights (1, 0, 0, 0)).
  vec2 c = vec2(p - u_phase) / float(u_factor);
  ivec2 i0 = ivec2(floor(c));
  vec2 f = c - vec2(i0);
  bool cast_here = f.x == 0.0 && f.y == 0.0;
  ivec2 a = clamp(i0, ivec2(0), u_cast_last), b = clamp(i0 + 1, ivec2(0), u_cast_last);
  vec4 c00 = texelFetch(u_cast, a, 0), c10 = texelFetch(u_cast, ivec2(b.x, a.y), 0);
  vec4 c01 = texelFetch(u_cast, ivec2(a.x, b.y), 0), c11 = texelFetch(u_cast, b, 0);
  vec4 fresh = mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
  // The four depths in one gather (w is texel i0; edges clamped by the sampler).
  vec4 depths = textureGather(u_cast_depth, (vec2(i0) + 1.0) / vec2(u_cast_last + 1), 0);
  float nearest = min(min(depths.x, depths.y), min(depths.z, depths.w));
  float d = cast_here ? depths.w : nearest;
  bool rejected = all(greaterThanEqual(p, u_reject.xy)) &&
                  all(lessThan(p, u_reject.xy + u_reject.zw));
#if CB_REPROJECT_MODE == 0
  vec4 colour = fresh;
  float depth = d;
#elif CB_REPROJECT_MODE == 1
  bool keep = !cast_here && !rejected;
  uvec2 history = texelFetch(u_history, p, 0).xy;
  vec4 colour = keep ? unpackUnorm4x8(history.x) : fresh;
  float depth = keep ? uintBitsToFloat(history.y) : d;
#else
  // The quad's motion (shaders/reproject_motion.frag.glsl): this pixel's place in the previous
  // frame and the depth its history must have there.
  vec4 motion = texelFetch(u_motion, a, 0);
  bool far = d >= u_no_depth * 0.5;
  vec2 prev_px = vec2(p) + 0.5 + motion.xy;
  bool on_screen = all(greaterThanEqual(prev_px, vec2(0.0))) && all(lessThan(prev_px, u_size));
  uvec2 h = texelFetch(u_history, clamp(ivec2(prev_px), ivec2(0), ivec2(u_size) - 1), 0).xy;
  vec4 history = unpackUnorm4x8(h.x);
  float history_depth = uintBitsToFloat(h.y);
  bool history_far = history_depth >= u_no_depth * 0.5;
  float expected = motion.z;
  bool keep = expected >= 0.0 && on_screen && !rejected && far == history_far &&
              (far || abs(history_depth - expected) <= u_depth_tolerance * expected);
  vec4 lo = min(min(c00, c10), min(c01, c11)), hi = max(max(c00, c10), max(c01, c11));
  vec4 spread = (hi - lo) * CB_CLAMP_SPREAD;
  lo = max(lo, fresh - spread);
  hi = min(hi, fresh + spread);
  vec4 colour = cast_here ? c00 : (keep ? clamp(history, lo, hi) : fresh);
  float depth = cast_here || !keep ? d : (far ? u_no_depth : d + (history_depth - expected));
#endif
  o_colour = colour;
  o_history = uvec2(packUnorm4x8(colour), floatBitsToUint(depth));
}
