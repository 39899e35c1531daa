#include "app/volume/scene_generators.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

// A small deterministic generator (SplitMix64): unlike std::uniform_real_distribution its
// output is fixed by the standard arithmetic, so scenes are identical on every platform.
class SeededRandom {
 public:
  explicit SeededRandom(uint64_t seed)
      : state_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi).
  float uniform(float lo, float hi) { return lo + (hi - lo) * float(next() >> 40) * 0x1.0p-24f; }

 private:
  uint64_t state_;
};

uint32_t hashLattice(int x, int y, int z, uint32_t seed) {
  uint32_t h = seed * 0x27d4eb2du;
  h ^= uint32_t(x) * 0x8da6b343u;
  h ^= uint32_t(y) * 0xd8163841u;
  h ^= uint32_t(z) * 0xcb1ab31fu;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return h;
}

float smoothWeight(float t) {
  return t * t * (3.0f - 2.0f * t);
}

// Trilinearly interpolated lattice noise in [0,1] with a smoothstep fade.
float valueNoise(glm::vec3 p, uint32_t seed) {
  glm::vec3 f = glm::floor(p);
  glm::ivec3 i(f);
  glm::vec3 t = p - f;
  glm::vec3 w(smoothWeight(t.x), smoothWeight(t.y), smoothWeight(t.z));
  float c[2][2][2];
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx)
        c[dz][dy][dx] = float(hashLattice(i.x + dx, i.y + dy, i.z + dz, seed) >> 8) * 0x1.0p-24f;
  auto lerp = [](float a, float b, float s) { return a + (b - a) * s; };
  float y0 = lerp(lerp(c[0][0][0], c[0][0][1], w.x), lerp(c[0][1][0], c[0][1][1], w.x), w.y);
  float y1 = lerp(lerp(c[1][0][0], c[1][0][1], w.x), lerp(c[1][1][0], c[1][1][1], w.x), w.y);
  return lerp(y0, y1, w.z);
}

// Three octaves of value noise, centred on 0, amplitude ≈ ±0.5.
float fractalNoise(glm::vec3 p, uint32_t seed) {
  float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
  for (int octave = 0; octave < 3; ++octave) {
    sum += amplitude * valueNoise(p, seed + uint32_t(octave) * 101u);
    norm += amplitude;
    p *= 2.03f;
    amplitude *= 0.5f;
  }
  return sum / norm - 0.5f;
}

struct Blob {
  glm::vec3 centre;
  float radius;
};

// Calls shape(world_point) for every voxel centre inside the world-space box [lo, hi] and
// stores the result (clamped to [0,1]); parallel over z slices.
template <class Shape>
void fillRegion(Volume& v, glm::vec3 lo, glm::vec3 hi, const Shape& shape) {
  glm::ivec3 dims = v.dims();
  glm::ivec3 a = glm::clamp(glm::ivec3(glm::floor(v.worldToVoxel(lo))), glm::ivec3(0), dims);
  glm::ivec3 b = glm::clamp(glm::ivec3(glm::ceil(v.worldToVoxel(hi))) + 1, glm::ivec3(0), dims);
  if (VoxelBox{a, b}.empty()) return;
  parallelFor(size_t(b.z - a.z), 1, [&](size_t, size_t z0, size_t z1) {
    for (int z = a.z + int(z0); z < a.z + int(z1); ++z)
      for (int y = a.y; y < b.y; ++y)
        for (int x = a.x; x < b.x; ++x) {
          glm::vec3 p = v.voxelToWorld(glm::vec3(x, y, z) + 0.5f);
          v.maxMerge(x, y, z, std::clamp(shape(p), 0.0f, 1.0f));
        }
  });
  v.markDirty({a, b});
}

}  // namespace

