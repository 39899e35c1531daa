#include "app/render/light_volume.h"

#include <algorithm>
#include <array>
#include <barrier>
#include <cmath>
#include <thread>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

// Attenuation of one voxel of density d over ℓ voxels: (1 − k·d)^ℓ, the per-step factor of
// Alg. 5 line 11 raised to the step length. Clamped so a very dense voxel is black, not NaN.
float voxelAttenuation(float density, float k, float step_length) {
  float f = 1.0f - k * density;
  if (f <= 0.0f) return 0.0f;
  return std::pow(f, step_length);
}

// (1 − k·d)^e tabulated over d in [0, 1] (linear interpolation; 4096 intervals keep the error
// below 1e-6 for the smooth curve) so the sweep needs no pow() per voxel.
class AttenuationTable {
 public:
  AttenuationTable(float k, float exponent) : k_(k), exponent_(exponent) {
    for (int i = 0; i <= kSize; ++i)
      table_[size_t(i)] = voxelAttenuation(float(i) / kSize, k, exponent);
  }
  float operator()(float d) const {
    if (d >= 1.0f) return voxelAttenuation(d, k_, exponent_);
    float x = d * float(kSize);
    int i = int(x);
    float t = x - float(i);
    return table_[size_t(i)] + (table_[size_t(i) + 1] - table_[size_t(i)]) * t;
  }

 private:
  static constexpr int kSize = 4096;
  float k_, exponent_;
  std::array<float, kSize + 1> table_;
};

float trilinearDensity(const Volume& v, glm::vec3 c) {
  // c in continuous voxel space (voxel centres at i + 0.5), clamp-to-edge like the GPU sampler.
  const glm::ivec3 d = v.dims();
  glm::vec3 q = c - 0.5f;
  glm::vec3 f = glm::floor(q);
  glm::vec3 t = q - f;
  glm::ivec3 i0 = glm::clamp(glm::ivec3(f), glm::ivec3(0), d - 1);
  glm::ivec3 i1 = glm::clamp(glm::ivec3(f) + 1, glm::ivec3(0), d - 1);
  auto at = [&](int x, int y, int z) { return v.at(x, y, z); };
  float c00 = at(i0.x, i0.y, i0.z) * (1 - t.x) + at(i1.x, i0.y, i0.z) * t.x;
  float c10 = at(i0.x, i1.y, i0.z) * (1 - t.x) + at(i1.x, i1.y, i0.z) * t.x;
  float c01 = at(i0.x, i0.y, i1.z) * (1 - t.x) + at(i1.x, i0.y, i1.z) * t.x;
  float c11 = at(i0.x, i1.y, i1.z) * (1 - t.x) + at(i1.x, i1.y, i1.z) * t.x;
  return (c00 * (1 - t.y) + c10 * t.y) * (1 - t.z) + (c01 * (1 - t.y) + c11 * t.y) * t.z;
}

// Geometry of a sweep: slices along `axis`, processed from the light side.
struct SweepFrame {
  int axis, b, c;        // slice axis and the two lateral axes
  int first, last, dir;  // slice order: first .. last inclusive, stepping dir (= −upstream step)
  glm::vec3 up;          // voxel-space offset to the upstream point (one slice towards the light)
  float step_length;     // |up|
};

SweepFrame makeFrame(glm::vec3 l, glm::ivec3 dims) {
  SweepFrame f;
  glm::vec3 a = glm::abs(l);
  f.axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  // Lateral axes: b (inner loop) has the smaller memory stride, so rows run along memory.
  f.b = std::min((f.axis + 1) % 3, (f.axis + 2) % 3);
  f.c = std::max((f.axis + 1) % 3, (f.axis + 2) % 3);
  f.up = l / a[f.axis];
  f.step_length = glm::length(f.up);
  bool light_at_high_side = l[f.axis] > 0.0f;
  f.first = light_at_high_side ? dims[f.axis] - 1 : 0;
  f.last = light_at_high_side ? 0 : dims[f.axis] - 1;
  f.dir = light_at_high_side ? -1 : 1;
  return f;
}

}  // namespace

bool LightVolume::matches(const Volume& volume, const Light& light) const {
  return dims == volume.dims() && extinction == light.extinction &&
         direction == lightDirectionInVoxels(volume, light) &&
         transmittance.size() == volume.voxelCount() && through.size() == volume.voxelCount();
}

glm::vec3 lightDirectionInVoxels(const Volume& volume, const Light& light) {
  glm::vec3 centre = 0.5f * (volume.worldMin() + volume.worldMax());
  glm::vec3 world = light.directionFrom(centre);
  return glm::normalize(world / volume.voxelSize());
}

