#include "app/render/light_volume.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <barrier>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <utility>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "app/core/parallel_for.h"
#include "app/volume/brick_table_shift.h"

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

// An incremental sweep follows a change downstream while it exceeds this: 0, any change, so
// updates equal a full recompute bit for bit.
constexpr float kChangeEpsilon = 0.0f;
// Edits with a smaller lateral area are swept by one thread.
constexpr int kThreadedArea = 64 * 64;
// Slices a tile row of the full sweep publishes at a time to the thread sweeping the next row.
constexpr int kRowBatch = 16;
constexpr int kTile = Volume::kBrickSize;  // a tile is a brick's 16×16 cross-section

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

// How many slices of each brick column along the sweep's axis (lateral tile tb + ntb·tc),
// counted from the light side in sweep order, store their light. A column stores down to its
// most downstream light brick (lightBrickList: an allocated brick or a neighbour, so one layer
// past an allocated brick, in its own column and the 8 around it); further downstream its shadow
// falls on nothing the renderer reads. A stored tile reads the upstream slice in tiles t + δ,
// δ ∈ {lo_b, lo_b + 1} × {lo_c, lo_c + 1} (lo = −1 where the upstream offset is negative, else
// 0), so a column stores at least as deep as every column it reads: the depths are a running
// maximum over those offsets. Unstored tiles are read only by unstored tiles, and the sweep
// reads only upstream, so they are neither computed nor stored (all 0 for an empty volume).
void closeStoredDepths(std::vector<int>& depth, int ntb, int ntc, int ob, int oc);

std::vector<int> storedSlices(const Volume& volume, const SweepFrame& f, int ob, int oc) {
  const glm::ivec3 bd = volume.brickDims();
  const int layers = bd[f.axis], n = volume.dims()[f.axis], ntb = bd[f.b], ntc = bd[f.c];
  std::vector<int> depth(size_t(ntb) * size_t(ntc), 0);
  for (const glm::ivec3 b : volume.allocatedBrickList()) {
    const int below = std::clamp(b[f.axis] + f.dir, 0, layers - 1);  // one layer downstream
    const int end =
        f.dir < 0 ? n - below * Volume::kBrickSize : std::min(n, (below + 1) * Volume::kBrickSize);
    for (int tc = std::max(0, b[f.c] - 1); tc <= std::min(ntc - 1, b[f.c] + 1); ++tc)
      for (int tb = std::max(0, b[f.b] - 1); tb <= std::min(ntb - 1, b[f.b] + 1); ++tb) {
        int& d = depth[size_t(tc) * size_t(ntb) + size_t(tb)];
        d = std::max(d, end);
      }
  }
  closeStoredDepths(depth, ntb, ntc, ob, oc);
  return depth;
}

// The running maximum of storedSlices over a column's readers: a column t reads t + δ,
// δ ∈ {lo_b, lo_b + 1} × {lo_c, lo_c + 1}, so depth(t + δ) ≥ depth(t) for every δ.
void closeStoredDepths(std::vector<int>& depth, int ntb, int ntc, int ob, int oc) {
  // depth(t + δ) ≥ depth(t): visit t before t + δ and pull from t − δ.
  const int lo_b = ob < 0 ? -1 : 0, lo_c = oc < 0 ? -1 : 0;
  for (int jc = 0; jc < ntc; ++jc) {
    const int tc = lo_c < 0 ? ntc - 1 - jc : jc;
    for (int jb = 0; jb < ntb; ++jb) {
      const int tb = lo_b < 0 ? ntb - 1 - jb : jb;
      int& d = depth[size_t(tc) * size_t(ntb) + size_t(tb)];
      for (int dc = lo_c; dc <= lo_c + 1; ++dc)
        for (int db = lo_b; db <= lo_b + 1; ++db) {
          const int pb = tb - db, pc = tc - dc;
          if ((db || dc) && pb >= 0 && pb < ntb && pc >= 0 && pc < ntc)
            d = std::max(d, depth[size_t(pc) * size_t(ntb) + size_t(pb)]);
        }
    }
  }
}

// The sweep over 16×16 tiles of a slice (a tile of slice s is the cross-section of one brick).
// processTile computes a rectangle inside one tile from the upstream slice, exactly as the dense
// sweep did voxel by voxel: the same bilinear expression, the same attenuation, so the same bits.
struct TileSweep {
  const Volume& volume;
  LightVolume& lv;
  const SweepFrame& f;
  const AttenuationPair& attenuation;
  int na, nb, nc;     // slices, lateral sizes
  int ob, oc;         // integer part of the upstream offset (each −1, 0 or 1)
  float wb, wc;       // its fractional part: the bilinear weights, constants of the sweep
  size_t sa, sb, sc;  // in-brick strides of the slice axis and the lateral axes
  // Per brick (LightBricks::brickIndex), the slots reading a voxel where LightVolume::at now
  // rounds to another 8-bit value (unorm8) than before (LightByteChanges::Brick::readers);
  // nullptr: not tracked. Tiles of one slice are distinct bricks and slices are separated by a
  // barrier, so plain byte stores do not race.
  uint8_t* changed_bytes = nullptr;

  glm::ivec3 brickCoord(int s, int tb, int tc) const {
    glm::ivec3 v;
    v[f.axis] = s >> Volume::kBrickShift;
    v[f.b] = tb;
    v[f.c] = tc;
    return v;
  }
  size_t offset(int s, int b, int c) const {
    constexpr int m = kTile - 1;
    return size_t(s & m) * sa + size_t(b & m) * sb + size_t(c & m) * sc;
  }

