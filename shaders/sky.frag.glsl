#version 450 core
// The sky pass: fills the frame (or the scissored region) with skyColour (sky.glsl, linked
// first) of each pixel's view ray; the cloud is then composited over it.
layout(location = 0) out vec4 o_colour;
uniform mat4 u_inv_view_proj;
uniform vec2 u_viewport;  // pixels of the image being drawn

void main() {
  vec2 ndc = gl_FragCoord.xy / u_viewport * 2.0 - 1.0;
  vec4 near_h = u_inv_view_proj * vec4(ndc, -1.0, 1.0);
  vec4 far_h = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
  vec3 dir = normalize(far_h.xyz / far_h.w - near_h.xyz / near_h.w);
  o_colour = vec4(skyColour(dir, gl_FragCoord.xy * (u_sky_frame_size / u_viewport)), 1.0);
}
