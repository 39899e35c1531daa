#include "app/tools/wind_kernels.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <limits>

#include "app/core/parallel_for.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace cb::wind {
namespace {

std::atomic<bool> g_allow_avx2{true};

bool useAvx2() {
#if defined(__x86_64__)
  static const bool has_avx2 = __builtin_cpu_supports("avx2");
  return has_avx2 && g_allow_avx2.load(std::memory_order_relaxed);
#else
  return false;
#endif
}

void backtraceCells(const glm::vec3* grid, glm::ivec3 n, int y, int z, const glm::vec3* u, float dt,
                    glm::vec3 cell, bool minus_step, int x_begin, glm::vec3* out) {
  for (int x = x_begin; x < n.x; ++x) {
    const glm::vec3 s = sampleClamped(grid, n, glm::vec3(x, y, z) - u[x] * dt / cell);
    out[x] = minus_step ? s - u[x] * dt : s;
  }
}

// Cell x of a Jacobi row, with the zero pressure outside the row's ends.
inline void jacobiCell(const JacobiRow& r, int x, int count, glm::vec3 inv_h2, float diagonal) {
  const float xm = x > 0 ? r.p[x - 1] : 0.0f, xp = x + 1 < count ? r.p[x + 1] : 0.0f;
  const float neighbours =
      (xm + xp) * inv_h2.x + (r.ym[x] + r.yp[x]) * inv_h2.y + (r.zm[x] + r.zp[x]) * inv_h2.z;
  r.out[x] = (neighbours - r.div[x]) / diagonal;
}

#if defined(__x86_64__)
// The lanes' a + (b − a)·t.
__attribute__((target("avx2"))) inline __m256 lerp8(__m256 a, __m256 b, __m256 t) {
  return _mm256_add_ps(a, _mm256_mul_ps(_mm256_sub_ps(b, a), t));
}

// The first cell of rows (j, k): (k·n.y + j)·n.x.
__attribute__((target("avx2"))) inline __m256i rowOffset(__m256i j, __m256i k, __m256i ny,
                                                         __m256i nx) {
  return _mm256_mullo_epi32(_mm256_add_epi32(_mm256_mullo_epi32(k, ny), j), nx);
}

// The x lerps of two cell rows of a glm::vec3 grid at once, one per 128-bit half as
// (x, y, z, ·): lerp(cell x0, cell x0 + 1, fx) with the cell x0 at `lo` and at `hi`.
__attribute__((target("avx2"))) inline __m256 lerpAlongX(const float* lo, const float* hi,
                                                         __m256 fx) {
  // (x0.x, x0.y, x0.z, x1.x) and (x0.z, x1.x, x1.y, x1.z) → (x1.x, x1.y, x1.z, x1.z): no read
  // past cell x0 + 1.
  const __m256 a =
      _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(lo)), _mm_loadu_ps(hi), 1);
  const __m256 b =
      _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(lo + 2)), _mm_loadu_ps(hi + 2), 1);
  return lerp8(a, _mm256_shuffle_ps(b, b, _MM_SHUFFLE(3, 3, 2, 1)), fx);
}