  // Marks in changed_bytes[bi] the slots (LightByteChanges::Brick::readers) that read a voxel of
  // rectangle r's `rows` rows where `values` (row stride `stride`) rounds to another 8-bit value
  // than `dst` holds: the slots reading voxel v are brick − δ for each δ whose axes all have
  // v_i < kLowVoxels.
  void markChangedReaders(size_t bi, int s, Rect r, const float* dst, const float* values, int rows,
                          size_t stride) const {
    static constexpr std::array<uint8_t, 8> kReaders = [] {
      std::array<uint8_t, 8> t{};
      for (int low = 0; low < 8; ++low)
        for (int d = 0; d < 8; ++d)
          if ((d & ~low) == 0) t[size_t(low)] |= uint8_t(1 << d);
      return t;
    }();
    constexpr int m = kTile - 1, kLow = LightByteChanges::kLowVoxels;
    uint8_t& readers = changed_bytes[bi];
    for (int rr = 0; rr < rows; ++rr) {
      const float* d = dst + offset(s, r.lo.x, r.lo.y + rr);
      const float* v = values + rr * stride;
      const int row_low =
          ((s & m) < kLow ? 1 << f.axis : 0) | (((r.lo.y + rr) & m) < kLow ? 1 << f.c : 0);
      for (int i = 0; i < r.hi.x - r.lo.x; ++i)
        if (unorm8(d[size_t(i) * sb]) != unorm8(v[i])) {
          readers |= kReaders[size_t(row_low | (((r.lo.x + i) & m) < kLow ? 1 << f.b : 0))];
          if (readers == 0xFF) return;
        }
    }
  }

  // The upstream footprint of rectangle r of slice s: [fb0, fb1) × [fc0, fc1) in slice s − dir,
  // the part of it inside the grid [gb0, gb1) × [gc0, gc1), and the (up to 2×2) upstream bricks
  // it covers from brick (ub0, uc0) (null where absent: all 1).
  struct Footprint {
    int su = 0, fb0 = 0, fc0 = 0, gb0 = 0, gb1 = 0, gc0 = 0, gc1 = 0, ub0 = 0, uc0 = 0;
    bool inside = false;   // an upstream slice exists and the footprint meets the grid
    bool all_ones = true;  // no upstream brick is allocated
    const float* bricks[2][2] = {{nullptr, nullptr}, {nullptr, nullptr}};
  };
  Footprint upstreamFootprint(int s, Rect r) const {
    Footprint u;
    u.su = s - f.dir;
    const bool has_upstream = u.su >= 0 && u.su < na;
    u.fb0 = r.lo.x + ob;
    u.fc0 = r.lo.y + oc;
    u.gb0 = std::max(u.fb0, 0);
    u.gb1 = std::min(r.hi.x + ob + 1, nb);
    u.gc0 = std::max(u.fc0, 0);
    u.gc1 = std::min(r.hi.y + oc + 1, nc);
    u.inside = has_upstream && u.gb1 > u.gb0 && u.gc1 > u.gc0;
    u.ub0 = u.gb0 >> Volume::kBrickShift;
    u.uc0 = u.gc0 >> Volume::kBrickShift;
    if (u.inside)
      for (int j = 0; j <= ((u.gc1 - 1) >> Volume::kBrickShift) - u.uc0; ++j)
        for (int i = 0; i <= ((u.gb1 - 1) >> Volume::kBrickShift) - u.ub0; ++i) {
          u.bricks[j][i] =
              lv.through.get(lv.through.brickIndex(brickCoord(u.su, u.ub0 + i, u.uc0 + j)));
          if (u.bricks[j][i]) u.all_ones = false;
        }
    return u;
  }

  // The upstream values over the footprint, pw × ph, row by row (1 outside the grid and in
  // absent bricks).
  void fillPatch(const Footprint& u, int pw, int ph, std::vector<float>* patch) const {
    patch->assign(size_t(pw * ph), 1.0f);
    if (!u.inside) return;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const float* p = u.bricks[j][i];
        if (!p) continue;
        const int b0 = std::max(u.gb0, (u.ub0 + i) * kTile),
                  b1 = std::min(u.gb1, (u.ub0 + i + 1) * kTile);
        const int c0 = std::max(u.gc0, (u.uc0 + j) * kTile),
                  c1 = std::min(u.gc1, (u.uc0 + j + 1) * kTile);
        for (int c = c0; c < c1; ++c) {
          float* row = patch->data() + size_t((c - u.fc0) * pw) + (b0 - u.fb0);
          const float* src = p + offset(u.su, b0, c);
          for (int b = 0; b < b1 - b0; ++b) row[b] = src[size_t(b) * sb];
        }
      }
  }

  // Stores the passed-on values (row stride kTile) into rectangle r of `through`; with `track`,
  // unites the voxels whose value changed into *changed.
  void storeThrough(float* through, int s, Rect r, int rows, const float* passed, bool track,
                    Rect* changed) const {
    const int n = r.hi.x - r.lo.x;
    for (int rr = 0; rr < rows; ++rr) {
      float* dst = through + offset(s, r.lo.x, r.lo.y + rr);
      const float* values = passed + rr * kTile;
      if (track) {
        int changed_lo = n, changed_hi = 0;
        for (int i = 0; i < n; ++i)
          if (std::abs(values[i] - dst[size_t(i) * sb]) > kChangeEpsilon) {
            changed_lo = std::min(changed_lo, i);
            changed_hi = i + 1;
          }
        if (changed_hi > changed_lo)
          *changed = changed->unite(
              Rect{{r.lo.x + changed_lo, r.lo.y + rr}, {r.lo.x + changed_hi, r.lo.y + rr + 1}});
      }
      for (int i = 0; i < n; ++i) dst[size_t(i) * sb] = values[i];
    }
  }

  // Sweeps rectangle r (inside tile (tb, tc) and the grid) of slice s. With `track`, unites the
  // voxels whose passed-on value changed into *changed. Returns whether a passed-on value is not 1.
  bool processTile(int s, int tb, int tc, Rect r, bool track, Rect* changed) const {
    const glm::ivec3 brick = brickCoord(s, tb, tc);
    const size_t bi = lv.through.brickIndex(brick);
    const float* density_brick = volume.brick(brick);
    // `at` reads lit where the volume holds the brick, else through. Whether a rewrite changes
    // what it reads in 8 bits (once a brick is marked its other rewrites are not compared).
    const bool compare = changed_bytes && changed_bytes[bi] != 0xFF;
    if (!density_brick && lv.lit.get(bi)) {
      lv.lit.release(bi);  // freed: T is the passed-on value
      if (changed_bytes) changed_bytes[bi] = 0xFF;
    }
    float* through = lv.through.getForWrite(bi);
    const Footprint u = upstreamFootprint(s, r);
    // No density, an upstream all 1 and a tile all 1 before: it stays all 1.
    if (!density_brick && u.all_ones && !through) return false;

    const int pw = r.hi.x - r.lo.x + 1, ph = r.hi.y - r.lo.y + 1;
    thread_local std::vector<float> patch;
    fillPatch(u, pw, ph, &patch);

    const int n = r.hi.x - r.lo.x, rows = ph - 1;
    float density[kTile], passed[kTile * kTile], own[kTile * kTile];
    bool not_one = false;
    for (int rr = 0; rr < rows; ++rr) {
      if (density_brick) {
        const float* src = density_brick + offset(s, r.lo.x, r.lo.y + rr);
        for (int i = 0; i < n; ++i) density[i] = src[size_t(i) * sb];
      } else {
        std::fill(density, density + n, 0.0f);
      }
      const float* up0 = patch.data() + size_t(rr * pw);
      float* out = passed + rr * kTile;
      sweepContiguousRun(up0, up0 + pw, density, out, own + rr * kTile, n, wb, wc, attenuation);
      for (int i = 0; i < n; ++i) not_one |= out[i] != 1.0f;
    }
    if (!through && not_one) through = lv.through.create(bi);  // all 1, as `at` read it
    if (through && compare && !density_brick)
      markChangedReaders(bi, s, r, through, passed, rows, kTile);
    if (through) storeThrough(through, s, r, rows, passed, track, changed);
    if (density_brick) {
      // A brick new to the lit set: its voxels outside this sweep hold no density (they were
      // not in an allocated brick and did not change), so their T is the passed-on value.
      float* lit = lv.lit.getForWrite(bi);
      if (!lit) {
        lit = lv.lit.create(bi, through);
        if (changed_bytes) changed_bytes[bi] = 0xFF;  // `at` switches from through to lit
      }
      if (compare) markChangedReaders(bi, s, r, lit, own, rows, kTile);
      for (int rr = 0; rr < rows; ++rr) {
        float* dst = lit + offset(s, r.lo.x, r.lo.y + rr);
        for (int i = 0; i < n; ++i) dst[size_t(i) * sb] = own[rr * kTile + i];
      }
    }
    return not_one;
  }
};