VoxelBox sweepLightVolume(LightVolume& lv, const Volume& volume, const Light& light,
                          const VoxelBox& dirty) {
  const glm::ivec3 dims = volume.dims();
  VoxelBox region = dirty.intersect(volume.bounds());
  if (!lv.matches(volume, light)) {
    lv.dims = dims;
    lv.direction = lightDirectionInVoxels(volume, light);
    lv.extinction = light.extinction;
    // A full sweep writes every voxel, so buffers of the right size are reused as they are.
    lv.transmittance.resize(volume.voxelCount());
    lv.through.resize(volume.voxelCount());
    region = volume.bounds();
  }
  if (region.empty()) return {};
  const SweepFrame f = makeFrame(lv.direction, dims);
  const float k = lv.extinction;
  const glm::vec2 lateral_up(f.up[f.b], f.up[f.c]);
  const glm::ivec2 lateral_dims(dims[f.b], dims[f.c]);
  glm::ivec3 stride(1, dims.x, dims.x * dims.y);
  const size_t sa = size_t(stride[f.axis]), sb = size_t(stride[f.b]), sc = size_t(stride[f.c]);

  // Slices to process: from the dirty box's upstream face to the far edge. The lateral rectangle
  // at j slices downstream of that face is the dirty rectangle shifted by −j·u_lateral, widened by
  // the spread of j chained bilinear lookups (std ≤ √j/2; we keep 4 std + 2 voxels).
  const int start = f.dir < 0 ? region.hi[f.axis] - 1 : region.lo[f.axis];
  const int slices = f.dir < 0 ? start + 1 : dims[f.axis] - start;
  const glm::vec2 rect_lo(region.lo[f.b], region.lo[f.c]);
  const glm::vec2 rect_hi(region.hi[f.b], region.hi[f.c]);
  const bool full = region == volume.bounds();
  auto lateralRect = [&](int j, glm::ivec2* lo, glm::ivec2* hi) {
    if (full) {
      *lo = glm::ivec2(0);
      *hi = lateral_dims;
      return;
    }
    glm::vec2 shift = -float(j) * lateral_up;
    float margin = 2.0f + 2.0f * std::sqrt(float(j));
    glm::vec2 l = rect_lo + glm::min(shift, glm::vec2(0.0f)) - margin;
    glm::vec2 h = rect_hi + glm::max(shift, glm::vec2(0.0f)) + margin;
    *lo = glm::clamp(glm::ivec2(glm::floor(l)), glm::ivec2(0), lateral_dims);
    *hi = glm::clamp(glm::ivec2(glm::ceil(h)), glm::ivec2(0), lateral_dims);
  };

  float* T = lv.through.data();
  float* lit = lv.transmittance.data();
  const float* density = volume.data();
  const AttenuationTable pass_through(k, f.step_length);
  const AttenuationTable own(k, 0.5f * (f.step_length + 1.0f));
  // The upstream point of lateral voxel (b, c) is (b + u_b, c + u_c): the same fractional
  // offsets for every voxel, so the bilinear weights are constants of the sweep.
  const int ob = int(std::floor(lateral_up.x)), oc = int(std::floor(lateral_up.y));
  const float wb = lateral_up.x - float(ob), wc = lateral_up.y - float(oc);
  const int nb = lateral_dims.x, nc = lateral_dims.y;
  // Process one slice's rows [r0, r1) of the lateral rectangle.
  auto sweepRows = [&](int s, glm::ivec2 lo, glm::ivec2 hi, int r0, int r1) {
    const int upstream = s - f.dir;  // slice towards the light
    const bool has_upstream = upstream >= 0 && upstream < dims[f.axis];
    for (int cc = r0; cc < r1; ++cc) {
      // The two upstream rows (nullptr: outside the volume, fully lit).
      const float* row[2] = {nullptr, nullptr};
      for (int r = 0; r < 2; ++r) {
        int c = cc + oc + r;
        if (has_upstream && c >= 0 && c < nc) row[r] = T + size_t(upstream) * sa + size_t(c) * sc;
      }
      auto at = [&](const float* r, int b) {
        return (r && b >= 0 && b < nb) ? r[size_t(b) * sb] : 1.0f;
      };
      const size_t base = size_t(s) * sa + size_t(cc) * sc;
      // Interior voxels need no bounds checks on b.
      const int inner_lo = std::clamp(-ob, lo.x, hi.x),
                inner_hi = std::clamp(nb - 1 - ob, lo.x, hi.x);
      auto voxel = [&](int bb, float t_up) {
        size_t idx = base + size_t(bb) * sb;
        float d = density[idx];
        if (d > 0.0f) {
          T[idx] = t_up * pass_through(d);
          lit[idx] = t_up * own(d);
        } else {
          T[idx] = lit[idx] = t_up;
        }
      };
      auto edgeVoxel = [&](int bb) {
        float t_up = (at(row[0], bb + ob) * (1 - wb) + at(row[0], bb + ob + 1) * wb) * (1 - wc) +
                     (at(row[1], bb + ob) * (1 - wb) + at(row[1], bb + ob + 1) * wb) * wc;
        voxel(bb, t_up);
      };
      for (int bb = lo.x; bb < std::min(inner_lo, hi.x); ++bb) edgeVoxel(bb);
      if (row[0] && row[1]) {
        for (int bb = inner_lo; bb < inner_hi; ++bb) {
          size_t o = size_t(bb + ob) * sb;
          float t_up = (row[0][o] * (1 - wb) + row[0][o + sb] * wb) * (1 - wc) +
                       (row[1][o] * (1 - wb) + row[1][o + sb] * wb) * wc;
          voxel(bb, t_up);
        }
      } else {
        for (int bb = inner_lo; bb < inner_hi; ++bb) edgeVoxel(bb);
      }
      for (int bb = std::max(inner_hi, lo.x); bb < hi.x; ++bb) edgeVoxel(bb);
    }
  };

  // Slices depend on their upstream neighbour, so threads split each slice's rows and meet at a
  // barrier between slices. Every voxel's value is independent of the split (deterministic).
  const int threads = std::max(1, std::min(workerThreads(), 16));
  glm::ivec2 all_lo(lateral_dims), all_hi(0);
  auto worker = [&](int id, std::barrier<>* sync) {
    for (int j = 0; j < slices; ++j) {
      int s = start + j * f.dir;
      glm::ivec2 lo, hi;
      lateralRect(j, &lo, &hi);
      int rows = std::max(0, hi.y - lo.y);
      int r0 = lo.y + rows * id / threads, r1 = lo.y + rows * (id + 1) / threads;
      if (hi.x > lo.x) sweepRows(s, lo, hi, r0, r1);
      if (sync) sync->arrive_and_wait();
    }
  };
  if (threads == 1) {
    worker(0, nullptr);
  } else {
    std::barrier<> sync(threads);
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker, i, &sync);
    worker(0, &sync);
    for (auto& t : pool) t.join();
  }
  // The rewritten box: the union of the per-slice rectangles.
  for (int j = 0; j < slices; ++j) {
    glm::ivec2 lo, hi;
    lateralRect(j, &lo, &hi);
    all_lo = glm::min(all_lo, lo);
    all_hi = glm::max(all_hi, hi);
  }
  VoxelBox out;
  out.lo[f.axis] = f.dir < 0 ? 0 : start;
  out.hi[f.axis] = f.dir < 0 ? start + 1 : dims[f.axis];
  out.lo[f.b] = all_lo.x;
  out.hi[f.b] = all_hi.x;
  out.lo[f.c] = all_lo.y;
  out.hi[f.c] = all_hi.y;
  return out.intersect(volume.bounds());
}

