// The 3D brush's ink dataset (thesis §5.3.1, Fig. 5.7): an n³ grid over [-1,1]³ (y up) holding a
// solid sphere that fades at its edge, low in the volume, plus a noise plume that rises from it
// along +y, narrowing and thinning towards the top. Cutting it high gives sparse noise, cutting it
// through the sphere's centre gives a solid disc.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace cb {

struct InkVolumeShape {
  glm::vec3 sphere_centre{0.0f, -0.35f, 0.0f};
  float sphere_radius = 0.55f;
  float top_y = 0.85f;  // highest plane the brush cuts (pressure 0)
};

class InkVolume {
 public:
  InkVolume(int n, uint32_t seed, const InkVolumeShape& shape = {});
  int size() const { return n_; }
  const InkVolumeShape& shape() const { return shape_; }
  float voxel(int x, int y, int z) const { return d_[(size_t(z) * n_ + y) * n_ + x]; }
  // Trilinear density at p in [-1,1]³ (voxel centres at the cell midpoints); 0 outside.
  float sample(glm::vec3 p) const;
  // Radius around the y axis outside which the volume holds no ink.
  float inkRadius() const { return shape_.sphere_radius; }
  // The cutting plane's height for a pressure 0..1: top_y at 0, the sphere's centre at 1.
  float planeHeight(float pressure) const;

 private:
  int n_;
  InkVolumeShape shape_;
  std::vector<float> d_;
  std::vector<float> padded_;  // (n+2)³ copy with a zero border, for sample()
};

// The default-shaped ink volume of (n, seed), made once per process and shared by every 3D brush
// (each new session made its own: tens of milliseconds on the host, about a second under an
// emulated CPU, paid again for each kiosk visitor). Thread-safe.
std::shared_ptr<const InkVolume> sharedInkVolume(int n, uint32_t seed);

}  // namespace cb
