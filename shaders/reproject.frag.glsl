#version 450 core
// Temporal reprojection (app/render/temporal_reprojection.h; Schneider, "The real-time volumetric
// cloudscapes of Horizon Zero Dawn", SIGGRAPH 2015): a full frame from a cast of one pixel in
// f×f and the previous full frame.
//
// Pixel p of the full frame is either
//  - cast this frame (p mod f = u_phase): the cast image's texel p / f, colour and depth as cast;
//  - or reprojected: its world point is the eye plus its ray times the depth nearest the eye of
//    the 2×2 cast pixels around it (the transmittance-weighted depths, so a cloud's edge moves
//    with the cloud), projected through the previous frame's camera (a pixel without depth, the
//    background, is a direction: at infinity). The history is read there (bilinear) if that
//    point is on the previous frame, outside u_reject (pixels a volume change made stale), and
//    the history's depth there agrees with the point's distance from the previous eye within
//    u_depth_tolerance (else: disocclusion). While the camera moves the history is clamped to
//    the colour range of the 2×2 cast pixels (it cannot hold what the fresh cast around it does
//    not show: no ghost trails). Without usable history: the cast image upsampled (bilinear).
//  - With u_static (the same camera as the previous frame) the history is read texel for texel
//    and never clamped, so after f² frames at rest every pixel holds its own cast exactly.
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;

uniform sampler2D u_cast;           // this frame's cast: texel i is full pixel f·i + u_phase
uniform sampler2D u_cast_depth;     // its depths (world distance from the eye; ≥ u_no_depth: none)
uniform sampler2D u_history;        // the previous full frame (bilinear)
uniform sampler2D u_history_depth;  // its depths (from the previous eye)
uniform int u_factor;               // f
uniform ivec2 u_phase;
uniform vec2 u_size;  // full frame, pixels
uniform vec3 u_ray_origin;  // the world direction (unnormalised) through the bottom-left corner
uniform vec3 u_ray_dx;      // its change across the width
uniform vec3 u_ray_dy;      // and the height
uniform mat4 u_prev_view_proj;
uniform vec3 u_eye;
uniform vec3 u_prev_eye;
uniform bool u_history_valid;
uniform bool u_static;
uniform ivec4 u_reject;  // x, y, width, height: history there is stale
uniform float u_depth_tolerance;
uniform float u_no_depth;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 block = p / u_factor;
  if (p - block * u_factor == u_phase) {
    o_colour = texelFetch(u_cast, block, 0);
    o_depth = texelFetch(u_cast_depth, block, 0).r;
    return;
  }
  // The 2×2 cast pixels around p's centre and p's bilinear weights between them.
  ivec2 last = textureSize(u_cast, 0) - 1;
  vec2 c = (vec2(p) + 0.5 - vec2(u_phase) - 0.5) / float(u_factor);
  ivec2 i0 = ivec2(floor(c));
  vec2 f = c - vec2(i0);
  ivec2 a = clamp(i0, ivec2(0), last), b = clamp(i0 + 1, ivec2(0), last);
  vec4 c00 = texelFetch(u_cast, a, 0), c10 = texelFetch(u_cast, ivec2(b.x, a.y), 0);
  vec4 c01 = texelFetch(u_cast, ivec2(a.x, b.y), 0), c11 = texelFetch(u_cast, b, 0);
  vec4 fresh = mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
  // The four depths in one gather (texels i0 + (0..1, 0..1), edges clamped by the sampler).
  vec4 depths = textureGather(u_cast_depth, (vec2(i0) + 1.0) / vec2(last + 1), 0);
  float d = min(min(depths.x, depths.y), min(depths.z, depths.w));
  bool far = d >= u_no_depth * 0.5;
  o_colour = fresh;
  o_depth = d;
  if (!u_history_valid) return;
  bool rejected = p.x >= u_reject.x && p.y >= u_reject.y && p.x < u_reject.x + u_reject.z &&
                  p.y < u_reject.y + u_reject.w;
  if (rejected) return;
  if (u_static) {
    o_colour = texelFetch(u_history, p, 0);
    o_depth = texelFetch(u_history_depth, p, 0).r;
    return;
  }
  // The ray's direction is linear across the screen: the corner rays interpolated (cheaper on
  // llvmpipe than unprojecting two points per pixel).
  vec2 uv = (vec2(p) + 0.5) / u_size;
  vec3 dir = normalize(u_ray_origin + uv.x * u_ray_dx + uv.y * u_ray_dy);
  vec3 world = u_eye + dir * (far ? 0.0 : d);
  vec4 prev = u_prev_view_proj * (far ? vec4(dir, 0.0) : vec4(world, 1.0));
  if (prev.w <= 1e-6) return;
  vec2 prev_px = (prev.xy / prev.w * 0.5 + 0.5) * u_size;
  if (any(lessThan(prev_px, vec2(0.0))) || any(greaterThanEqual(prev_px, u_size))) return;
  float history_depth = texelFetch(u_history_depth, ivec2(prev_px), 0).r;
  bool history_far = history_depth >= u_no_depth * 0.5;
  float expected = far ? u_no_depth : distance(world, u_prev_eye);
  if (far != history_far) return;  // disocclusion: a cloud edge crossed this pixel
  if (!far && abs(history_depth - expected) > u_depth_tolerance * expected) return;
  vec4 history = texture(u_history, prev_px / u_size);
  vec4 lo = min(min(c00, c10), min(c01, c11)), hi = max(max(c00, c10), max(c01, c11));
  o_colour = clamp(history, lo, hi);
  o_depth = far ? u_no_depth : d + (history_depth - expected);
}
