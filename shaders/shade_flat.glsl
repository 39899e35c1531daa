// Scratch trial style "flat": the thesis shading stage under another name (a recipe check).
// Shading stage: the thesis's light model (§4.5.2, Fig. 4.19). Given a sample's density and
// its transmittance towards the light T (from the light volume, Alg. 5), returns the strength
// the sample emits: I = 1 − T is the thesis's inverted illuminance; S = 0.55 + cos(0.4 − I·π)/2.2
// is ≈ 0.97 fully lit, peaks at ≈ 1.0 on the rim just inside the surface and ≈ 0.13 in deep
// shadow. The light is grey times the light's colour, so a sample's shade is one number
// (CB_SHADE float) and the ray's composited sum is tinted once, in styleEndRay (a vec3 per
// sample cost 4 % of a frame). The density is composited as it is (no per-ray state).
//
// A composited shading stage defines CB_SHADE (the type of a sample's shade), `styleBeginRay`,
// `styleDensity`, `shadeSample` and `styleEndRay` (see raycast.frag.glsl); other styles are
// other files with the same functions.
#define CB_SHADE float

uniform vec3 u_light_colour;

void styleBeginRay(vec3 dir) {}

float styleDensity(float density, vec3 texcoord) {
  return density;
}

vec3 styleEndRay(float shade, float transmittance) {
  return shade * u_light_colour;
}

// S(T) = 0.55 + cos(0.4 − I·π)/2.2 with I = 1 − T, as a polynomial in u = 2I − 1 = 1 − 2T (degree
// 9: cos interpolated at the Chebyshev nodes, coefficients divided by 2.2 and 0.55 added to the
// constant; largest error 1.1e-7 over the 256 values of the 8-bit T, a thousandth of an 8-bit
// step): a third of llvmpipe's cos, which reduces the argument's range first — and this runs for
// every ray sample.
float thesisStrength(float transmittance) {
  float u = 1.0 - 2.0 * transmittance;
  float p = -6.34995013e-05;
  p = p * u + 1.51896951e-04;
  p = p * u + 1.95689616e-03;
  p = p * u - 3.68363480e-03;
  p = p * u - 3.33633088e-02;
  p = p * u + 4.48982865e-02;
  p = p * u + 2.70441830e-01;
  p = p * u - 2.18374863e-01;
  p = p * u - 6.57636046e-01;
  return p * u + 7.27008343e-01;
}

float shadeSample(float density, float transmittance) {
  return thesisStrength(transmittance);
}
