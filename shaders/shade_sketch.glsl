// Shading stage: sketched clouds after Álvarez et al. (seed 003, §4, Fig. 2 and 6), on the
// iso-surface of the density. Writes what the screen-space pass (style_compose.frag.glsl,
// CB_COMPOSE_SKETCH) draws as pencil strokes on paper:
//   r = tone (0 lit … 1 dark, for hatching), g = outline stroke, a = coverage.
// Tone is 1 − d with d = N·L times 0.35 + 0.65·T (T the light volume's transmittance); the N·V
// outline and the inner surface's silhouette (innerSilhouette, surface_sample.glsl: a line at most
// two pixels wide) are those of the cartoon style (shade_cartoon.glsl). Rays that pass just
// outside the surface add coverage only: the outline on the paper is drawn by the compose pass
// from the blurred coverage (a continuous pencil line); drawn from this near-miss band it was a
// soft grey that broke on the strokes' lower edges.
uniform vec3 u_light_dir;       // towards the sun, unit
uniform float u_outline_width;  // [style.sketch] outline_width, 0.3 (as the cartoon's)
// The inner surface's lines in lighter pencil than the outline (seed 003 Fig. 6: detail drawn
// over the outline's weight): at 0.7 a painted stroke's inner bodies drew as heavy as its outline.
const float kInnerLine = 0.45;

vec4 shadeSurface(SurfaceSample s) {
  float near_miss = smoothstep(0.6 * u_iso, u_iso, s.max_density);
  if (!s.hit) return vec4(0.0, 0.0, 0.0, near_miss);
  float d = max(dot(s.normal, u_light_dir), 0.0) * (0.35 + 0.65 * s.light_transmittance);
  float outline =
      1.0 - smoothstep(0.5 * u_outline_width, u_outline_width, abs(dot(s.normal, s.view)));
  return vec4(1.0 - d, max(outline, kInnerLine * innerSilhouette(s)), 0.0, 1.0);
}