std::vector<float> marchLightReference(const Volume& volume, const Light& light, int z_step) {
  z_step = std::max(1, z_step);
  const glm::ivec3 dims = volume.dims();
  const glm::vec3 l = lightDirectionInVoxels(volume, light);
  const glm::vec3 extent(dims);
  std::vector<float> out(volume.voxelCount(), -1.0f);
  parallelFor(size_t(dims.z), 1, [&](size_t, size_t z0, size_t z1) {
    for (int z = int(z0); z < int(z1); ++z)
      for (int y = 0; y < dims.y && z % z_step == 0; ++y)
        for (int x = 0; x < dims.x; ++x) {
          glm::vec3 start = glm::vec3(x, y, z) + 0.5f;
          float t = 1.0f;
          // Alg. 5: walk unit steps towards the light until leaving the box.
          for (int i = 0;; ++i) {
            glm::vec3 p = start + float(i) * l;
            if (glm::any(glm::lessThan(p, glm::vec3(0.0f))) ||
                glm::any(glm::greaterThan(p, extent)))
              break;
            float d = trilinearDensity(volume, p);
            t *= std::max(0.0f, 1.0f - light.extinction * d);
            if (t == 0.0f) break;
          }
          out[volume.index(x, y, z)] = t;
        }
  });
  return out;
}

float thesisStrength(float transmittance) {
  const float illuminance = 1.0f - transmittance;  // I, the inverted value of Alg. 5 line 13
  return 0.55f + std::cos(0.4f - illuminance * 3.14159265f) / 2.2f;
}

}  // namespace cb
