#include "app/render/light_volume.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <barrier>
#include <cmath>
#include <thread>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

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

// The two per-voxel factors of the sweep, (1 − k·d)^ℓ (passed on downstream) and
// (1 − k·d)^((ℓ+1)/2) (the voxel's own value), tabulated over d in [0, 1] with slopes for
// linear interpolation: one 16-byte entry per lookup, 1024 intervals (16 KiB, stays in L1; the
// interpolation error of the smooth curve is below 1e-8). Densities outside [0, 1] take the
// exact (slow) path; d ≤ 0 and NaN attenuate nothing.
class AttenuationPair {
 public:
  AttenuationPair(float k, float pass_exponent, float own_exponent)
      : k_(k), pass_exponent_(pass_exponent), own_exponent_(own_exponent) {
    for (int i = 0; i < kSize; ++i) {
      float d0 = float(i) / kSize, d1 = float(i + 1) / kSize;
      float p0 = voxelAttenuation(d0, k, pass_exponent),
            p1 = voxelAttenuation(d1, k, pass_exponent);
      float o0 = voxelAttenuation(d0, k, own_exponent), o1 = voxelAttenuation(d1, k, own_exponent);
      table_[size_t(i)] = {p0, p1 - p0, o0, o1 - o0};
    }
    // d = 1 exactly (common inside a cloud) lands on the last entry with t = 0.
    table_[kSize] = {voxelAttenuation(1.0f, k, pass_exponent), 0.0f,
                     voxelAttenuation(1.0f, k, own_exponent), 0.0f};
  }
  // Writes t_up·(1 − k·d)^ℓ to *through and t_up·(1 − k·d)^((ℓ+1)/2) to *own.
  void attenuate(float d, float t_up, float* through, float* own) const {
    if (d >= 0.0f && d <= 1.0f) [[likely]] {
      const float x = d * float(kSize);
      const int i = int(x);
      const float t = x - float(i);
      const Entry& e = table_[size_t(i)];
      *through = t_up * (e.pass + e.pass_slope * t);
      *own = t_up * (e.own + e.own_slope * t);
    } else if (d > 0.0f) {
      *through = t_up * voxelAttenuation(d, k_, pass_exponent_);
      *own = t_up * voxelAttenuation(d, k_, own_exponent_);
    } else {
      *through = *own = t_up;
    }
  }

  // The table as 4 floats per entry (pass, pass slope, own, own slope) for vector gathers.
  const float* entries() const { return &table_[0].pass; }
  static constexpr int kEntries = 1024;

 private:
  struct Entry {
    float pass, pass_slope, own, own_slope;
  };
  static_assert(sizeof(Entry) == 4 * sizeof(float));
  static constexpr int kSize = kEntries;
  float k_, pass_exponent_, own_exponent_;
  std::array<Entry, kSize + 1> table_;
};

// One interior run of a row whose voxels are contiguous (b is the x axis): voxel i reads the
// upstream rows at i and i + 1. Separate restrict-qualified pointers let the compiler keep them
// in registers (the general loop reloads its captures after every store). The bilinear
// expression is the same as sweepLightVolume's general path, so both give identical bits.
void sweepContiguousRunScalar(const float* __restrict up0, const float* __restrict up1,
                              const float* __restrict density, float* __restrict through,
                              float* __restrict lit, int count, float wb, float wc,
                              const AttenuationPair& attenuation) {
  for (int i = 0; i < count; ++i) {
    const float t_up = (up0[i] * (1 - wb) + up0[i + 1] * wb) * (1 - wc) +
                       (up1[i] * (1 - wb) + up1[i + 1] * wb) * wc;
    attenuation.attenuate(density[i], t_up, &through[i], &lit[i]);
  }
}