// backtraceCells for n.x ≥ 8 cells. Eight cells at a time, per lane: sampleClamped's clamp
// (glm's max(c, 0) then min(·, n − 1), `(c < 0) ? 0 : c` then `(n − 1 < c) ? n − 1 : c`, which
// are _mm256_max_ps(0, c) and _mm256_min_ps(n − 1, c)), floor, cells and weights; then each
// cell's lerps on its (x, y, z) as a vector, two cell rows at a time. The cell after x0 is
// x0 + 1 (n.x ≥ 2). A row not a multiple of 8 long ends with eight overlapping the eight before
// (the same values written again).
__attribute__((target("avx2"))) void backtraceRowAvx2(const glm::vec3* grid, glm::ivec3 n, int y,
                                                      int z, const glm::vec3* u, float dt,
                                                      glm::vec3 cell, bool minus_step,
                                                      glm::vec3* out) {
  const float* g = &grid[0].x;
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i thirds = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  const __m256i one = _mm256_set1_epi32(1), nx = _mm256_set1_epi32(n.x);
  const __m256i ny = _mm256_set1_epi32(n.y);
  const __m256 zero = _mm256_setzero_ps(), dt8 = _mm256_set1_ps(dt);
  // Per lane: the float offset of cell x0 in the rows (y0, z0), (y1, z0), (y0, z1), (y1, z1);
  // the weights along x, y, z; u·dt.
  alignas(32) int start[4][8];
  alignas(32) float weight[3][8], step[3][8];
  for (int group = 0; group < n.x; group += 8) {
    const int x = std::min(group, n.x - 8);
    __m256i i0[3], i1[3];
    const __m256 position[3] = {_mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(x), lanes)),
                                _mm256_set1_ps(float(y)), _mm256_set1_ps(float(z))};
    for (int a = 0; a < 3; ++a) {
      const __m256 uc = _mm256_i32gather_ps(&u[x].x + a, thirds, 4);
      const __m256 u_dt = _mm256_mul_ps(uc, dt8);
      __m256 c = _mm256_sub_ps(position[a], _mm256_div_ps(u_dt, _mm256_set1_ps(cell[a])));
      c = _mm256_min_ps(_mm256_set1_ps(float(n[a] - 1)), _mm256_max_ps(zero, c));
      i0[a] = _mm256_min_epi32(_mm256_cvttps_epi32(_mm256_floor_ps(c)),
                               _mm256_set1_epi32(std::max(n[a] - 2, 0)));
      i1[a] = _mm256_min_epi32(_mm256_add_epi32(i0[a], one), _mm256_set1_epi32(n[a] - 1));
      _mm256_store_ps(weight[a], _mm256_sub_ps(c, _mm256_cvtepi32_ps(i0[a])));
      _mm256_store_ps(step[a], u_dt);
    }
    const __m256i rows[4] = {rowOffset(i0[1], i0[2], ny, nx), rowOffset(i1[1], i0[2], ny, nx),
                             rowOffset(i0[1], i1[2], ny, nx), rowOffset(i1[1], i1[2], ny, nx)};
    for (int r = 0; r < 4; ++r) {
      const __m256i cell0 = _mm256_add_epi32(rows[r], i0[0]);
      _mm256_store_si256(reinterpret_cast<__m256i*>(start[r]),
                         _mm256_add_epi32(_mm256_slli_epi32(cell0, 1), cell0));
    }
    for (int i = 0; i < 8; ++i) {
      const __m256 fx = _mm256_broadcast_ss(&weight[0][i]);
      const __m256 y0 = lerpAlongX(g + start[0][i], g + start[1][i], fx);  // (c00 | c10)
      const __m256 y1 = lerpAlongX(g + start[2][i], g + start[3][i], fx);  // (c01 | c11)
      const __m256 along_y =
          lerp8(_mm256_permute2f128_ps(y0, y1, 0x20), _mm256_permute2f128_ps(y0, y1, 0x31),
                _mm256_broadcast_ss(&weight[1][i]));
      const __m128 lo = _mm256_castps256_ps128(along_y), hi = _mm256_extractf128_ps(along_y, 1);
      __m128 s = _mm_add_ps(lo, _mm_mul_ps(_mm_sub_ps(hi, lo), _mm_broadcast_ss(&weight[2][i])));
      if (minus_step) s = _mm_sub_ps(s, _mm_setr_ps(step[0][i], step[1][i], step[2][i], 0.0f));
      glm::vec3& o = out[x + i];
      _mm_storel_pi(reinterpret_cast<__m64*>(&o.x), s);
      _mm_store_ss(&o.z, _mm_movehl_ps(s, s));
    }
  }
}

// The first of `count` cells of a row left to do when the eight-cell groups of [begin, end)
// are done, a last group overlapping the one before when its length is not a multiple of 8 (for
// kernels whose output is not an input, so the same values are written again).
template <typename Group>
__attribute__((target("avx2"))) inline int eightAtATime(int begin, int end, Group group) {
  if (end - begin < 8) return begin;
  for (int x = begin; x < end; x += 8) group(std::min(x, end - 8));
  return end;
}