const float* onesBrick() {
  static const std::vector<float> ones(size_t(Volume::kBrickVoxels), 1.0f);
  return ones.data();
}

}  // namespace

LightBricks::LightBricks(const LightBricks& o) {
  *this = o;
}

LightBricks& LightBricks::operator=(const LightBricks& o) {
  if (this == &o) return *this;
  reset(o.brick_dims_);
  for (size_t i = 0; i < table_.size(); ++i)
    if (const float* p = o.get(i)) create(i, p);
  return *this;
}

LightBricks::LightBricks(LightBricks&& o) noexcept {
  *this = std::move(o);
}

LightBricks& LightBricks::operator=(LightBricks&& o) noexcept {
  if (this == &o) return *this;
  freeAll();
  brick_dims_ = o.brick_dims_;
  table_ = std::move(o.table_);
  allocated_.store(o.allocated_.load());
  spare_ = std::move(o.spare_);
  o.spare_.clear();
  o.table_.clear();
  o.brick_dims_ = glm::ivec3(0);
  o.allocated_.store(0);
  return *this;
}

LightBricks::~LightBricks() {
  freeAll();
  dropSpare();
}

void LightBricks::freeAll() {
  for (float*& p : table_) {
    delete[] p;
    p = nullptr;
  }
  allocated_.store(0);
}

void LightBricks::reset(glm::ivec3 brick_dims) {
  freeAll();
  brick_dims_ = brick_dims;
  table_.assign(size_t(brick_dims.x) * size_t(brick_dims.y) * size_t(brick_dims.z), nullptr);
}

void LightBricks::recycle(glm::ivec3 brick_dims) {
  for (float*& p : table_)
    if (p) spare_.push_back(std::exchange(p, nullptr));
  allocated_.store(0);
  brick_dims_ = brick_dims;
  table_.assign(size_t(brick_dims.x) * size_t(brick_dims.y) * size_t(brick_dims.z), nullptr);
}

void LightBricks::shift(glm::ivec3 brick_dims, glm::ivec3 brick_offset) {
  table_ = shiftedBrickTable(table_, brick_dims_, brick_dims, brick_offset);
  brick_dims_ = brick_dims;
}

void LightBricks::dropSpare() {
  for (float* p : spare_) delete[] p;
  spare_.clear();
  spare_.shrink_to_fit();
}

float* LightBricks::create(size_t i, const float* init) {
  float* p = nullptr;
  {
    std::lock_guard<std::mutex> lock(spare_mutex_);
    if (!spare_.empty()) {
      p = spare_.back();
      spare_.pop_back();
    }
  }
  if (!p) p = new float[size_t(Volume::kBrickVoxels)];
  if (init)
    std::copy(init, init + Volume::kBrickVoxels, p);
  else
    std::fill(p, p + Volume::kBrickVoxels, 1.0f);
  std::atomic_ref<float*>(table_[i]).store(p, std::memory_order_release);
  allocated_.fetch_add(1, std::memory_order_relaxed);
  return p;
}

void LightBricks::release(size_t i) {
  float* p = std::atomic_ref<float*>(table_[i]).exchange(nullptr);
  if (!p) return;
  delete[] p;
  allocated_.fetch_sub(1, std::memory_order_relaxed);
}

bool LightVolume::matches(const Volume& volume, const Light& light) const {
  return dims == volume.dims() && extinction == light.extinction &&
         direction == lightDirectionInVoxels(volume, light) &&
         through.brickDims() == volume.brickDims() && lit.brickDims() == volume.brickDims();
}

