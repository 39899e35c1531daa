// What the ray caster (raycast.frag.glsl, CB_SURFACE) hands an iso-surface style's
// `vec4 shadeSurface(SurfaceSample s)`: linked before the shading stage. World-space vectors.
struct SurfaceSample {
  bool hit;                   // the ray reached density u_iso
  vec3 normal;                // outward unit normal at the hit (−∇density), else = view
  vec3 view;                  // unit vector from the surface towards the eye
  float light_transmittance;  // light volume at the hit (§4.5, Alg. 5), 1 without a hit
  float max_density;          // largest density sampled before the hit (the whole ray on a miss)
  float inner_max_density;    // largest density (smoothed over ~3 voxels) within u_inner_depth
                              // voxels behind the hit
};

uniform float u_iso;              // density of the outer iso-surface
uniform float u_inner_iso;        // density of the inner (detail) surface
uniform float u_inner_depth;      // voxels searched behind the outer hit for the inner surface
uniform float u_gradient_voxels;  // central-difference spacing of the normal, voxels
