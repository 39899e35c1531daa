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

// cos(0.4 − I·π) for I ∈ [0, 1] as a polynomial in u = 2I − 1 (degree 9, interpolating at the
// Chebyshev nodes; largest error 1.1e-7, 2.2e-7 in float arithmetic, a thousandth of an 8-bit
// step): a third of llvmpipe's cos, which reduces the argument's range first — and this runs
// for every ray sample. I = 1 − T, so u = 1 − 2T.
float thesisCos(float transmittance) {
  float u = 1.0 - 2.0 * transmittance;
  float p = -0.000139698896;
  p = p * u + 0.000334173295;
  p = p * u + 0.00430517178;
  p = p * u - 0.00810399652;
  p = p * u - 0.0733992755;
  p = p * u + 0.0987762287;
  p = p * u + 0.594972014;
  p = p * u - 0.480424702;
  p = p * u - 1.44679928;
  return p * u + 0.389418334;
}

vec3 shadeSample(float density, float transmittance) {
  float strength = 0.55 + thesisCos(transmittance) / 2.2;
  return strength * u_light_colour;
}