// The middle cells of a Jacobi row (1 … count − 2), eight at a time; returns the first not done.
__attribute__((target("avx2"))) int jacobiMiddleAvx2(const JacobiRow& r, int count,
                                                     glm::vec3 inv_h2, float diagonal) {
  const __m256 hx = _mm256_set1_ps(inv_h2.x), hy = _mm256_set1_ps(inv_h2.y);
  const __m256 hz = _mm256_set1_ps(inv_h2.z), d = _mm256_set1_ps(diagonal);
  return eightAtATime(
      1, count - 1, [&](int x) __attribute__((target("avx2"))) {
        const __m256 sx = _mm256_add_ps(_mm256_loadu_ps(r.p + x - 1), _mm256_loadu_ps(r.p + x + 1));
        const __m256 sy = _mm256_add_ps(_mm256_loadu_ps(r.ym + x), _mm256_loadu_ps(r.yp + x));
        const __m256 sz = _mm256_add_ps(_mm256_loadu_ps(r.zm + x), _mm256_loadu_ps(r.zp + x));
        const __m256 neighbours = _mm256_add_ps(
            _mm256_add_ps(_mm256_mul_ps(sx, hx), _mm256_mul_ps(sy, hy)), _mm256_mul_ps(sz, hz));
        _mm256_storeu_ps(r.out + x,
                         _mm256_div_ps(_mm256_sub_ps(neighbours, _mm256_loadu_ps(r.div + x)), d));
      });
}

// The middle cells of a divergence row (1 … count − 2), eight at a time; returns the first not
// done.
__attribute__((target("avx2"))) int divergenceMiddleAvx2(const DivergenceRow& r, int count,
                                                         glm::vec3 two_h) {
  const __m256i thirds = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  const __m256 hx = _mm256_set1_ps(two_h.x), hy = _mm256_set1_ps(two_h.y);
  const __m256 hz = _mm256_set1_ps(two_h.z);
  return eightAtATime(
      1, count - 1, [&](int x) __attribute__((target("avx2"))) {
        auto component = [&](const glm::vec3* row, int c) __attribute__((target("avx2"))) {
          return _mm256_i32gather_ps(&row->x + c, thirds, 4);
        };
        const __m256 dx =
            _mm256_div_ps(_mm256_sub_ps(component(r.u + x + 1, 0), component(r.u + x - 1, 0)), hx);
        const __m256 dy =
            _mm256_div_ps(_mm256_sub_ps(component(r.yp + x, 1), component(r.ym + x, 1)), hy);
        const __m256 dz =
            _mm256_div_ps(_mm256_sub_ps(component(r.zp + x, 2), component(r.zm + x, 2)), hz);
        _mm256_storeu_ps(r.out + x, _mm256_add_ps(_mm256_add_ps(dx, dy), dz));
      });
}

// The middle cells of a gradient row (1 … count − 2), eight at a time (the last group applied
// only to the cells the ones before did not); returns the first not done.
__attribute__((target("avx2"))) int gradientMiddleAvx2(const GradientRow& r, int count,
                                                       glm::vec3 two_h) {
  const __m256 hx = _mm256_set1_ps(two_h.x), hy = _mm256_set1_ps(two_h.y);
  const __m256 hz = _mm256_set1_ps(two_h.z);
  int done = 1;
  return eightAtATime(
      1, count - 1, [&](int x) __attribute__((target("avx2"))) {
        alignas(32) float g[3][8];
        _mm256_store_ps(g[0], _mm256_div_ps(_mm256_sub_ps(_mm256_loadu_ps(r.p + x + 1),
                                                          _mm256_loadu_ps(r.p + x - 1)),
                                            hx));
        _mm256_store_ps(
            g[1],
            _mm256_div_ps(_mm256_sub_ps(_mm256_loadu_ps(r.yp + x), _mm256_loadu_ps(r.ym + x)), hy));
        _mm256_store_ps(
            g[2],
            _mm256_div_ps(_mm256_sub_ps(_mm256_loadu_ps(r.zp + x), _mm256_loadu_ps(r.zm + x)), hz));
        for (int i = done - x; i < 8; ++i) r.u[x + i] -= glm::vec3(g[0][i], g[1][i], g[2][i]);
        done = x + 8;
      });
}

