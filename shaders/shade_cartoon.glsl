// Shading stage: cartoon clouds after Álvarez et al. (seed 003, §4–5), on the iso-surface of the
// density (the seed's implicit surface F(q) = Σ Dᵢ(q) − T = 0 is our density = u_iso).
//  - Cel bands (§4, up to 32 gradations from a 1D texture in the seed): four flat tones chosen
//    by d = N·L times 0.35 + 0.65·T, T the light volume's transmittance (self-shadowing that
//    darkens but does not blacken, as in shade_ink.glsl), tinted by the sun.
//  - Outline: where the surface turns away from the eye (|N·V| < 0.3) and, just outside it, on
//    rays whose largest density comes within 40% of the iso level (a line from the density
//    field, anti-aliased by that band).
//  - Detail layer (§5): a second, inner surface at density u_inner_iso (the seed shrinks the
//    particles' radius and mass; a higher threshold of the same field does that), drawn only as
//    its silhouette over the outer surface (innerSilhouette, surface_sample.glsl: a line at most
//    two pixels wide where the largest density behind the hit grazes u_inner_iso). The ray
//    caster reads that density smoothed over about 3 voxels (raycast.frag.glsl), so single
//    voxels of a painted cloud's scattered edge samples draw no dots or broken dashes.
uniform vec3 u_light_dir;  // towards the sun, unit
uniform vec3 u_light_colour;

const vec3 kOutline = vec3(0.10, 0.12, 0.22);
const vec3 kCel[4] =
    vec3[4](vec3(0.50, 0.57, 0.78), vec3(0.68, 0.75, 0.90), vec3(0.86, 0.90, 0.97), vec3(1.0));

// Style parameters (render_style_params.h, config/render.toml [style.cartoon]); defaults:
uniform vec3 u_cel_thresholds;  // 0.2, 0.45, 0.75: d between the four tones
uniform float u_outline_width;  // 0.3: outline where |N·V| < this, soft from half of it

int celBand(float d) {
  return d < u_cel_thresholds.x ? 0 : d < u_cel_thresholds.y ? 1 : d < u_cel_thresholds.z ? 2 : 3;
}

vec4 shadeSurface(SurfaceSample s) {
  float near_miss = smoothstep(0.6 * u_iso, u_iso, s.max_density);
  if (!s.hit) return vec4(kOutline * near_miss, near_miss);
  float d = max(dot(s.normal, u_light_dir), 0.0) * (0.35 + 0.65 * s.light_transmittance);
  vec3 cel = kCel[celBand(d)] * u_light_colour;
  float outline =
      1.0 - smoothstep(0.5 * u_outline_width, u_outline_width, abs(dot(s.normal, s.view)));
  return vec4(mix(cel, kOutline, max(outline, 0.8 * innerSilhouette(s))), 1.0);
}
