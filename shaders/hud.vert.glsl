// HUD overlay (app/render/hud_overlay.h): one instanced quad per item, covering the item's
// bounding rectangle in screen pixels (y down), or for a segment a quad along it. Items come
// from a storage buffer.
struct HudItem {
  vec4 rect;    // x0, y0, x1, y1 in pixels, y down
  vec4 colour;  // straight alpha
  vec4 p0;      // kind (0 rect, 1 ring, 2 segment), then shape parameters
  vec4 p1;
};
layout(std430, binding = 0) readonly buffer HudItems { HudItem items[]; };
uniform vec2 u_viewport;  // width, height in pixels
flat out int v_item;

void main() {
  HudItem item = items[gl_InstanceID];
  vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
  vec2 px = mix(item.rect.xy, item.rect.zw, corner);
  if (int(item.p0.x + 0.5) == 2) {
    // A segment: a quad along it (a width beyond each end and side), not its bounding box, so
    // a long diagonal costs its own pixels only.
    vec2 a = item.p0.yz, b = item.p1.yz;
    vec2 along = b - a;
    along = dot(along, along) > 1e-12 ? normalize(along) : vec2(1.0, 0.0);
    vec2 across = vec2(-along.y, along.x);
    float reach = item.p1.x;
    px = mix(a - reach * along, b + reach * along, corner.x) + (corner.y * 2.0 - 1.0) * reach * across;
  }
  gl_Position = vec4(px.x / u_viewport.x * 2.0 - 1.0, 1.0 - px.y / u_viewport.y * 2.0, 0.0, 1.0);
  v_item = gl_InstanceID;
}
