// Detail noise for the physically based style (seed 004, "Texture generation"): a cube of
// fractal Brownian motion, fbm(x) = Σᵢ wⁱ·perlin(sⁱ·x) with w = ½ and s = 2, precomputed on the
// CPU once and sampled (repeating) by shaders/shade_physical.glsl to erode cloud edges.
#pragma once

#include <cstdint>
#include <vector>

namespace cb {

struct DetailNoise {
  int size = 0;                 // texels per side (the cube repeats seamlessly)
  std::vector<uint8_t> texels;  // size³ values, x fastest; fbm rescaled to [0,255]
};

// A size³ repeating fBm cube: `octaves` octaves of tileable Perlin gradient noise, the first with
// `base_cells` lattice cells per side (so size must be a multiple of base_cells·2^(octaves−1)).
// Pure function of its arguments.
DetailNoise makeDetailNoise(int size = 64, int base_cells = 4, int octaves = 4, uint32_t seed = 7);

}  // namespace cb
