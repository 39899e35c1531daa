// HUD overlay: solid rectangles, rings (|distance to centre - radius| <= width/2) and line
// segments (distance to the segment <= width/2), tested at the pixel centre, no blending tricks.
struct HudItem {
  vec4 rect;
  vec4 colour;
  vec4 p0;  // ring: (1, cx, cy, radius); segment: (2, ax, ay, 0)
  vec4 p1;  // ring: (width, 0, 0, 0);     segment: (width, bx, by, 0)
};
layout(std430, binding = 0) readonly buffer HudItems { HudItem items[]; };
uniform vec2 u_viewport;
flat in int v_item;
out vec4 frag_colour;

void main() {
  HudItem item = items[v_item];
  vec2 p = vec2(gl_FragCoord.x, u_viewport.y - gl_FragCoord.y);  // pixel centre, y down
  int kind = int(item.p0.x + 0.5);
  float half_width = 0.5 * item.p1.x;
  if (kind == 1) {
    if (abs(length(p - item.p0.yz) - item.p0.w) > half_width) discard;
  } else if (kind == 2) {
    vec2 a = item.p0.yz, b = item.p1.yz;
    vec2 ab = b - a;
    float t = clamp(dot(p - a, ab) / max(dot(ab, ab), 1e-6), 0.0, 1.0);
    if (length(p - (a + t * ab)) > half_width) discard;
  }
  frag_colour = item.colour;
}
