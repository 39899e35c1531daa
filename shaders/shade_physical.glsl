// Shading stage: physically based clouds after Jiménez de Parga (seed 004, "Radiometric
// equations" and "Texture generation"), composited by the ray caster with Beer–Lambert opacity
// α = 1 − exp(−σ·ρ·Δs) (seed 004 "Absorption": T = e^(−τ)).
//
// Light grid (seed 004, pre-computed lighting): L(v) = I₀·T(0,D) + ∫₀ᴰ C(l)·T(l,D) dl. The light
// volume holds T(0,D) (Alg. 5 of the thesis). With the light scattered forward at each point in
// proportion to the optical depth it crosses, C(l) = κ_s·I₀·T(0,l)·dτ/dl, the integral has the
// closed form κ_s·I₀·T·τ (T(0,l)·T(l,D) = T(0,D)), so L = I₀·T·(1 + κ_s·τ) with τ = −ln T:
// the in-scattering term costs one log per sample and no second grid.
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
//  - an exponential exposure per sample, 1 − e^(−1.6·c), so sunlit sides (c > 1 when the sun is
//    behind the viewer) keep their shape instead of clipping, and shadows lift a little.
//
// fBm detail (seed 004, "Texture generation"): a tileable 64³ texture of fbm = Σᵢ wⁱ·noise(sⁱ·x)
// with w = ½, s = 2 (built on the CPU, detail_noise.h) erodes the density at render time:
// ρ' = max(ρ − κ_e·n·(1 − ρ), 0), so thin edges break up finer than the voxels while cores stay.
uniform vec3 u_light_colour;
uniform vec3 u_light_dir;          // towards the sun, unit
uniform vec3 u_sky_colour;         // ambient sky light (the background colour)
uniform sampler3D u_detail_noise;  // fBm in [0,1], repeating
uniform vec3 u_noise_repeat;       // noise repeats per volume texture coordinate unit, per axis
uniform float u_erosion;           // κ_e

const float kReflection = 0.55;       // κ₁
const float kScattering = 0.45;       // κ₂
const float kInScattering = 0.6;      // κ_s of the light grid's in-scattering term
const float kForwardG = 0.6, kBackG = -0.3, kForwardWeight = 0.75;
const float kOctaveAttenuation = 0.5;  // a: weight of each further octave
const float kOctaveDepth = 0.5;        // b: optical depth scale per octave
const float kOctavePhase = 0.5;        // c: anisotropy scale per octave
const float kAmbient = 0.5;
const float kExposure = 1.6;

float henyeyGreenstein4Pi(float cos_theta, float g) {
  float denom = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (denom * sqrt(denom));
}

float phaseOctave[3];  // 4π·P for each octave of this ray

void styleBeginRay(vec3 dir) {
  float cos_theta = dot(dir, u_light_dir);
  float g = 1.0;
  for (int i = 0; i < 3; ++i) {
    phaseOctave[i] = mix(henyeyGreenstein4Pi(cos_theta, kBackG * g),
                         henyeyGreenstein4Pi(cos_theta, kForwardG * g), kForwardWeight);
    g *= kOctavePhase;
  }
}

float styleDensity(float density, vec3 texcoord) {
  float n = textureLod(u_detail_noise, texcoord * u_noise_repeat, 0.0).r;
  return max(density - u_erosion * n * (1.0 - density), 0.0);
}

vec3 shadeSample(float density, float transmittance) {
  float tau = -log(max(transmittance, 1.0 / 512.0));
  // Octave i sees optical depth bⁱ·τ: T_i = exp(−bⁱτ), grid term T_i·(1 + κ_s·bⁱτ).
  float light0 = exp(-tau) * (1.0 + kInScattering * tau);
  float tau1 = kOctaveDepth * tau, tau2 = kOctaveDepth * tau1;
  float light1 = exp(-tau1) * (1.0 + kInScattering * tau1);
  float light2 = exp(-tau2) * (1.0 + kInScattering * tau2);
  float scattered = light0 * phaseOctave[0] +
                    kOctaveAttenuation * (light1 * phaseOctave[1] +
                                          kOctaveAttenuation * light2 * phaseOctave[2]);
  vec3 sun = u_light_colour * (kReflection * light0 + kScattering * scattered);
  vec3 sky = u_sky_colour * (kAmbient * exp(-0.125 * tau));
  return vec3(1.0) - exp(-kExposure * (sun + sky));
}