// cellRange with the cells as (x, y, z, 0) vectors: glm::min(m, d) is `(d < m) ? d : m`, which
// is _mm_min_ps(d, m); glm::max(m, d) is `(m < d) ? d : m`, which is _mm_max_ps(d, m).
__attribute__((target("avx2"))) void cellRangeAvx2(const glm::vec3* grid, glm::ivec3 n,
                                                   glm::ivec3 lo, glm::ivec3 hi, glm::vec3* min,
                                                   glm::vec3* max) {
  __m128 low = _mm_set1_ps(std::numeric_limits<float>::infinity()),
         high = _mm_sub_ps(_mm_setzero_ps(), low);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y) {
      const glm::vec3* row = grid + (size_t(z) * n.y + y) * n.x;
      for (int x = lo.x; x <= hi.x; ++x) {
        const __m128 xy = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(&row[x].x)));
        const __m128 d = _mm_movelh_ps(xy, _mm_load_ss(&row[x].z));
        low = _mm_min_ps(d, low);
        high = _mm_max_ps(d, high);
      }
    }
  alignas(16) float l[4], h[4];
  _mm_store_ps(l, low);
  _mm_store_ps(h, high);
  *min = glm::vec3(l[0], l[1], l[2]);
  *max = glm::vec3(h[0], h[1], h[2]);
}

// lerp(p[i], p[i + 1], t) for the eight float indices i, given as lanes (0, 1, 4, 5) and
// (2, 3, 6, 7).
__attribute__((target("avx2"))) inline __m256 lerpPair(const float* p, __m128i first,
                                                       __m128i second, __m256 t) {
  const long long* q = reinterpret_cast<const long long*>(p);
  const __m256 a = _mm256_castsi256_ps(_mm256_i32gather_epi64(q, first, 4));  // a0 b0 a1 b1 | a4 …
  const __m256 b = _mm256_castsi256_ps(_mm256_i32gather_epi64(q, second, 4));  // a2 b2 a3 b3 | a6 …
  return lerp8(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0)),
               _mm256_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1)), t);
}

// PaddedDense::sample for eight voxels (x0 … x0 + 7, y, z) displaced by (dx, dy, dz) world units,
// times fade, into out, when the eight voxels each reads lie within the padded copy (then the
// result is whether any is not 0); −1, writing nothing, when a lane's do not.
__attribute__((target("avx2"))) int sampleEightAvx2(const float* voxels, glm::ivec3 dims,
                                                    glm::ivec3 padded, int x0, int y, int z,
                                                    const float* dx, const float* dy,
                                                    const float* dz, glm::vec3 voxel_size,
                                                    float fade, float* out) {
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256 v[3] = {_mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(x0), lanes)),
                       _mm256_set1_ps(float(y)), _mm256_set1_ps(float(z))};
  const float* d[3] = {dx, dy, dz};
  __m256i i0[3], inside = _mm256_set1_epi32(-1);
  __m256 f[3];
  for (int a = 0; a < 3; ++a) {
    const __m256 p =
        _mm256_add_ps(v[a], _mm256_div_ps(_mm256_loadu_ps(d[a]), _mm256_set1_ps(voxel_size[a])));
    i0[a] = _mm256_cvttps_epi32(_mm256_floor_ps(p));
    f[a] = _mm256_sub_ps(p, _mm256_cvtepi32_ps(i0[a]));
    inside = _mm256_and_si256(inside, _mm256_cmpgt_epi32(i0[a], _mm256_set1_epi32(-2)));
    inside = _mm256_and_si256(inside, _mm256_cmpgt_epi32(_mm256_set1_epi32(dims[a]), i0[a]));
  }
  if (_mm256_movemask_ps(_mm256_castsi256_ps(inside)) != 0xff) return -1;
  const __m256i one = _mm256_set1_epi32(1);
  const __m256i index = _mm256_add_epi32(
      _mm256_mullo_epi32(_mm256_add_epi32(_mm256_mullo_epi32(_mm256_add_epi32(i0[2], one),
                                                             _mm256_set1_epi32(padded.y)),
                                          _mm256_add_epi32(i0[1], one)),
                         _mm256_set1_epi32(padded.x)),
      _mm256_add_epi32(i0[0], one));
  // Each voxel's x pairs read as one 64 bits, lanes (0, 1, 4, 5) then (2, 3, 6, 7) so that one
  // in-lane shuffle puts both back in order.
  const __m256i order =
      _mm256_permutevar8x32_epi32(index, _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7));
  const __m128i first = _mm256_castsi256_si128(order), second = _mm256_extracti128_si256(order, 1);
  const size_t sy = size_t(padded.x), sz = size_t(padded.x) * padded.y;
  const __m256 c00 = lerpPair(voxels, first, second, f[0]);
  const __m256 c10 = lerpPair(voxels + sy, first, second, f[0]);
  const __m256 c01 = lerpPair(voxels + sz, first, second, f[0]);
  const __m256 c11 = lerpPair(voxels + sz + sy, first, second, f[0]);
  const __m256 rho = _mm256_mul_ps(lerp8(lerp8(c00, c10, f[1]), lerp8(c01, c11, f[1]), f[2]),
                                   _mm256_set1_ps(fade));
  _mm256_storeu_ps(out, rho);
  return _mm256_movemask_ps(_mm256_cmp_ps(rho, _mm256_setzero_ps(), _CMP_NEQ_UQ)) != 0;
}
#endif

}  // namespace

