// The sun by the time of day: its direction (Light::direction) and colour at a latitude and day
// of the year, local solar time (no time zone or equation of time: noon is when the sun is
// highest).
//
// Position (the standard low-precision approximation, as in e.g. Duffie & Beckman, "Solar
// Engineering of Thermal Processes", §1.6):
//   declination δ = −23.44°·cos(360°/365·(N + 10))        (Cooper-style approximation)
//   hour angle  H = 15°·(t − 12 h)
//   elevation   sin α = sin φ·sin δ + cos φ·cos δ·cos H
//   azimuth     from north through east: A = atan2(−sin H·cos δ, cos φ·sin δ − sin φ·cos δ·cos H)
// Scene axes: y up, −z north, +x east (so the default morning sun comes from +x, the east).
//
// Colour: the sunlight's transmittance through the air mass m (Kasten & Young 1989:
// m = 1 / (sin α + 0.50572·(α + 6.07995°)^−1.6364)), per channel T = e^(−τ·m), τ the zenith
// optical depth of Rayleigh scattering (Bucholtz 1995 fit, τ_R ≈ 0.0088·λ^−4.05, λ in µm, at
// 680/550/440 nm) plus a grey aerosol depth 0.05; divided by T at m = 1 so the noon sun keeps the
// configured colour. Near the horizon the sun is warmer (blue goes first) and dimmer.
#pragma once

#include <glm/glm.hpp>

namespace cb {

struct SunPosition {
  float elevation_deg = 0.0f;             // above the horizon (negative: below)
  float azimuth_deg = 0.0f;               // from north through east
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // towards the sun, unit (scene axes above)
};

inline constexpr float kDefaultLatitudeDeg = 45.0f;  // mid-latitudes
inline constexpr int kDefaultDayOfYear = 172;        // 21 June

SunPosition sunPosition(float hours, float latitude_deg, int day_of_year);
// The sun's colour at `elevation_deg` (clamped to ≥ 0) relative to its colour overhead.
glm::vec3 sunTransmittance(float elevation_deg);
// Parses "HH:MM" (00:00–23:59) into hours; false for anything else.
bool parseTimeOfDay(const char* text, float* hours);

}  // namespace cb