#if defined(__x86_64__)
// The same run, 8 voxels at a time with AVX2 (gathers for the table), for CPUs that have it.
// Written with separate multiplies and adds in the scalar order and compiled without FMA, so it
// gives the scalar path's bits exactly. Blocks with a density outside [0, 1] go the scalar way.
__attribute__((target("avx2"))) void sweepContiguousRunAvx2(
    const float* __restrict up0, const float* __restrict up1, const float* __restrict density,
    float* __restrict through, float* __restrict lit, int count, float wb, float wc,
    const AttenuationPair& attenuation) {
  const __m256 wb1 = _mm256_set1_ps(1 - wb), wb0 = _mm256_set1_ps(wb);
  const __m256 wc1 = _mm256_set1_ps(1 - wc), wc0 = _mm256_set1_ps(wc);
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 scale = _mm256_set1_ps(float(AttenuationPair::kEntries));
  const float* table = attenuation.entries();
  int i = 0;
  for (; i + 8 <= count; i += 8) {
    const __m256 d = _mm256_loadu_ps(density + i);
    const __m256 in_range =
        _mm256_and_ps(_mm256_cmp_ps(d, zero, _CMP_GE_OQ), _mm256_cmp_ps(d, one, _CMP_LE_OQ));
    if (_mm256_movemask_ps(in_range) != 0xff) {
      sweepContiguousRunScalar(up0 + i, up1 + i, density + i, through + i, lit + i, 8, wb, wc,
                               attenuation);
      continue;
    }
    const __m256 row0 = _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(up0 + i), wb1),
                                      _mm256_mul_ps(_mm256_loadu_ps(up0 + i + 1), wb0));
    const __m256 row1 = _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(up1 + i), wb1),
                                      _mm256_mul_ps(_mm256_loadu_ps(up1 + i + 1), wb0));
    const __m256 t_up = _mm256_add_ps(_mm256_mul_ps(row0, wc1), _mm256_mul_ps(row1, wc0));
    const __m256 x = _mm256_mul_ps(d, scale);
    const __m256i index = _mm256_cvttps_epi32(x);
    const __m256 t = _mm256_sub_ps(x, _mm256_cvtepi32_ps(index));
    const __m256i entry = _mm256_slli_epi32(index, 2);
    const __m256 pass = _mm256_i32gather_ps(table, entry, 4);
    const __m256 pass_slope = _mm256_i32gather_ps(table + 1, entry, 4);
    const __m256 own = _mm256_i32gather_ps(table + 2, entry, 4);
    const __m256 own_slope = _mm256_i32gather_ps(table + 3, entry, 4);
    _mm256_storeu_ps(through + i,
                     _mm256_mul_ps(t_up, _mm256_add_ps(pass, _mm256_mul_ps(pass_slope, t))));
    _mm256_storeu_ps(lit + i, _mm256_mul_ps(t_up, _mm256_add_ps(own, _mm256_mul_ps(own_slope, t))));
  }
  sweepContiguousRunScalar(up0 + i, up1 + i, density + i, through + i, lit + i, count - i, wb, wc,
                           attenuation);
}
#endif

void sweepContiguousRun(const float* up0, const float* up1, const float* density, float* through,
                        float* lit, int count, float wb, float wc,
                        const AttenuationPair& attenuation) {
#if defined(__x86_64__)
  static const bool has_avx2 = __builtin_cpu_supports("avx2");
  if (has_avx2)
    return sweepContiguousRunAvx2(up0, up1, density, through, lit, count, wb, wc, attenuation);
#endif
  sweepContiguousRunScalar(up0, up1, density, through, lit, count, wb, wc, attenuation);
}

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

// A lateral rectangle [lo, hi) of a slice (b, c coordinates).
struct Rect {
  glm::ivec2 lo{0}, hi{0};
  bool empty() const { return hi.x <= lo.x || hi.y <= lo.y; }
  int area() const { return empty() ? 0 : (hi.x - lo.x) * (hi.y - lo.y); }
  Rect unite(const Rect& o) const {
    if (empty()) return o;
    if (o.empty()) return *this;
    return {glm::min(lo, o.lo), glm::max(hi, o.hi)};
  }
  Rect intersect(const Rect& o) const { return {glm::max(lo, o.lo), glm::min(hi, o.hi)}; }
};

