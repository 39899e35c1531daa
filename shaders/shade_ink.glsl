// Shading stage: Chinese ink wash after Cao (seed 001, §3.3.3–3.3.5, §4.1), on the iso-surface
// of the density (surface_sample.glsl). Writes ink amounts, not colours; the screen-space pass
// (style_compose.frag.glsl, CB_COMPOSE_INK) bleeds the silhouette, applies smoothstep and lays
// the ink on xuan paper:
//   r = interior wash, g = silhouette ink, a = coverage.
//
// Interior (§3.3.3): diffuse d = N·L (here times 0.35 + 0.65·T with T the light volume's
// transmittance, so the cloud shadows itself without going black), in bands of the wash:
//   d ≤ 0.25 → 1.0,  ≤ 0.55 → 0.7,  ≤ 0.8 → 0.4,  else 0.1.
// While moving (CB_MOVING) the seed simplifies the interior: two bands, and no bleeding.
// Silhouette (§3.3.4): edge = N·V; where edge < threshold (0.5, §4.1.1) the ink falls off as the
// Gaussian exp(−x²/2) of x = 3·edge/threshold. Rays that pass just outside the surface (their
// largest density within 40% of the iso level) continue the line outwards, so the outline is
// taken from the density field on both sides of the silhouette. On a painted stroke this line is
// under a pixel wide; the compose pass adds an outline of fixed screen width found from the
// blurred coverage (a), style_compose.frag.glsl.
uniform vec3 u_light_dir;  // towards the sun, unit

// Style parameters (render_style_params.h, config/render.toml [style.ink]); defaults:
uniform float u_ink_line_width;  // silhouette threshold on N·V, 0.5 (seed 001 §4.1.1)
uniform float u_ink_wash;        // darkest interior wash, 0.35: clouds are mostly paper

float inkBand(float d) {
#if CB_MOVING
  return d <= 0.55 ? 0.7 : 0.1;
#else
  return d <= 0.25 ? 1.0 : d <= 0.55 ? 0.7 : d <= 0.8 ? 0.4 : 0.1;
#endif
}

vec4 shadeSurface(SurfaceSample s) {
  float near_miss = smoothstep(0.6 * u_iso, u_iso, s.max_density);
  if (!s.hit) return vec4(0.0, near_miss, 0.0, near_miss);
  float d = max(dot(s.normal, u_light_dir), 0.0) * (0.35 + 0.65 * s.light_transmittance);
  float edge = abs(dot(s.normal, s.view));
  float x = 3.0 * edge / u_ink_line_width;
  float silhouette = edge < u_ink_line_width ? exp(-0.5 * x * x) : 0.0;
  return vec4(u_ink_wash * inkBand(d), silhouette, 0.0, 1.0);
}
