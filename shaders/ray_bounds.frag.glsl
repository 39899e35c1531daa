// Ray bounds pass: distance from the eye to each face fragment, written as (d, ∞) for entry
// (front) faces and (∞, −d) for exit (back) faces into an RG32F target blended with MIN, so
// r = nearest entry and −g = farthest exit distance per pixel (∞ = 1e30 where none).
in vec3 v_world;

uniform vec3 u_eye;

layout(location = 0) out vec2 o_bounds;

void main() {
  float d = distance(v_world, u_eye);
  // Front faces are where rays enter occupied cells (nearest wanted), back faces where they
  // leave (farthest wanted); the other channel gets a value the MIN blend ignores.
  const float none = 1e30;
  o_bounds = gl_FrontFacing ? vec2(d, none) : vec2(none, -d);
}
