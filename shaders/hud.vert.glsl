// HUD overlay (app/render/hud_overlay.h): one instanced quad per item, covering the item's
// bounding rectangle given in screen pixels (y down). Items come from a storage buffer.
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
  gl_Position = vec4(px.x / u_viewport.x * 2.0 - 1.0, 1.0 - px.y / u_viewport.y * 2.0, 0.0, 1.0);
  v_item = gl_InstanceID;
}