const float* LightVolume::brickTransmittance(glm::ivec3 brick) const {
  const glm::ivec3 bd = through.brickDims();
  if (glm::any(glm::lessThan(brick, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(brick, bd)))
    return nullptr;
  const size_t i = through.brickIndex(brick);
  if (const float* p = lit.get(i)) return p;
  if (const float* p = through.get(i)) return p;
  return onesBrick();
}

void LightVolume::readRow(glm::ivec3 start, int n, float* out) const {
  constexpr int m = Volume::kBrickSize - 1;
  for (int x = start.x; x < start.x + n;) {
    const int run = std::min(start.x + n, (x | m) + 1) - x;  // to the end of this brick
    const float* p =
        through.brickDims().x == 0
            ? nullptr
            : brickTransmittance(glm::ivec3(x, start.y, start.z) >> Volume::kBrickShift);
    if (p)
      std::copy_n(p + ((size_t(start.z & m) * Volume::kBrickSize + size_t(start.y & m)) *
                           Volume::kBrickSize +
                       size_t(x & m)),
                  run, out + (x - start.x));
    else
      std::fill_n(out + (x - start.x), run, 1.0f);
    x += run;
  }
}

std::vector<float> LightVolume::toDense() const {
  const size_t n = size_t(dims.x) * size_t(dims.y) * size_t(dims.z);
  if (n > (size_t(1) << 31)) throw std::length_error("LightVolume::toDense: more than 2^31 voxels");
  std::vector<float> out(n);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x)
        out[(size_t(z) * size_t(dims.y) + size_t(y)) * size_t(dims.x) + size_t(x)] = at(x, y, z);
  return out;
}

glm::vec3 lightDirectionInVoxels(const Volume& volume, const Light& light) {
  return glm::normalize(light.direction / volume.voxelSize());
}

std::vector<glm::ivec3> lightBrickList(const Volume& volume) {
  const glm::ivec3 bd = volume.brickDims();
  std::vector<uint8_t> mark(volume.brickCount(), 0);
  auto index = [&](glm::ivec3 b) {
    return (size_t(b.z) * size_t(bd.y) + size_t(b.y)) * size_t(bd.x) + size_t(b.x);
  };
  for (const glm::ivec3 b : volume.allocatedBrickList()) {
    const glm::ivec3 lo = glm::max(b - 1, glm::ivec3(0)), hi = glm::min(b + 1, bd - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) mark[index({x, y, z})] = 1;
  }
  std::vector<glm::ivec3> list;
  for (int z = 0; z < bd.z; ++z)
    for (int y = 0; y < bd.y; ++y)
      for (int x = 0; x < bd.x; ++x)
        if (mark[index({x, y, z})]) list.push_back({x, y, z});
  return list;
}

