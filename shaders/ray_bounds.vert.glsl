// Ray bounds pass: the boundary faces of the occupied occupancy cells (voxel coordinates),
// rasterised so each pixel learns where its ray enters and leaves occupied space.
layout(location = 0) in vec3 a_voxel;

uniform mat4 u_view_proj;
uniform vec3 u_world_min;
uniform vec3 u_voxel_size;

out vec3 v_world;

void main() {
  v_world = u_world_min + a_voxel * u_voxel_size;
  gl_Position = u_view_proj * vec4(v_world, 1.0);
}