void allowAvx2(bool allow) {
  g_allow_avx2.store(allow);
}

glm::vec3 sampleClamped(const glm::vec3* grid, glm::ivec3 n, glm::vec3 c) {
  c = glm::clamp(c, glm::vec3(0), glm::vec3(n - 1));
  const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(c)), glm::max(n - 2, glm::ivec3(0)));
  const glm::vec3 f = c - glm::vec3(i0);
  const glm::ivec3 i1 = glm::min(i0 + 1, n - 1);
  auto at = [&](int x, int y, int z) { return grid[(size_t(z) * n.y + y) * n.x + x]; };
  const glm::vec3 c00 = lerp(at(i0.x, i0.y, i0.z), at(i1.x, i0.y, i0.z), f.x);
  const glm::vec3 c10 = lerp(at(i0.x, i1.y, i0.z), at(i1.x, i1.y, i0.z), f.x);
  const glm::vec3 c01 = lerp(at(i0.x, i0.y, i1.z), at(i1.x, i0.y, i1.z), f.x);
  const glm::vec3 c11 = lerp(at(i0.x, i1.y, i1.z), at(i1.x, i1.y, i1.z), f.x);
  return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
}

void backtraceRow(const glm::vec3* grid, glm::ivec3 n, int y, int z, const glm::vec3* u, float dt,
                  glm::vec3 cell, bool minus_step, glm::vec3* out) {
#if defined(__x86_64__)
  // The offsets are 32-bit lanes.
  if (useAvx2() && n.x >= 8 && size_t(n.x) * n.y * n.z * 3 <= size_t(INT_MAX))
    return backtraceRowAvx2(grid, n, y, z, u, dt, cell, minus_step, out);
#endif
  backtraceCells(grid, n, y, z, u, dt, cell, minus_step, 0, out);
}

void jacobiRow(const JacobiRow& row, int count, glm::vec3 inv_h2, float diagonal) {
  if (count <= 2) {
    for (int x = 0; x < count; ++x) jacobiCell(row, x, count, inv_h2, diagonal);
    return;
  }
  jacobiCell(row, 0, count, inv_h2, diagonal);
  int x = 1;
#if defined(__x86_64__)
  if (useAvx2()) x = jacobiMiddleAvx2(row, count, inv_h2, diagonal);
#endif
  for (; x < count - 1; ++x) {
    const float neighbours = (row.p[x - 1] + row.p[x + 1]) * inv_h2.x +
                             (row.ym[x] + row.yp[x]) * inv_h2.y +
                             (row.zm[x] + row.zp[x]) * inv_h2.z;
    row.out[x] = (neighbours - row.div[x]) / diagonal;
  }
  jacobiCell(row, count - 1, count, inv_h2, diagonal);
}