// An incremental sweep follows a change downstream only while it exceeds this (see
// sweepLightVolume); 256 slices of it stay far below the 1e-2 accuracy bound.
constexpr float kChangeEpsilon = 0.0f;  // any change: updates equal a full recompute bit for bit
// Slices (and edits) with a smaller lateral area are swept by one thread.
constexpr int kThreadedArea = 64 * 64;
// Slices a plane of the full sweep publishes at a time to the thread sweeping the next plane.
constexpr int kPlaneBatch = 16;

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
  return glm::normalize(light.direction / volume.voxelSize());
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
  const bool full = region == volume.bounds();

  // Slices to process: from the dirty box's upstream face towards the far edge. The first
  // `dirty_slices` slices hold the dirty box; beyond it, a slice's rectangle is the set of voxels
  // whose bilinear upstream footprint meets a voxel whose passed-on transmittance changed in the
  // previous slice (by more than kChangeEpsilon, which is 0), so the update follows the actual
  // shadow of the edit and stops where it no longer changes anything or falls into shadow that is
  // already black. Voxels left alone are exactly what a full recompute gives, so undo/redo
  // restore the light volume bit for bit (app/session/history.h).
  const int start = f.dir < 0 ? region.hi[f.axis] - 1 : region.lo[f.axis];
  const int slices = f.dir < 0 ? start + 1 : dims[f.axis] - start;
  const int dirty_slices = region.hi[f.axis] - region.lo[f.axis];
  const Rect dirty_rect{{region.lo[f.b], region.lo[f.c]}, {region.hi[f.b], region.hi[f.c]}};
  const Rect all{glm::ivec2(0), lateral_dims};

  float* T = lv.through.data();
  float* lit = lv.transmittance.data();
  const AttenuationPair attenuation(k, f.step_length, 0.5f * (f.step_length + 1.0f));
  // The upstream point of lateral voxel (b, c) is (b + u_b, c + u_c): the same fractional
  // offsets for every voxel, so the bilinear weights are constants of the sweep.
  const int ob = int(std::floor(lateral_up.x)), oc = int(std::floor(lateral_up.y));
  const float wb = lateral_up.x - float(ob), wc = lateral_up.y - float(oc);
  const int nb = lateral_dims.x, nc = lateral_dims.y;
  // Process one slice's rows [r0, r1) of rectangle `rect`; with `kTrack`, returns the bounding
  // rectangle of the voxels whose passed-on transmittance changed.
  auto sweepRows = [&]<bool kTrack>(int s, Rect rect, int r0, int r1) {
    Rect changed;
    const int upstream = s - f.dir;  // slice towards the light
    const bool has_upstream = upstream >= 0 && upstream < dims[f.axis];
    const glm::ivec2 lo = rect.lo, hi = rect.hi;
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
      // This row's densities [lo.x, hi.x) along b, read out of the volume's bricks.
      thread_local std::vector<float> density_row;
      density_row.resize(size_t(std::max(hi.x - lo.x, 0)));
      if (hi.x > lo.x) {
        glm::ivec3 first;
        first[f.axis] = s;
        first[f.c] = cc;
        first[f.b] = lo.x;
        volume.readLine(first, f.b, hi.x - lo.x, density_row.data());
      }
      const float* density = density_row.data();  // [bb - lo.x]
      int changed_lo = hi.x, changed_hi = lo.x;
      // Interior voxels need no bounds checks on b.
      const int inner_lo = std::clamp(-ob, lo.x, hi.x),
                inner_hi = std::clamp(nb - 1 - ob, lo.x, hi.x);
      auto voxel = [&](int bb, float t_up) {
        size_t idx = base + size_t(bb) * sb;
        float through, own_t;
        attenuation.attenuate(density[bb - lo.x], t_up, &through, &own_t);
        if constexpr (kTrack) {
          if (std::abs(through - T[idx]) > kChangeEpsilon) {
            changed_lo = std::min(changed_lo, bb);
            changed_hi = bb + 1;
          }
        }
        T[idx] = through;
        lit[idx] = own_t;
      };
      auto edgeVoxel = [&](int bb) {
        float t_up = (at(row[0], bb + ob) * (1 - wb) + at(row[0], bb + ob + 1) * wb) * (1 - wc) +
                     (at(row[1], bb + ob) * (1 - wb) + at(row[1], bb + ob + 1) * wb) * wc;
        voxel(bb, t_up);
      };
      for (int bb = lo.x; bb < std::min(inner_lo, hi.x); ++bb) edgeVoxel(bb);
      if (sb == 1 && row[0] && row[1] && inner_hi > inner_lo) {
        const size_t i0 = base + size_t(inner_lo);
        const int count = inner_hi - inner_lo;
        // Tracking compares with the old values afterwards (kept per thread), so the run itself
        // stays the fast one.
        thread_local std::vector<float> old_row;
        if constexpr (kTrack) old_row.assign(T + i0, T + i0 + count);
        sweepContiguousRun(row[0] + inner_lo + ob, row[1] + inner_lo + ob,
                           density + (inner_lo - lo.x), T + i0, lit + i0, count, wb, wc,
                           attenuation);
        if constexpr (kTrack) {
          auto moved = [&](int i) {
            return std::abs(T[i0 + size_t(i)] - old_row[size_t(i)]) > kChangeEpsilon;
          };
          int first = 0;
          while (first < count && !moved(first)) ++first;
          if (first < count) {
            int last = count - 1;
            while (!moved(last)) --last;
            changed_lo = std::min(changed_lo, inner_lo + first);
            changed_hi = std::max(changed_hi, inner_lo + last + 1);
          }
        }
      } else if (row[0] && row[1]) {
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
      if (kTrack && changed_hi > changed_lo)
        changed = changed.unite(Rect{{changed_lo, cc}, {changed_hi, cc + 1}});
    }
    return changed;
  };

  // The voxels of the next slice whose upstream footprint (b + ob + {0,1}, c + oc + {0,1})
  // meets `changed`.
  auto downstreamOf = [&](Rect changed) {
    if (changed.empty()) return Rect{};
    return Rect{changed.lo - glm::ivec2(ob, oc) - 1, changed.hi - glm::ivec2(ob, oc)}.intersect(
        all);
  };

  // Slices depend on their upstream neighbour, so threads split each slice's rows and meet at a
  // barrier between slices. Small edits run on one thread (a barrier per slice costs more than
  // they do). Each thread's changed rectangle is double-buffered by slice parity, so one barrier
  // per slice suffices; every voxel's value is independent of the split (deterministic).
  const int lateral_area =
      (dirty_rect.hi.x - dirty_rect.lo.x) * (dirty_rect.hi.y - dirty_rect.lo.y);
  const int threads =
      (full || lateral_area >= kThreadedArea) ? std::max(1, std::min(workerThreads(), 16)) : 1;
  std::vector<Rect> changed_by_thread(size_t(2 * threads));
  std::vector<Rect> swept(
      static_cast<size_t>(slices));  // the rectangle of each slice (written by thread 0)
  auto worker = [&](int id, std::barrier<>* sync) {
    for (int j = 0; j < slices; ++j) {
      Rect rect = all;
      if (!full) {
        Rect changed;
        if (j > 0)
          for (int t = 0; t < threads; ++t)
            changed = changed.unite(changed_by_thread[size_t(2 * t + (j - 1) % 2)]);
        rect = downstreamOf(changed);
        if (j < dirty_slices) rect = rect.unite(dirty_rect);
        if (rect.empty()) break;  // every thread sees the same rectangles and stops together
      }
      const int s = start + j * f.dir;
      const int rows = rect.hi.y - rect.lo.y;
      const int share = rect.area() < kThreadedArea ? (id == 0 ? 1 : 0) : 1;
      const int parts = rect.area() < kThreadedArea ? 1 : threads;
      const int part = rect.area() < kThreadedArea ? 0 : id;
      int r0 = rect.lo.y + rows * part / parts, r1 = rect.lo.y + rows * (part + 1) / parts;
      if (!share) r1 = r0;
      Rect changed = full ? sweepRows.template operator()<false>(s, rect, r0, r1)
                          : sweepRows.template operator()<true>(s, rect, r0, r1);
      changed_by_thread[size_t(2 * id + j % 2)] = changed;
      if (id == 0) swept[size_t(j)] = rect;
      if (sync) sync->arrive_and_wait();
    }
  };
  if (full && f.axis != 2) {
    // A full sweep along x or y: its slices are strided in memory (1 KiB runs 256 KiB apart at
    // 256³), which costs more than the arithmetic. Row c of a slice reads rows c + oc and
    // c + oc + 1 of the slice upstream, and |u_c| ≤ 1, so whole row planes (c fixed, all slices,
    // contiguous in memory as c is the z axis) can be swept one after another, from the side
    // the upstream rows lie on. Same voxel values as the slice order.
    // Threads take planes in turn (plane i on thread i % threads) and run as a pipeline: plane
    // i's slice j reads plane i − 1 at slice j − 1, so a thread waits until the previous plane
    // has published that far (in batches of kPlaneBatch slices). Values do not depend on it.
    const bool descending = oc >= 0;
    std::vector<std::atomic<int>> progress(
        static_cast<size_t>(nc));  // slices done per plane (in order)
    for (auto& p : progress) p.store(0, std::memory_order_relaxed);
    auto planeWorker = [&](int id) {
      for (int i = id; i < nc; i += threads) {
        const int c = descending ? nc - 1 - i : i;
        for (int j0 = 0; j0 < slices; j0 += kPlaneBatch) {
          const int j1 = std::min(slices, j0 + kPlaneBatch);
          if (i > 0) {
            std::atomic<int>& previous = progress[size_t(i - 1)];
            for (int done = previous.load(std::memory_order_acquire); done < j1;
                 done = previous.load(std::memory_order_acquire))
              previous.wait(done, std::memory_order_acquire);
          }
          for (int j = j0; j < j1; ++j)
            sweepRows.template operator()<false>(start + j * f.dir, all, c, c + 1);
          progress[size_t(i)].store(j1, std::memory_order_release);
          progress[size_t(i)].notify_all();
        }
      }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(planeWorker, i);
    planeWorker(0);
    for (auto& t : pool) t.join();
    return volume.bounds();
  }
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
  Rect lateral;
  int last = -1;
  for (int j = 0; j < slices; ++j) {
    if (swept[size_t(j)].empty()) continue;
    lateral = lateral.unite(swept[size_t(j)]);
    last = j;
  }
  if (last < 0) return {};
  VoxelBox out;
  const int end = start + last * f.dir;
  out.lo[f.axis] = std::min(start, end);
  out.hi[f.axis] = std::max(start, end) + 1;
  out.lo[f.b] = lateral.lo.x;
  out.hi[f.b] = lateral.hi.x;
  out.lo[f.c] = lateral.lo.y;
  out.hi[f.c] = lateral.hi.y;
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
