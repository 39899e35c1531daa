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

// The inner surface's silhouette (seed 003 §5), 0…1, shared by cartoon and sketch: rays whose
// largest density behind the hit comes within ±0.06 of u_inner_iso graze it, drawn at most two
// pixels wide (that density's change to the next pixel, fwidth). A painted cloud's interior stays
// near u_inner_iso over wide areas, which without the width limit drew solid patches (dark in the
// cartoon, graphite grey in the sketch) instead of lines.
float innerSilhouette(SurfaceSample s) {
  float off = abs(s.inner_max_density - u_inner_iso);
  return (1.0 - smoothstep(0.03, 0.06, off)) *
         (1.0 - smoothstep(1.0, 2.0, off / max(fwidth(s.inner_max_density), 1e-4)));
}