void divergenceRow(const DivergenceRow& row, int count, glm::vec3 two_h) {
  auto cell = [&](int x) {
    const float xm = row.u[std::max(x - 1, 0)].x, xp = row.u[std::min(x + 1, count - 1)].x;
    row.out[x] = (xp - xm) / two_h.x + (row.yp[x].y - row.ym[x].y) / two_h.y +
                 (row.zp[x].z - row.zm[x].z) / two_h.z;
  };
  int x = 1;
#if defined(__x86_64__)
  if (useAvx2() && count >= 3) x = divergenceMiddleAvx2(row, count, two_h);
#endif
  cell(0);
  for (; x < count; ++x) cell(x);
}

void subtractGradientRow(const GradientRow& row, int count, glm::vec3 two_h) {
  auto cell = [&](int x) {
    const float xm = x > 0 ? row.p[x - 1] : 0.0f, xp = x + 1 < count ? row.p[x + 1] : 0.0f;
    row.u[x] -= glm::vec3((xp - xm) / two_h.x, (row.yp[x] - row.ym[x]) / two_h.y,
                          (row.zp[x] - row.zm[x]) / two_h.z);
  };
  int x = 1;
#if defined(__x86_64__)
  if (useAvx2() && count >= 3) x = gradientMiddleAvx2(row, count, two_h);
#endif
  if (count > 0) cell(0);
  for (; x < count; ++x) cell(x);
}

void cellRange(const glm::vec3* grid, glm::ivec3 n, glm::ivec3 lo, glm::ivec3 hi, glm::vec3* min,
               glm::vec3* max) {
#if defined(__x86_64__)
  if (useAvx2()) return cellRangeAvx2(grid, n, lo, hi, min, max);
#endif
  glm::vec3 low(std::numeric_limits<float>::infinity()), high(-low);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const glm::vec3 d = grid[(size_t(z) * n.y + y) * n.x + x];
        low = glm::min(low, d);
        high = glm::max(high, d);
      }
  *min = low;
  *max = high;
}

VoxelCellSampler::VoxelCellSampler(const std::vector<glm::vec3>& grid, glm::ivec3 cells,
                                   glm::ivec3 voxels, glm::vec3 voxel_to_cells, glm::vec3 offset)
    : grid_(grid), cells_(cells) {
  for (int a = 0; a < 3; ++a) {
    Taps& t = taps_[a];
    t.i0.resize(size_t(voxels[a]));
    t.i1.resize(size_t(voxels[a]));
    t.f.resize(size_t(voxels[a]));
    for (int v = 0; v < voxels[a]; ++v) {
      const float c =
          glm::clamp(float(v) * voxel_to_cells[a] + offset[a], 0.0f, float(cells[a] - 1));
      const int i0 = std::min(int(std::floor(c)), std::max(cells[a] - 2, 0));
      t.i0[size_t(v)] = i0;
      t.i1[size_t(v)] = std::min(i0 + 1, cells[a] - 1);
      t.f[size_t(v)] = c - float(i0);
    }
  }
}

