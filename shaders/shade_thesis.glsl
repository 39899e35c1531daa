// Shading stage: the thesis's light model (§4.5.2, Fig. 4.19). Given a sample's density and
// its transmittance towards the light T (from the light volume, Alg. 5), returns the colour the
// sample emits. I = 1 − T is the thesis's inverted illuminance; S = 0.55 + cos(0.4 − I·π)/2.2
// is ≈ 0.97 fully lit, peaks at ≈ 1.0 on the rim just inside the surface and ≈ 0.13 in deep
// shadow. Tinted by the light colour. The density is composited as it is (no per-ray state).
//
// A composited shading stage defines `styleBeginRay`, `styleDensity`, `shadeSample` and
// `styleEndRay` (see raycast.frag.glsl); other styles are other files with the same functions.
uniform vec3 u_light_colour;

void styleBeginRay(vec3 dir) {}

float styleDensity(float density, vec3 texcoord) {
  return density;
}

vec3 styleEndRay(vec3 colour, float transmittance) {
  return colour;
}

vec3 shadeSample(float density, float transmittance) {
  float illuminance = 1.0 - transmittance;
  float strength = 0.55 + cos(0.4 - illuminance * 3.14159265) / 2.2;
  return strength * u_light_colour;
}
