// The time-of-day sun (sun_position.h): elevations against values worked by hand from the
// standard formula, the direction's axes, and the air-mass reddening.
#include "app/scene/sun_position.h"

#include <cmath>

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(SunPosition, NoonIsHigherThanSixInTheEveningAtTheDefaultLatitude) {
  // 21 June (day 172), 45° N: δ = −23.44°·cos(360/365·182) = 23.43°;
  // noon α = 90° − 45° + 23.43° = 68.4°; 18:00 (H = 90°): sin α = sin 45°·sin 23.43° → 16.3°.
  const SunPosition noon = sunPosition(12.0f, kDefaultLatitudeDeg, kDefaultDayOfYear);
  const SunPosition six = sunPosition(18.0f, kDefaultLatitudeDeg, kDefaultDayOfYear);
  EXPECT_NEAR(noon.elevation_deg, 68.4f, 0.2f);
  EXPECT_NEAR(six.elevation_deg, 16.3f, 0.2f);
  EXPECT_NEAR(noon.azimuth_deg, 180.0f, 0.5f);  // due south at solar noon
  EXPECT_GT(six.azimuth_deg, 270.0f);           // a June evening sun sets north of west
  EXPECT_NEAR(std::asin(noon.direction.y) * 57.29578f, noon.elevation_deg, 0.01f);
  EXPECT_GT(noon.direction.z, 0.9f * std::cos(noon.elevation_deg / 57.29578f));  // south = +z
  EXPECT_LT(six.direction.x, 0.0f);                                              // west = −x
  EXPECT_GT(sunPosition(8.0f, 45.0f, 172).direction.x, 0.0f);                    // morning: east
  EXPECT_LT(sunPosition(0.0f, 45.0f, 172).elevation_deg, 0.0f);                  // midnight
  EXPECT_NEAR(sunPosition(12.0f, 45.0f, 355).elevation_deg, 90.0f - 45.0f - 23.44f, 0.2f);
}

TEST(SunPosition, TheLowSunIsWarmerAndDimmer) {
  const glm::vec3 high = sunTransmittance(68.4f), low = sunTransmittance(5.0f);
  EXPECT_NEAR(sunTransmittance(90.0f).r, 1.0f, 1e-4f);
  EXPECT_GT(high.b, 0.9f);
  EXPECT_LT(low.r, high.r);  // dimmer
  EXPECT_LT(low.b, low.g);   // blue goes first …
  EXPECT_LT(low.g, low.r);
  EXPECT_GT(low.r / low.b, 2.0f * high.r / high.b);  // … so it is much redder
}

TEST(SunPosition, TimesOfDayParse) {
  float h = 0.0f;
  EXPECT_TRUE(parseTimeOfDay("18:30", &h));
  EXPECT_FLOAT_EQ(h, 18.5f);
  EXPECT_TRUE(parseTimeOfDay("00:00", &h));
  for (const char* bad : {"24:00", "7:30", "12:60", "12-30", "noon", "12:30x", ""})
    EXPECT_FALSE(parseTimeOfDay(bad, &h)) << bad;
}

}  // namespace
}  // namespace cb
