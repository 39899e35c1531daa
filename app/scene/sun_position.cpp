#include "app/scene/sun_position.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace cb {
namespace {

constexpr float kDegToRad = 0.017453292519943295f;

}  // namespace

SunPosition sunPosition(float hours, float latitude_deg, int day_of_year) {
  const float declination =
      -23.44f * kDegToRad * std::cos(360.0f / 365.0f * float(day_of_year + 10) * kDegToRad);
  const float hour_angle = 15.0f * (hours - 12.0f) * kDegToRad;
  const float phi = latitude_deg * kDegToRad;
  const float sin_elevation = std::sin(phi) * std::sin(declination) +
                              std::cos(phi) * std::cos(declination) * std::cos(hour_angle);
  const float elevation = std::asin(std::clamp(sin_elevation, -1.0f, 1.0f));
  const float azimuth =
      std::atan2(-std::sin(hour_angle) * std::cos(declination),
                 std::cos(phi) * std::sin(declination) -
                     std::sin(phi) * std::cos(declination) * std::cos(hour_angle));
  SunPosition s;
  s.elevation_deg = elevation / kDegToRad;
  s.azimuth_deg = std::fmod(azimuth / kDegToRad + 360.0f, 360.0f);
  // North = −z, east = +x.
  const float horizontal = std::cos(elevation);
  s.direction = glm::normalize(glm::vec3(horizontal * std::sin(azimuth), std::sin(elevation),
                                         -horizontal * std::cos(azimuth)));
  return s;
}

glm::vec3 sunTransmittance(float elevation_deg) {
  const float a = std::max(elevation_deg, 0.0f);
  auto airmass = [](float deg) {
    return 1.0f / (std::sin(deg * kDegToRad) + 0.50572f * std::pow(deg + 6.07995f, -1.6364f));
  };
  // Zenith optical depth: Rayleigh at 680, 550, 440 nm + grey aerosol.
  const glm::vec3 lambda_um(0.68f, 0.55f, 0.44f);
  const glm::vec3 tau = 0.0088f * glm::pow(lambda_um, glm::vec3(-4.05f)) + 0.05f;
  return glm::exp(-tau * (airmass(a) - airmass(90.0f)));
}

bool parseTimeOfDay(const char* text, float* hours) {
  int h = -1, m = -1;
  char extra = 0;
  if (std::strlen(text) != 5 || text[2] != ':' ||
      std::sscanf(text, "%2d:%2d%c", &h, &m, &extra) != 2)
    return false;
  if (h < 0 || h > 23 || m < 0 || m > 59) return false;
  *hours = float(h) + float(m) / 60.0f;
  return true;
}

}  // namespace cb
