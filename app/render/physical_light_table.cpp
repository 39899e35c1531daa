#include "app/render/physical_light_table.h"

#include <algorithm>
#include <cmath>

namespace cb {

std::array<glm::vec4, 256> physicalLightTable() {
  std::array<glm::vec4, 256> table;
  auto grid = [](float tau) { return std::exp(-tau) * (1.0f + kPhysicalInScattering * tau); };
  for (int i = 0; i < 256; ++i) {
    const float t = float(i) / 255.0f;
    const float tau = -std::log(std::max(t, 1.0f / 512.0f));
    const float b = kPhysicalOctaveDepth;
    table[size_t(i)] = glm::vec4(grid(tau), grid(b * tau), grid(b * b * tau),
                                 std::exp(-kPhysicalAmbientFalloff * tau));
  }
  return table;
}

}  // namespace cb