Volume makeBundledCumulus(glm::ivec3 dims, uint32_t seed) {
  Volume v(dims);
  SeededRandom rng(seed);
  const float base_y = -0.42f;
  std::vector<Blob> blobs;
  // A wide, flat base of four large blobs whose centres sit near the base plane.
  for (int i = 0; i < 4; ++i) {
    float a = 6.2831853f * (float(i) + rng.uniform(-0.2f, 0.2f)) / 4.0f;
    float r = rng.uniform(0.36f, 0.44f);
    blobs.push_back({{0.38f * std::cos(a), base_y + 0.28f, 0.38f * std::sin(a)}, r});
  }
  blobs.push_back({{0.0f, base_y + 0.35f, 0.0f}, 0.55f});  // the core
  // The domed tower, slightly off-centre.
  glm::vec3 tower(rng.uniform(-0.12f, 0.12f), base_y + 0.75f, rng.uniform(-0.12f, 0.12f));
  blobs.push_back({tower, rng.uniform(0.36f, 0.42f)});
  blobs.push_back({tower + glm::vec3(rng.uniform(-0.1f, 0.1f), 0.3f, rng.uniform(-0.1f, 0.1f)),
                   rng.uniform(0.24f, 0.3f)});
  // Side turrets around the tower.
  for (int i = 0; i < 6; ++i) {
    float a = rng.uniform(0.0f, 6.2831853f);
    float d = rng.uniform(0.35f, 0.55f);
    blobs.push_back({{d * std::cos(a), base_y + rng.uniform(0.35f, 0.6f), d * std::sin(a)},
                     rng.uniform(0.2f, 0.3f)});
  }
  // Stretch the heap to fill ~30% of the box: wider than tall, as cumulus humilis/mediocris are.
  for (Blob& b : blobs) {
    b.centre =
        glm::vec3(b.centre.x * 1.4f, base_y + (b.centre.y - base_y) * 1.05f, b.centre.z * 1.4f);
    b.radius *= 1.27f;
  }
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const Blob& b : blobs) {
    lo = glm::min(lo, b.centre - b.radius - 0.1f);
    hi = glm::max(hi, b.centre + b.radius + 0.1f);
  }
  lo.y = std::max(lo.y, base_y - 0.02f);
  const uint32_t noise_seed = seed * 7919u + 17u;
  fillRegion(v, lo, hi, [&](glm::vec3 p) {
    // Signed "inside-ness" in world units: positive inside the union of blobs.
    float inside = -1e9f;
    for (const Blob& b : blobs) inside = std::max(inside, b.radius - glm::length(p - b.centre));
    // Noise erodes and bulges the rim by up to 0.08 world units (0.16 × [-0.5, 0.5]); the soft
    // rim is 0.12 wide. Outside the reach of both the result is known without the noise.
    if (inside <= -0.08f) return 0.0f;
    // Flat base: cumulus bottoms are level (the condensation height).
    float base = std::clamp((p.y - base_y) / 0.05f, 0.0f, 1.0f);
    if (inside >= 0.2f) return base;
    inside += 0.16f * fractalNoise(p * 6.0f, noise_seed);
    return inside / 0.12f * base;
  });
  return v;
}

Volume makeSparsePuffs(glm::ivec3 dims, uint32_t seed) {
  Volume v(dims);
  SeededRandom rng(seed);
  const uint32_t noise_seed = seed * 104729u + 5u;
  for (int i = 0; i < 20; ++i) {
    Blob b{{rng.uniform(-0.8f, 0.8f), rng.uniform(-0.8f, 0.8f), rng.uniform(-0.8f, 0.8f)},
           rng.uniform(0.05f, 0.11f)};
    fillRegion(v, b.centre - b.radius - 0.02f, b.centre + b.radius + 0.02f, [&](glm::vec3 p) {
      float inside = b.radius - glm::length(p - b.centre);
      inside += 0.03f * fractalNoise(p * 18.0f, noise_seed);
      return inside / (0.4f * b.radius);
    });
  }
  return v;
}

Volume makeSingleVoxel(glm::ivec3 dims, glm::ivec3 voxel, float density) {
  Volume v(dims);
  v.set(voxel.x, voxel.y, voxel.z, density);
  return v;
}

Volume makeSphere(glm::ivec3 dims, glm::vec3 centre, float radius, float density, float soft) {
  Volume v(dims);
  soft = std::max(soft, 1e-6f);
  fillRegion(v, centre - radius, centre + radius, [&](glm::vec3 p) {
    float r = glm::length(p - centre) / radius;  // 0 at the centre, 1 on the surface
    return density * std::clamp((1.0f - r) / soft, 0.0f, 1.0f);
  });
  return v;
}

double filledFraction(const Volume& volume) {
  // Unallocated bricks hold no density; count the allocated ones, brick by brick in parallel.
  const std::vector<glm::ivec3> bricks = volume.allocatedBrickList();
  std::vector<size_t> counts(bricks.size(), 0);
  parallelFor(bricks.size(), 16, [&](size_t, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const float* d = volume.brick(bricks[i]);
      size_t c = 0;
      for (int k = 0; k < Volume::kBrickVoxels; ++k) c += d[k] > 0.0f;
      counts[i] = c;
    }
  });
  size_t total = 0;
  for (size_t c : counts) total += c;
  return double(total) / double(volume.voxelCount());
}

void mergeSoftBall(Volume* v, glm::vec3 centre, float radius) {
  const glm::ivec3 lo = glm::max(glm::ivec3(centre - radius), glm::ivec3(0));
  const glm::ivec3 hi = glm::min(glm::ivec3(centre + radius) + 1, v->dims());
  for (int z = lo.z; z < hi.z; ++z)
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        const float r = glm::length(glm::vec3(x, y, z) + 0.5f - centre) / radius;
        if (r < 1.0f) v->maxMerge(x, y, z, std::min(1.0f, 1.5f * (1.0f - r)));
      }
  v->markDirty({lo, hi});
}

}  // namespace cb