void VoxelCellSampler::block(const VoxelBox& block, BlockDisplacement* out) const {
  const glm::ivec3 lo = block.lo, size = block.hi - block.lo;
  // The cells along y and z the block's voxels read, each once (slots), and which two slots
  // each voxel row and layer reads.
  struct Slots {
    int count = 0;
    int cell[2 * kBlock], s0[kBlock], s1[kBlock];
  };
  auto slots = [&](int axis) {
    Slots s;
    auto slot = [&s](int cell) {
      for (int i = 0; i < s.count; ++i)
        if (s.cell[i] == cell) return i;
      s.cell[s.count] = cell;
      return s.count++;
    };
    const Taps& t = taps_[axis];
    for (int v = 0; v < size[axis]; ++v) {
      s.s0[v] = slot(t.i0[size_t(lo[axis] + v)]);
      s.s1[v] = slot(t.i1[size_t(lo[axis] + v)]);
    }
    return s;
  };
  const Slots sy = slots(1), sz = slots(2);
  const Taps &tx = taps_[0], &ty = taps_[1], &tz = taps_[2];
  // The x lerps of every (y, z) slot pair, then the y lerps of every z slot, then the z lerps.
  // Columns past the block's width repeat its last voxel (computed, never used).
  float along_x[3][2 * kBlock][2 * kBlock][kBlock];
  for (int k = 0; k < sz.count; ++k)
    for (int j = 0; j < sy.count; ++j) {
      const glm::vec3* line = &grid_[(size_t(sz.cell[k]) * cells_.y + sy.cell[j]) * cells_.x];
      for (int i = 0; i < kBlock; ++i) {
        const size_t x = size_t(lo.x + std::min(i, size.x - 1));
        const glm::vec3 c = lerp(line[tx.i0[x]], line[tx.i1[x]], tx.f[x]);
        for (int a = 0; a < 3; ++a) along_x[a][k][j][i] = c[a];
      }
    }
  float along_y[3][2 * kBlock][kBlock][kBlock];
  for (int k = 0; k < sz.count; ++k)
    for (int y = 0; y < size.y; ++y) {
      const float fy = ty.f[size_t(lo.y + y)];
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < kBlock; ++i)
          along_y[a][k][y][i] = lerp(along_x[a][k][sy.s0[y]][i], along_x[a][k][sy.s1[y]][i], fy);
    }
  for (int z = 0; z < size.z; ++z) {
    const float fz = tz.f[size_t(lo.z + z)];
    for (int y = 0; y < size.y; ++y)
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < kBlock; ++i)
          out->d[a][(z * kBlock + y) * kBlock + i] =
              lerp(along_y[a][sz.s0[z]][y][i], along_y[a][sz.s1[z]][y][i], fz);
  }
}

PaddedDense::PaddedDense(const Volume& volume)
    : dims_(volume.dims()),
      padded_(dims_ + 2),
      voxels_(size_t(padded_.x) * padded_.y * padded_.z, 0.0f) {
  parallelFor(size_t(dims_.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    for (int z = int(z_begin); z < int(z_end); ++z)
      for (int y = 0; y < dims_.y; ++y)
        volume.readLine({0, y, z}, 0, dims_.x, &voxels_[index(0, y, z)]);
  });
}

float PaddedDense::sample(glm::vec3 v) const {
  const glm::ivec3 i0 = glm::ivec3(glm::floor(v));
  const glm::vec3 f = v - glm::vec3(i0);
  if (glm::all(glm::greaterThanEqual(i0, glm::ivec3(-1))) && glm::all(glm::lessThan(i0, dims_))) {
    const float* p = &voxels_[index(i0.x, i0.y, i0.z)];
    const size_t sy = size_t(padded_.x), sz = size_t(padded_.x) * padded_.y;
    const float c00 = lerp(p[0], p[1], f.x);
    const float c10 = lerp(p[sy], p[sy + 1], f.x);
    const float c01 = lerp(p[sz], p[sz + 1], f.x);
    const float c11 = lerp(p[sz + sy], p[sz + sy + 1], f.x);
    return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
  }
  auto at = [&](int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= dims_.x || y >= dims_.y || z >= dims_.z) return 0.0f;
    return voxels_[index(x, y, z)];
  };
  return trilinear(at, i0, f);
}

bool PaddedDense::sampleRow(int x0, int y, int z, int count, const float* dx, const float* dy,
                            const float* dz, glm::vec3 voxel_size, float fade, float* out) const {
  bool any = false;
  auto one = [&](int i) {
    const glm::vec3 v(x0 + i, y, z);
    out[i] = sample(v + glm::vec3(dx[i], dy[i], dz[i]) / voxel_size) * fade;
    any = any || out[i] != 0.0f;
  };
  int i = 0;
#if defined(__x86_64__)
  // The gathers index the copy with 32-bit lanes.
  if (useAvx2() && voxels_.size() <= size_t(INT_MAX))
    for (; i + 8 <= count; i += 8) {
      const int r = sampleEightAvx2(voxels_.data(), dims_, padded_, x0 + i, y, z, dx + i, dy + i,
                                    dz + i, voxel_size, fade, out + i);
      if (r >= 0)
        any = any || r > 0;
      else
        for (int k = i; k < i + 8; ++k) one(k);
    }
#endif
  for (; i < count; ++i) one(i);
  return any;
}

}  // namespace cb::wind
