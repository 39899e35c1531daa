#version 450 core
// The motion of each 2×2 quad of the reprojection's cast image (app/render/temporal_reprojection.h,
// shaders/reproject.frag.glsl), computed once per quad instead of per full-frame pixel: texel i
// is the quad of cast pixels i .. i + 1 and describes the full pixels between their centres.
// Its world point is the eye plus the ray through the quad's centre times the depth nearest the
// eye of the quad (the transmittance-weighted depths, so a cloud's inside moves with the cloud),
// projected through the previous frame's camera (no depth, the background: a direction, at
// infinity). A camera's motion moves the pixels of a quad (4 full pixels across) alike, so
// each pixel's place in the previous frame is its own plus the quad's motion.
//   xy: the motion in full pixels (previous − current);
//   z:  the point's expected depth in the previous frame (its distance from the previous eye;
//       u_no_depth for the background), or −1: no history for this quad — the point is behind
//       the previous camera, or the quad is mixed (cloud and background: at a cloud's soft edge
//       the weighted depth of the translucent rim does not say where its colour moves, and a
//       reprojected rim drifts outward frame by frame into dots around the cast pixels);
//   w:  the quad's nearest depth (≥ u_no_depth · ½: none).
layout(location = 0) out vec4 o_motion;

uniform sampler2D u_cast_depth;  // the cast's depths (world distance from the eye)
uniform int u_factor;            // f
uniform ivec2 u_phase;
uniform ivec2 u_cast_last;  // the cast image's last texel
uniform vec2 u_size;        // the full frame, pixels
uniform vec3 u_ray_origin;  // the world direction (unnormalised) through the bottom-left corner
uniform vec3 u_ray_dx;      // its change across the width
uniform vec3 u_ray_dy;      // and the height
uniform mat4 u_prev_view_proj;
uniform vec3 u_eye;
uniform vec3 u_prev_eye;
uniform float u_no_depth;

void main() {
  ivec2 i = ivec2(gl_FragCoord.xy);
  // The four depths in one gather (texels i + (0..1, 0..1), edges clamped by the sampler).
  vec4 depths = textureGather(u_cast_depth, (vec2(i) + 1.0) / vec2(u_cast_last + 1), 0);
  float d = min(min(depths.x, depths.y), min(depths.z, depths.w));
  bool far = d >= u_no_depth * 0.5;
  bool mixed = !far && max(max(depths.x, depths.y), max(depths.z, depths.w)) >= u_no_depth * 0.5;
  // The quad's centre in full pixels: cast pixel i's centre is full pixel f·i + phase's.
  vec2 centre = float(u_factor) * (vec2(i) + 0.5) + vec2(u_phase) + 0.5;
  vec2 uv = centre / u_size;
  vec3 dir = normalize(u_ray_origin + uv.x * u_ray_dx + uv.y * u_ray_dy);
  vec3 world = u_eye + dir * d;
  vec4 prev = u_prev_view_proj * (far ? vec4(dir, 0.0) : vec4(world, 1.0));
  vec2 prev_px = (prev.xy / max(prev.w, 1e-6) * 0.5 + 0.5) * u_size;
  float expected = far ? u_no_depth : distance(world, u_prev_eye);
  bool usable = prev.w > 1e-6 && !mixed;
  o_motion = vec4(prev_px - centre, usable ? expected : -1.0, d);
}
