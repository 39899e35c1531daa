#include "app/render/screen_blur.h"

#include <algorithm>
#include <cmath>

namespace cb {

ScreenBlurWeights screenBlurWeights(float sigma, int radius) {
  radius = std::clamp(radius, 0, kMaxInkBleedRadius);
  ScreenBlurWeights w{};
  const float inv_two_sigma2 = 1.0f / (2.0f * sigma * sigma);
  float norm = 1.0f;
  w[0] = 1.0f;
  for (int i = 1; i <= radius; ++i) {
    w[i] = std::exp(-float(i * i) * inv_two_sigma2);
    norm += 2.0f * w[i];
  }
  for (float& x : w) x /= norm;
  return w;
}

std::string screenBlurDefine(int radius) {
  return "#define CB_BLUR_RADIUS " + std::to_string(std::clamp(radius, 1, kMaxInkBleedRadius)) +
         "\n";
}

}  // namespace cb
