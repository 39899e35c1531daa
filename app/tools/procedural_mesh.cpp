#include "app/tools/procedural_mesh.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace cb {

float displacedTorusTubeRadius(float minor, float amplitude, float u, float v) {
  return minor * (1.0f + amplitude * std::sin(5.0f * u) * std::sin(3.0f * v));
}

TriangleMesh makeDisplacedTorus(float major, float minor, float amplitude, int rings, int sides) {
  TriangleMesh mesh;
  const float two_pi = 6.28318530718f;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sides; ++j) {
      const float u = two_pi * float(i) / float(rings), v = two_pi * float(j) / float(sides);
      const float r = displacedTorusTubeRadius(minor, amplitude, u, v);
      const float ring = major + r * std::cos(v);
      mesh.vertices.emplace_back(ring * std::cos(u), r * std::sin(v), ring * std::sin(u));
    }
  auto id = [&](int i, int j) { return uint32_t((i % rings) * sides + (j % sides)); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sides; ++j) {
      const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      mesh.triangles.emplace_back(a, c, b);
      mesh.triangles.emplace_back(a, d, c);
    }
  return mesh;
}

void writeObj(const std::string& path, const TriangleMesh& mesh) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot write");
  for (const glm::vec3& p : mesh.vertices) std::fprintf(f, "v %.7g %.7g %.7g\n", p.x, p.y, p.z);
  for (const glm::uvec3& t : mesh.triangles)
    std::fprintf(f, "f %u %u %u\n", t.x + 1, t.y + 1, t.z + 1);
  if (std::fclose(f) != 0) throw std::runtime_error(path + ": write failed");
}

}  // namespace cb
