// The LIC cloud layer of the sky (seed 002, Yu & Wang §3.2.2–3.2.3): line-integral convolution
// (Cabral & Leedom 1993, the seed's [28] and Fig. 7) of white noise along a flow field, so the
// noise is smeared into streaks along the streamlines, the way the seed turns a cloud
// photograph into a convoluted "cloudy sky plane". We have no photograph: the source image is
// white noise, the flow field a smooth periodic wind with eddies, and the streaks are gathered
// into patches by a low-frequency coverage field. Made once on the CPU, deterministically from a
// seed (the same bytes on any thread count), tileable, and uploaded as a texture.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace cb {

// A square, periodic field of values (row-major, x fastest).
struct ScalarImage {
  int size = 0;
  std::vector<float> values;
  float at(int x, int y) const;       // wraps
  float bilinear(glm::vec2 p) const;  // texel centres at i + ½, wraps
};

// Seeded white noise in [0, 1).
ScalarImage whiteNoise(int size, uint32_t seed);
// The flow: unit direction at p (texels) of a periodic field of period `size`: a prevailing wind
// whose angle is bent by a few seeded sinusoidal eddies.
glm::vec2 licFlow(glm::vec2 p, int size, uint32_t seed);
// Line-integral convolution of `source` along licFlow: each texel averages the source over the
// streamline through it, `length` unit steps forward and backward (midpoint integration), with a
// box kernel (Cabral & Leedom's simplest). Parallel over rows.
ScalarImage lineIntegralConvolution(const ScalarImage& source, int length, uint32_t seed);

// The sky texture: LIC of white noise, contrast restored, smoothed (the seed smooths its LIC
// results "with some iteration", §3.2.2), times a periodic coverage field, as 8-bit opacity of
// the cloud layer. size in [16, 4096], length in [1, 256].
std::vector<uint8_t> makeLicSkyTexture(int size, int length, float coverage, uint32_t seed);

}  // namespace cb
