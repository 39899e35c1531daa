// Shading stage: the thesis's light model (§4.5.2, Fig. 4.19). Given a sample's density and
// its transmittance towards the light T (from the light volume, Alg. 5), returns the colour the
// sample emits. I = 1 − T is the thesis's inverted illuminance; S = 0.55 + cos(0.4 − I·π)/2.2
// is ≈ 0.97 fully lit, peaks at ≈ 1.0 on the rim just inside the surface and ≈ 0.13 in deep
// shadow. Tinted by the light colour.
//
// A shading stage defines exactly `vec3 shadeSample(float density, float transmittance)`; the
// ray caster (raycast.frag.glsl) knows nothing else about it, so other styles (ink-wash,
// cartoon, physically based) are other files with the same function.
uniform vec3 u_light_colour;

vec3 shadeSample(float density, float transmittance) {
  float illuminance = 1.0 - transmittance;
  float strength = 0.55 + cos(0.4 - illuminance * 3.14159265) / 2.2;
  return strength * u_light_colour;
}
