#version 450 core
// The painting-mode frame (thesis §3.3, §5.3.1 Fig. 5.6): the cached rendered scene, the live
// stroke footprint over it, and the pen cursor. Drawn with fullscreen.vert.glsl.
in vec2 v_uv;  // 0..1, v = 0 at the bottom
out vec4 frag_colour;

uniform sampler2D u_scene;      // the cached scene (GL orientation: row 0 at the bottom)
uniform sampler2D u_footprint;  // R32F, uploaded with row 0 = the footprint's top row
uniform vec2 u_target_size;     // framebuffer size in pixels
uniform vec3 u_ink_colour;
uniform float u_ink_opacity;
uniform vec2 u_cursor_px;       // screen pixels, y down
uniform float u_cursor_radius_px;
uniform float u_cursor_width_px;
uniform vec4 u_cursor_colour;   // a = 0 hides the cursor

void main() {
  vec3 scene = texture(u_scene, v_uv).rgb;
  float ink = clamp(texture(u_footprint, vec2(v_uv.x, 1.0 - v_uv.y)).r, 0.0, 1.0);
  vec3 colour = mix(scene, u_ink_colour, ink * u_ink_opacity);
  vec2 px = vec2(gl_FragCoord.x, u_target_size.y - gl_FragCoord.y);
  float ring = abs(length(px - u_cursor_px) - u_cursor_radius_px);
  float cursor = clamp(0.5 * u_cursor_width_px - ring + 0.5, 0.0, 1.0) * u_cursor_colour.a;
  frag_colour = vec4(mix(colour, u_cursor_colour.rgb, cursor), 1.0);
}
