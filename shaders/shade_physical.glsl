// Shading stage: physically based clouds after Jiménez de Parga (seed 004, "Radiometric
// equations" and "Texture generation"), composited by the ray caster with Beer–Lambert opacity
// α = 1 − exp(−σ·ρ·Δs) (seed 004 "Absorption": T = e^(−τ)).
//
// Light grid (seed 004, pre-computed lighting): L(v) = I₀·T(0,D) + ∫₀ᴰ C(l)·T(l,D) dl. The light
// volume holds T(0,D) (Alg. 5 of the thesis). With the light scattered forward at each point in
// proportion to the optical depth it crosses, C(l) = κ_s·I₀·T(0,l)·dτ/dl, the integral has the
// closed form κ_s·I₀·T·τ (T(0,l)·T(l,D) = T(0,D)), so L = I₀·T·(1 + κ_s·τ) with τ = −ln T:
// the in-scattering term needs no second grid. L depends on T alone, so it is tabulated for the
// 256 values of the 8-bit T (physical_light_table.h, u_light_table), one fetch per sample.
//
// Render time (seed 004): I = ∫ [L·ρ·κ₁ (reflection) + L·ρ·P(θ)·κ₂ (scattering)]·T(0,s) ds;
// ρ·ds is the compositing weight, so a sample emits L·(κ₁ + κ₂·4π·P(θ)). P is Henyey–Greenstein,
// P(θ) = (1 − g²) / (4π·(1 + g² − 2g·cos θ)^(3/2)), θ between the sun's light and the view ray.
//
// Beyond the seed (cheap, and each visibly better on painted clouds):
//  - two lobes, forward g = 0.6 and back g = −0.3 blended 0.75/0.25: a silver lining towards the
//    sun without losing the lit side's brightness when the sun is behind the viewer;
//  - multiple scattering by attenuated octaves (Wrenninge's approximation, as production cloud
//    renderers use): Σᵢ aⁱ·L(bⁱ·τ)·P(cⁱ·g) with a = b = c = ½, 3 octaves, so shadowed cores are
//    not black. The phase terms depend only on the ray, so styleBeginRay computes them once;
//  - an ambient sky term, the sky (background) colour times T^⅛, lighting shadowed parts blue;
//  - an exponential exposure of each ray's emitted colour c (its composited colour over its
//    opacity), 1 − e^(−1.6·c), in styleEndRay: sunlit sides (c > 1 when the sun is behind the
//    viewer) keep their shape instead of clipping, and shadows lift a little.
//
// fBm detail (seed 004, "Texture generation"): a tileable 64³ texture of fbm = Σᵢ wⁱ·noise(sⁱ·x)
// with w = ½, s = 2 (built on the CPU, detail_noise.h) erodes the density at render time:
// ρ' = max(ρ − κ_e·n·(1 − ρ), 0), so thin edges break up finer than the voxels while cores stay.
#define CB_SHADE vec3  // a sample's shade is a colour

uniform vec3 u_light_colour;
uniform vec3 u_light_dir;          // towards the sun, unit
uniform vec3 u_sky_colour;         // ambient sky light (the background colour)
uniform sampler3D u_detail_noise;  // fBm in [0,1], repeating
uniform vec3 u_noise_repeat;       // noise repeats per volume texture coordinate unit, per axis
uniform float u_erosion;           // κ_e
uniform sampler1D u_light_table;   // 256 × (L(τ), L(bτ), L(b²τ), e^(−τ/8)) by 8-bit T

// Style parameters (render_style_params.h, config/render.toml [style.physical]); defaults:
uniform float u_reflection;  // κ₁ = 0.55
uniform float u_scattering;  // κ₂ = 0.45
uniform vec3 u_phase_lobes;  // forward g = 0.6, back g = −0.3, forward weight 0.75
uniform int u_octaves;       // 3 (1..3)
uniform float u_ambient;     // κ_a = 0.5
uniform float u_exposure;    // 1.6
const float kOctaveAttenuation = 0.5;  // a: weight of each further octave
const float kOctavePhase = 0.5;        // c: anisotropy scale per octave

float henyeyGreenstein4Pi(float cos_theta, float g) {
  float denom = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (denom * sqrt(denom));
}

// Per ray: the sun's weight on each octave's light term, and the sky's.
vec3 sunOctave0, sunOctave1, sunOctave2, skyWeight;

void styleBeginRay(vec3 dir) {
  float cos_theta = dot(dir, u_light_dir);
  float phase[3];
  float g = 1.0;
  for (int i = 0; i < 3; ++i) {
    phase[i] = mix(henyeyGreenstein4Pi(cos_theta, u_phase_lobes.y * g),
                   henyeyGreenstein4Pi(cos_theta, u_phase_lobes.x * g), u_phase_lobes.z);
    g *= kOctavePhase;
  }
  // Emitted = sun·(κ₁·L₀ + κ₂·Σ aⁱ·Pᵢ·Lᵢ) + sky·κ_a·e^(−τ/8), octaves beyond u_octaves off.
  float a1 = u_octaves > 1 ? kOctaveAttenuation : 0.0;
  float a2 = u_octaves > 2 ? kOctaveAttenuation * kOctaveAttenuation : 0.0;
  sunOctave0 = u_light_colour * (u_reflection + u_scattering * phase[0]);
  sunOctave1 = u_light_colour * (u_scattering * a1 * phase[1]);
  sunOctave2 = u_light_colour * (u_scattering * a2 * phase[2]);
  skyWeight = u_sky_colour * u_ambient;
}

float styleDensity(float density, vec3 texcoord) {
  float n = textureLod(u_detail_noise, texcoord * u_noise_repeat, 0.0).r;
  return max(density - u_erosion * n * (1.0 - density), 0.0);
}

vec3 shadeSample(float density, float transmittance) {
  vec4 light = texelFetch(u_light_table, int(transmittance * 255.0 + 0.5), 0);
  return sunOctave0 * light.x + sunOctave1 * light.y + sunOctave2 * light.z + skyWeight * light.w;
}

vec3 styleEndRay(vec3 colour, float transmittance) {
  float opacity = 1.0 - transmittance;
  vec3 emitted = colour / max(opacity, 1e-4);
  return (vec3(1.0) - exp(-u_exposure * emitted)) * opacity;
}
