// 3D simplex noise (Perlin 2001, as explained by Gustavson 2005) with a seeded gradient
// permutation, and the pre-generated, tiling noise texture the sphere mapping samples
// (thesis §6.5: "produced by Simplex Noise functions, only generated when the system is
// launched").
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "app/mapping/mapping_config.h"

namespace cb {

class SimplexNoise3 {
 public:
  explicit SimplexNoise3(uint32_t seed);
  // Noise in about [-1, 1], smooth, zero on the lattice points.
  float operator()(glm::vec3 p) const;

 private:
  std::array<uint8_t, 512> perm_{};
};

// A size³ texture of fractal simplex noise remapped to [0, 1], periodic with period `size` in
// each axis so it can tile the volume (one texel per voxel: texel = voxel index mod size).
// Periodicity comes from blending the noise with its copies shifted by one period (the
// standard 8-corner tiling blend), so no seam shows where tiles meet.
class NoiseTexture {
 public:
  explicit NoiseTexture(const NoiseTextureConfig& config);
  int size() const { return size_; }
  float at(int x, int y, int z) const {
    const int m = size_ - 1;
    return texels_[(size_t(z & m) * size_ + size_t(y & m)) * size_ + size_t(x & m)];
  }
  const std::vector<float>& texels() const { return texels_; }

 private:
  int size_;
  std::vector<float> texels_;
};

// The texture of `config`, generated once per process and shared (thesis §6.5: generated when
// the system is launched). Every session's mapper asks for it: generating it took about 1 s per
// session on the host (64³ texels of 3-octave noise, blended over 8 corners) and 10–20 s under
// an emulated CPU, which the kiosk paid for each visitor's fresh session. Thread-safe.
std::shared_ptr<const NoiseTexture> sharedNoiseTexture(const NoiseTextureConfig& config);

}  // namespace cb