namespace {

// The full sweep. Tile row tc of slice s reads tile rows tc and tc + ⌊u_c⌋… of the slice
// upstream, i.e. rows tc and one neighbour (tc − 1 when the upstream rows lie below, else
// tc + 1), so tile rows are swept one after another from the side the light comes from, each
// over every slice. Threads take rows in turn and run as a pipeline: row i's slice j waits until
// row i − 1 has published slice j − 1 (in batches of kRowBatch slices); no barrier per slice,
// and no value depends on the split. A tile is swept only when its brick holds density or a
// tile in its upstream footprint passed on a value other than 1; the others stay all 1. Only the
// stored slices of each column (`depth`, storedSlices) are swept.
void sweepAllTiles(const TileSweep& t, const std::vector<int>& depth) {
  const SweepFrame& f = t.f;
  const int ntb = (t.nb + kTile - 1) / kTile, ntc = (t.nc + kTile - 1) / kTile;
  const int slices = depth.empty() ? 0 : *std::max_element(depth.begin(), depth.end());
  const int layers = t.volume.brickDims()[f.axis];
  // Tile rows holding density, per brick layer along the axis.
  std::vector<uint8_t> row_has_density(size_t(layers) * size_t(ntc), 0);
  for (const glm::ivec3 b : t.volume.allocatedBrickList())
    row_has_density[size_t(b[f.axis]) * size_t(ntc) + size_t(b[f.c])] = 1;
  // Per slice (in sweep order) and tile: passed on a value other than 1; and per tile row.
  std::vector<uint8_t> tile_not_one(size_t(slices) * size_t(ntc) * size_t(ntb), 0);
  std::vector<uint8_t> row_not_one(size_t(slices) * size_t(ntc), 0);
  const bool descending = t.oc >= 0;
  const int tb_lo = t.ob < 0 ? -1 : 0, tb_hi = t.ob < 0 ? 0 : 1;  // upstream tiles of tile tb
  const int threads = std::max(1, std::min({workerThreads(), 16, ntc}));
  std::vector<std::atomic<int>> progress(static_cast<size_t>(ntc));
  for (auto& p : progress) p.store(0, std::memory_order_relaxed);
  auto rowWorker = [&](int id) {
    for (int i = id; i < ntc; i += threads) {
      const int tc = descending ? ntc - 1 - i : i;
      const int neighbour = descending ? tc + 1 : tc - 1;  // the other upstream tile row
      const bool has_neighbour = neighbour >= 0 && neighbour < ntc;
      const int c0 = tc * kTile, c1 = std::min(t.nc, c0 + kTile);
      for (int j0 = 0; j0 < slices; j0 += kRowBatch) {
        const int j1 = std::min(slices, j0 + kRowBatch);
        if (i > 0) {
          std::atomic<int>& previous = progress[size_t(i - 1)];
          for (int done = previous.load(std::memory_order_acquire); done < j1;
               done = previous.load(std::memory_order_acquire))
            previous.wait(done, std::memory_order_acquire);
        }
        for (int j = j0; j < j1; ++j) {
          const int s = f.first + j * f.dir;
          const bool density =
              row_has_density[size_t(s >> Volume::kBrickShift) * size_t(ntc) + size_t(tc)] != 0;
          const uint8_t* up =
              j > 0 ? &tile_not_one[size_t(j - 1) * size_t(ntc) * size_t(ntb)] : nullptr;
          const bool shadow_upstream =
              j > 0 &&
              (row_not_one[size_t(j - 1) * size_t(ntc) + size_t(tc)] ||
               (has_neighbour && row_not_one[size_t(j - 1) * size_t(ntc) + size_t(neighbour)]));
          if (!density && !shadow_upstream) continue;
          uint8_t* now = &tile_not_one[size_t(j) * size_t(ntc) * size_t(ntb)];
          bool row_any = false;
          for (int tb = 0; tb < ntb; ++tb) {
            if (j >= depth[size_t(tc) * size_t(ntb) + size_t(tb)]) continue;  // not stored
            bool active = density && t.volume.brick(t.brickCoord(s, tb, tc)) != nullptr;
            for (int ub = std::max(0, tb + tb_lo);
                 !active && shadow_upstream && ub <= std::min(ntb - 1, tb + tb_hi); ++ub)
              active = up[size_t(tc) * size_t(ntb) + size_t(ub)] ||
                       (has_neighbour && up[size_t(neighbour) * size_t(ntb) + size_t(ub)]);
            if (!active) continue;
            const int b0 = tb * kTile;
            if (t.processTile(s, tb, tc, Rect{{b0, c0}, {std::min(t.nb, b0 + kTile), c1}}, false,
                              nullptr)) {
              now[size_t(tc) * size_t(ntb) + size_t(tb)] = 1;
              row_any = true;
            }
          }
          row_not_one[size_t(j) * size_t(ntc) + size_t(tc)] = row_any;
        }
        progress[size_t(i)].store(j1, std::memory_order_release);
        progress[size_t(i)].notify_all();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(rowWorker, i);
  rowWorker(0);
  for (auto& th : pool) th.join();
}

// Slice s's index in sweep order: 0 at the light side.
int sweepIndex(const SweepFrame& f, int s) {
  return (s - f.first) * f.dir;
}

// How the columns' stored depths moved since the last sweep (storedSlices before and after).
struct DepthChange {
  Rect grown_rect;                 // the newly stored columns' bounding rectangle (voxels)
  int grown_lo = 0, grown_hi = 0;  // their newly stored slices (sweep indices)
  int stored_end = 0;              // the deepest stored slice + 1
  bool grown() const { return grown_hi > 0; }
};

// Columns an erase made shallower free their bricks past the new depth (marked in
// changed_bytes when tracked); columns an edit made deeper (a brick allocated further downstream)
// are to be swept whole over their newly stored slices [depth_before, depth): nothing of them
// was kept.
DepthChange applyStoredDepths(LightVolume& lv, const Volume& volume, const SweepFrame& f,
                              const std::vector<int>& depth, const std::vector<int>& depth_before,
                              std::vector<uint8_t>& changed_bytes) {
  const glm::ivec3 dims = volume.dims(), bd = volume.brickDims();
  const int ntb = bd[f.b];
  DepthChange d;
  d.grown_lo = dims[f.axis];
  for (size_t i = 0; i < depth.size(); ++i) {
    d.stored_end = std::max(d.stored_end, depth[i]);
    glm::ivec3 b;
    b[f.b] = int(i % size_t(ntb));
    b[f.c] = int(i / size_t(ntb));
    if (depth[i] > depth_before[i]) {
      d.grown_rect = d.grown_rect.unite(
          Rect{{b[f.b] * kTile, b[f.c] * kTile}, {(b[f.b] + 1) * kTile, (b[f.c] + 1) * kTile}});
      d.grown_lo = std::min(d.grown_lo, depth_before[i]);
      d.grown_hi = std::max(d.grown_hi, depth[i]);
    } else if (depth[i] < depth_before[i]) {
      for (b[f.axis] = 0; b[f.axis] < bd[f.axis]; ++b[f.axis]) {
        const int s0 = b[f.axis] * Volume::kBrickSize;
        if (std::min(sweepIndex(f, s0), sweepIndex(f, std::min(dims[f.axis], s0 + kTile) - 1)) <
            depth[i])
          continue;
        lv.through.release(lv.through.brickIndex(b));
        lv.lit.release(lv.lit.brickIndex(b));
        if (!changed_bytes.empty()) changed_bytes[lv.through.brickIndex(b)] = 0xFF;
      }
    }
  }
  return d;
}

// The bricks marked in changed_bytes, in the volume's brick order (z, y, x).
void collectBrickChanges(const LightVolume& lv, glm::ivec3 bd,
                         const std::vector<uint8_t>& changed_bytes, LightByteChanges* changes) {
  if (changed_bytes.empty()) return;
  for (int z = 0; z < bd.z; ++z)
    for (int y = 0; y < bd.y; ++y)
      for (int x = 0; x < bd.x; ++x)
        if (const uint8_t readers = changed_bytes[lv.through.brickIndex({x, y, z})])
          changes->bricks.push_back({{x, y, z}, readers});
}

// An incremental sweep's slices: from `first` (a sweep index; slice `start`) over `slices`
// slices; the dirty box's rectangle on its slices dirty_lo … + dirty_slices.
struct ChangedSlices {
  const TileSweep& t;
  const std::vector<int>& depth;
  const std::vector<int>& depth_before;
  const DepthChange& grow;
  int first, start, slices, dirty_lo, dirty_slices;
  Rect dirty_rect, all;
};

// What an incremental sweep rewrote: each slice's rectangle, and per thread the newly stored
// tiles that are not all 1.
struct SweptSlices {
  struct Fresh {
    Rect lateral;
    int first = -1, last = -1;
  };
  std::vector<Rect> swept;
  std::vector<Fresh> fresh;
};

// A slice's rectangle is the set of voxels whose bilinear upstream footprint meets a voxel whose
// passed-on transmittance changed in the previous slice (by more than kChangeEpsilon, which is
// 0), plus the dirty box on its slices, so the update follows the actual shadow of the edit and
// stops where it no longer changes anything or falls into shadow that is already black. Tiles
// past their column's stored depth are passed over (only unstored tiles read them); newly stored
// tiles are swept whole (a tile stored before reads only tiles stored before, so their values
// need no change tracking).
//
// Slices depend on their upstream neighbour, so threads split each slice's tile rows (a tile
// belongs to one thread) and meet at a barrier between slices. Small edits run on one thread
// (a barrier per slice costs more than they do). Each thread's changed rectangle is
// double-buffered by slice parity, so one barrier per slice suffices; every voxel's value is
// independent of the split (deterministic).
SweptSlices sweepChangedSlices(const ChangedSlices& in) {
  const TileSweep& t = in.t;
  const SweepFrame& f = t.f;
  const int ntb = t.volume.brickDims()[f.b];
  const int threads =
      in.dirty_rect.area() >= kThreadedArea || in.grow.grown_rect.area() >= kThreadedArea
          ? std::max(1, std::min(workerThreads(), 16))
          : 1;
  // The voxels of the next slice whose upstream footprint (b + ob + {0,1}, c + oc + {0,1})
  // meets `changed`.
  auto downstreamOf = [&](Rect changed) {
    if (changed.empty()) return Rect{};
    return Rect{changed.lo - glm::ivec2(t.ob, t.oc) - 1, changed.hi - glm::ivec2(t.ob, t.oc)}
        .intersect(in.all);
  };
  std::vector<Rect> changed_by_thread(size_t(2 * threads));
  SweptSlices out;
  out.swept.resize(size_t(in.slices));  // each slice's rectangle (thread 0)
  out.fresh.resize(size_t(threads));
  const bool grown = in.grow.grown();
  auto worker = [&](int id, std::barrier<>* sync) {
    for (int j = 0; j < in.slices; ++j) {
      Rect changed;
      if (j > 0)
        for (int i = 0; i < threads; ++i)
          changed = changed.unite(changed_by_thread[size_t(2 * i + (j - 1) % 2)]);
      Rect rect = downstreamOf(changed);
      if (j >= in.dirty_lo && j < in.dirty_lo + in.dirty_slices) rect = rect.unite(in.dirty_rect);
      const int k = in.first + j;  // the slice's sweep index
      const bool growing = grown && k >= in.grow.grown_lo && k < in.grow.grown_hi;
      // Every thread sees the same rectangles and stops together; before newly stored slices
      // an empty slice is passed over.
      if (rect.empty() && !(grown && k < in.grow.grown_hi)) break;
      const Rect work = growing ? rect.unite(in.grow.grown_rect).intersect(in.all) : rect;
      const int s = in.start + j * f.dir;
      const int tr0 = work.lo.y / kTile, tr1 = (work.hi.y - 1) / kTile + 1;
      const int parts = work.area() < kThreadedArea ? 1 : threads;
      const int r0 = id < parts && !work.empty() ? tr0 + (tr1 - tr0) * id / parts : tr0;
      const int r1 = id < parts && !work.empty() ? tr0 + (tr1 - tr0) * (id + 1) / parts : tr0;
      Rect mine;
      for (int tc = r0; tc < r1; ++tc)
        for (int tb = work.lo.x / kTile; tb * kTile < work.hi.x; ++tb) {
          const size_t column = size_t(tc) * size_t(ntb) + size_t(tb);
          if (k >= in.depth[column]) continue;  // not stored
          const Rect tile{{tb * kTile, tc * kTile}, {(tb + 1) * kTile, (tc + 1) * kTile}};
          if (k >= in.depth_before[column]) {  // newly stored: swept whole
            // `at` read 1 there before: the tile is rewritten only where it is not 1 now.
            if (t.processTile(s, tb, tc, tile.intersect(in.all), false, nullptr)) {
              SweptSlices::Fresh& mine_fresh = out.fresh[size_t(id)];
              mine_fresh.lateral = mine_fresh.lateral.unite(tile.intersect(in.all));
              if (mine_fresh.first < 0) mine_fresh.first = j;
              mine_fresh.last = j;
            }
            continue;
          }
          const Rect r = rect.intersect(tile);
          if (!r.empty()) t.processTile(s, tb, tc, r, true, &mine);
        }
      changed_by_thread[size_t(2 * id + j % 2)] = mine;
      if (id == 0) out.swept[size_t(j)] = rect;
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
    for (auto& th : pool) th.join();
  }
  return out;
}

// The rewritten box: the union of the per-slice rectangles and the newly stored tiles not 1
// (empty when nothing was rewritten); bricks the update left all 1 (an erase's shadow gone)
// are dropped there: absent reads the same.
VoxelBox rewrittenBox(LightVolume& lv, const Volume& volume, const SweepFrame& f, int start,
                      const SweptSlices& done) {
  Rect lateral;
  int first_rewritten = int(done.swept.size()), last = -1;
  for (size_t j = 0; j < done.swept.size(); ++j) {
    if (done.swept[j].empty()) continue;
    lateral = lateral.unite(done.swept[j]);
    first_rewritten = std::min(first_rewritten, int(j));
    last = int(j);
  }
  for (const SweptSlices::Fresh& f_id : done.fresh) {
    if (f_id.last < 0) continue;
    lateral = lateral.unite(f_id.lateral);
    first_rewritten = std::min(first_rewritten, f_id.first);
    last = std::max(last, f_id.last);
  }
  if (last < 0) return {};
  VoxelBox out;
  const int begin = start + first_rewritten * f.dir, end = start + last * f.dir;
  out.lo[f.axis] = std::min(begin, end);
  out.hi[f.axis] = std::max(begin, end) + 1;
  out.lo[f.b] = lateral.lo.x;
  out.hi[f.b] = lateral.hi.x;
  out.lo[f.c] = lateral.lo.y;
  out.hi[f.c] = lateral.hi.y;
  out = out.intersect(volume.bounds());
  const glm::ivec3 blo = out.lo >> Volume::kBrickShift, bhi = (out.hi - 1) >> Volume::kBrickShift;
  for (int z = blo.z; z <= bhi.z; ++z)
    for (int y = blo.y; y <= bhi.y; ++y)
      for (int x = blo.x; x <= bhi.x; ++x) {
        const size_t i = lv.through.brickIndex({x, y, z});
        const float* p = lv.through.get(i);
        if (p && std::all_of(p, p + Volume::kBrickVoxels, [](float v) { return v == 1.0f; }))
          lv.through.release(i);
      }
  return out;
}

// Hashes of the 8-bit light of one brick's 16³ values (unorm8, as the GPU copy holds it), one
// per part: part bit a set for the voxels with coordinate a below LightByteChanges::kLowVoxels
// (those the slot one brick below on that axis reads too).
LightVolume::BrickHash brickByteHash(const float* t) {
  constexpr int S = Volume::kBrickSize, L = LightByteChanges::kLowVoxels;
  static_assert(S == 16 && L == 4, "a row is one 4-byte low word and 12 high bytes");
  alignas(16) uint8_t bytes[Volume::kBrickVoxels];
  for (int i = 0; i < Volume::kBrickVoxels; ++i) bytes[i] = unorm8(t[i]);
  LightVolume::BrickHash h;
  h.fill(0x9E3779B97F4A7C15ull);
  auto mix = [](uint64_t& into, uint64_t w) {
    into = (into ^ w) * 0xBF58476D1CE4E5B9ull;
    into ^= into >> 31;
  };
  for (int z = 0; z < S; ++z)
    for (int y = 0; y < S; ++y) {
      const uint8_t* row = bytes + (z * S + y) * S;
      const int yz = (y < L ? 2 : 0) | (z < L ? 4 : 0);
      uint32_t low, tail;
      uint64_t mid;
      std::memcpy(&low, row, 4);
      std::memcpy(&mid, row + 4, 8);
      std::memcpy(&tail, row + 12, 4);
      mix(h[size_t(yz | 1)], low);
      mix(h[size_t(yz)], mid);
      mix(h[size_t(yz)], tail);
    }
  return h;
}

// Every brick's byte hashes (an absent brick reads 1: the hashes of a brick of ones). Each
// brick's hashes are its own, so the split over threads changes nothing.
std::vector<LightVolume::BrickHash> brickByteHashes(const LightVolume& lv) {
  const glm::ivec3 bd = lv.through.brickDims();
  const size_t n = size_t(bd.x) * size_t(bd.y) * size_t(bd.z);
  std::vector<LightVolume::BrickHash> hashes(n);
  const LightVolume::BrickHash ones = brickByteHash(onesBrick());
  parallelFor(n, 2048, [&](size_t, size_t i0, size_t i1) {
    for (size_t i = i0; i < i1; ++i) {
      const float* p = lv.lit.get(i);
      if (!p) p = lv.through.get(i);
      hashes[i] = p ? brickByteHash(p) : ones;
    }
  });
  return hashes;
}

// After a full sweep: the bricks whose byte hashes differ from `before`, each with the slots
// below it that read a changed part (LightByteChanges::Brick::readers), when `before` was known
// for this grid; else `all` stays.
void listFullSweepChanges(LightVolume& lv, const std::vector<LightVolume::BrickHash>& before,
                          LightByteChanges* changes) {
  if (!changes) return;
  lv.byte_hash = brickByteHashes(lv);
  if (before.size() != lv.byte_hash.size()) return;
  changes->all = false;
  const glm::ivec3 bd = lv.through.brickDims();
  for (int z = 0; z < bd.z; ++z)
    for (int y = 0; y < bd.y; ++y)
      for (int x = 0; x < bd.x; ++x) {
        const size_t i = lv.through.brickIndex({x, y, z});
        if (lv.byte_hash[i] == before[i]) continue;
        // The slot of brick − δ reads part r's voxels when r is low on every axis δ names.
        uint8_t readers = 0;
        for (int r = 0; r < 8; ++r)
          if (lv.byte_hash[i][size_t(r)] != before[i][size_t(r)])
            for (int d = 0; d < 8; ++d)
              if ((d & ~r) == 0) readers |= uint8_t(1u << d);
        changes->bricks.push_back({{x, y, z}, readers});
      }
}

// After an incremental sweep: the byte hashes of the bricks it names as changed, re-hashed
// (they stay unknown when it named none: `changes` not asked for).
void rehashChangedBricks(LightVolume& lv, const LightByteChanges* changes) {
  const glm::ivec3 bd = lv.through.brickDims();
  if (!changes || lv.byte_hash.size() != size_t(bd.x) * size_t(bd.y) * size_t(bd.z)) {
    lv.byte_hash.clear();
    return;
  }
  for (const LightByteChanges::Brick& c : changes->bricks) {
    const size_t i = lv.through.brickIndex(c.brick);
    const float* p = lv.lit.get(i);
    if (!p) p = lv.through.get(i);
    lv.byte_hash[i] = brickByteHash(p ? p : onesBrick());
  }
}

}  // namespace

VoxelBox sweepLightVolume(LightVolume& lv, const Volume& volume, const Light& light,
                          const VoxelBox& dirty, LightByteChanges* changes) {
  const glm::ivec3 dims = volume.dims();
  VoxelBox region = dirty.intersect(volume.bounds());
  if (changes) *changes = LightByteChanges{};
  if (!lv.matches(volume, light)) {
    lv.dims = dims;
    lv.direction = lightDirectionInVoxels(volume, light);
    lv.extinction = light.extinction;
    region = volume.bounds();
  }
  if (region.empty()) return {};
  if (changes) changes->all = region == volume.bounds();
  // Per brick: the 8-bit light changed (TileSweep::changed_bytes), for an incremental sweep.
  std::vector<uint8_t> changed_bytes;
  if (changes && !changes->all) {
    const glm::ivec3 bd = volume.brickDims();
    changed_bytes.assign(size_t(bd.x) * size_t(bd.y) * size_t(bd.z), 0);
  }
  const SweepFrame f = makeFrame(lv.direction, dims);
  const glm::vec2 lateral_up(f.up[f.b], f.up[f.c]);
  const glm::ivec2 lateral_dims(dims[f.b], dims[f.c]);
  const glm::ivec3 brick_stride(1, kTile, kTile * kTile);
  const AttenuationPair attenuation(lv.extinction, f.step_length, 0.5f * (f.step_length + 1.0f));
  // The upstream point of lateral voxel (b, c) is (b + u_b, c + u_c): the same fractional
  // offsets for every voxel, so the bilinear weights are constants of the sweep.
  const int ob = int(std::floor(lateral_up.x)), oc = int(std::floor(lateral_up.y));
  const TileSweep t{volume,
                    lv,
                    f,
                    attenuation,
                    dims[f.axis],
                    lateral_dims.x,
                    lateral_dims.y,
                    ob,
                    oc,
                    lateral_up.x - float(ob),
                    lateral_up.y - float(oc),
                    size_t(brick_stride[f.axis]),
                    size_t(brick_stride[f.b]),
                    size_t(brick_stride[f.c]),
                    changed_bytes.empty() ? nullptr : changed_bytes.data()};

  // Slices of each brick column whose light is stored (storedSlices), before and after.
  const std::vector<int> depth = storedSlices(volume, f, ob, oc);
  std::vector<int> depth_before = std::exchange(lv.stored_slices, depth);
  if (region == volume.bounds()) {
    const std::vector<LightVolume::BrickHash> hashes_before = std::exchange(lv.byte_hash, {});
    lv.lit.recycle(volume.brickDims());
    lv.through.recycle(volume.brickDims());
    sweepAllTiles(t, depth);
    lv.lit.dropSpare();
    lv.through.dropSpare();
    listFullSweepChanges(lv, hashes_before, changes);
    return volume.bounds();
  }
  if (depth_before.size() != depth.size()) depth_before.assign(depth.size(), 0);
  const DepthChange grow = applyStoredDepths(lv, volume, f, depth, depth_before, changed_bytes);

  // An incremental sweep: slices from the dirty box's upstream face (or the first newly stored
  // slice) towards the far edge. Voxels left alone are exactly what a full recompute gives, so
  // undo/redo restore the light volume bit for bit (app/session/history.h).
  const int dirty_start = sweepIndex(f, f.dir < 0 ? region.hi[f.axis] - 1 : region.lo[f.axis]);
  const int first = grow.grown() ? std::min(dirty_start, grow.grown_lo) : dirty_start;
  const int start = f.first + first * f.dir;  // the first slice swept
  const int slices = grow.stored_end - first;
  if (slices <= 0) {
    collectBrickChanges(lv, volume.brickDims(), changed_bytes, changes);
    rehashChangedBricks(lv, changes);
    return {};
  }
  const ChangedSlices in{t,
                         depth,
                         depth_before,
                         grow,
                         first,
                         start,
                         slices,
                         dirty_start - first,
                         region.hi[f.axis] - region.lo[f.axis],
                         Rect{{region.lo[f.b], region.lo[f.c]}, {region.hi[f.b], region.hi[f.c]}},
                         Rect{glm::ivec2(0), lateral_dims}};
  const SweptSlices done = sweepChangedSlices(in);
  collectBrickChanges(lv, volume.brickDims(), changed_bytes, changes);
  const VoxelBox rewritten = rewrittenBox(lv, volume, f, start, done);
  rehashChangedBricks(lv, changes);
  return rewritten;
}

void shiftLightVolume(LightVolume& lv, glm::ivec3 old_dims, const Volume& grown,
                      glm::ivec3 brick_offset) {
  const glm::ivec3 old_bricks = old_dims >> Volume::kBrickShift;
  // The columns: lateral bricks (tb, tc), tb fastest; depths from the light side.
  const glm::ivec3 dims = grown.dims(), bd = grown.brickDims();
  const SweepFrame f = makeFrame(lv.direction, dims);
  const int ntb_old = old_bricks[f.b], ntc_old = old_bricks[f.c];
  if (lv.dims != old_dims || lv.extinction < 0.0f || lv.through.brickDims() != old_bricks ||
      lv.lit.brickDims() != old_bricks ||
      lv.stored_slices.size() != size_t(ntb_old) * size_t(ntc_old) ||
      old_dims % Volume::kBrickSize != glm::ivec3(0)) {
    lv = LightVolume{};
    return;
  }
  lv.lit.shift(bd, brick_offset);
  lv.through.shift(bd, brick_offset);
  lv.byte_hash.clear();  // the next full sweep reports every brick
  lv.dims = dims;
  const int ntb = bd[f.b], ntc = bd[f.c];
  const int offset_slices = brick_offset[f.axis] * Volume::kBrickSize;
  const int added = f.dir > 0 ? offset_slices : dims[f.axis] - old_dims[f.axis] - offset_slices;
  std::vector<int> depth(size_t(ntb) * size_t(ntc), 0);
  for (int tc = 0; tc < ntc_old; ++tc)
    for (int tb = 0; tb < ntb_old; ++tb) {
      const int d = lv.stored_slices[size_t(tc) * size_t(ntb_old) + size_t(tb)];
      depth[size_t(tc + brick_offset[f.c]) * size_t(ntb) + size_t(tb + brick_offset[f.b])] =
          d > 0 ? d + added : 0;
    }
  // The old edge's columns read, upstream, columns of the grown sky that nothing stored (the old
  // grid's outside, read as 1): these now store as deep as their readers, as storedSlices of the
  // grown volume has them, so that a later edit's change there is followed into the columns
  // reading it. Their light is 1 (absent bricks): all they read upstream is grown, empty sky.
  closeStoredDepths(depth, ntb, ntc, int(std::floor(f.up[f.b])), int(std::floor(f.up[f.c])));
  lv.stored_slices = std::move(depth);
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
