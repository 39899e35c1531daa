#include "app/tools/distance_transform.h"

#include <algorithm>
#include <limits>

#include "app/core/parallel_for.h"

namespace cb {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// 1D lower envelope of parabolas: d[q] = min_p (q − p)² + f[p]; arg[q] = the minimising p.
// Scratch v (n ints) and z (n+1 floats) are passed in to avoid reallocating per row.
void envelope1d(const float* f, int n, float* d, int* arg, int* v, float* z) {
  int k = -1;  // index of the rightmost parabola in the envelope
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;  // not a feature and no finite distance yet: no parabola
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    float s;
    while (true) {  // z[0] = -inf ends the loop at k = 0 at the latest
      const int p = v[k];
      s = ((f[q] + float(q) * q) - (f[p] + float(p) * p)) / (2.0f * float(q - p));
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  if (k < 0) {
    for (int q = 0; q < n; ++q) {
      d[q] = kInf;
      if (arg) arg[q] = -1;
    }
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < float(q)) ++j;
    const float dq = float(q - v[j]);
    d[q] = dq * dq + f[v[j]];
    if (arg) arg[q] = v[j];
  }
}

}  // namespace

void squaredDistance2d(int width, int height, const std::vector<uint8_t>& feature,
                       std::vector<float>* squared, std::vector<int>* nearest) {
  const size_t n = size_t(width) * height;
  std::vector<float> column_d(n);
  std::vector<int> column_arg(n);  // nearest feature row within the column
  parallelFor(size_t(width), 64, [&](size_t, size_t b, size_t e) {
    std::vector<float> f(height), d(height), z(height + 1);
    std::vector<int> v(height), arg(height);
    for (size_t x = b; x < e; ++x) {
      for (int y = 0; y < height; ++y) f[y] = feature[size_t(y) * width + x] ? 0.0f : kInf;
      envelope1d(f.data(), height, d.data(), arg.data(), v.data(), z.data());
      for (int y = 0; y < height; ++y) {
        column_d[size_t(y) * width + x] = d[y];
        column_arg[size_t(y) * width + x] = arg[y];
      }
    }
  });
  squared->assign(n, kInf);
  if (nearest) nearest->assign(n, -1);
  parallelFor(size_t(height), 64, [&](size_t, size_t b, size_t e) {
    std::vector<float> z(width + 1);
    std::vector<int> v(width), arg(width);
    for (size_t y = b; y < e; ++y) {
      const float* f = &column_d[y * width];
      envelope1d(f, width, &(*squared)[y * width], arg.data(), v.data(), z.data());
      if (nearest)
        for (int x = 0; x < width; ++x) {
          const int fx = arg[x];
          if (fx < 0) continue;
          const int fy = column_arg[y * width + fx];
          (*nearest)[y * width + x] = fy * width + fx;
        }
    }
  });
}

void squaredDistance3d(int nx, int ny, int nz, const std::vector<uint8_t>& feature,
                       std::vector<float>* squared) {
  const size_t n = size_t(nx) * ny * nz;
  std::vector<float>& g = *squared;
  g.resize(n);
  for (size_t i = 0; i < n; ++i) g[i] = feature[i] ? 0.0f : kInf;
  const int longest = std::max(nx, std::max(ny, nz));
  // One pass per axis; each pass reads a line, solves it, and writes it back.
  auto pass = [&](int axis) {
    const int len = axis == 0 ? nx : axis == 1 ? ny : nz;
    const size_t stride = axis == 0 ? 1 : axis == 1 ? size_t(nx) : size_t(nx) * ny;
    const int a = axis == 0 ? ny : nx, b = axis == 2 ? ny : nz;
    const size_t lines = size_t(a) * b;
    parallelFor(lines, 256, [&](size_t, size_t lb, size_t le) {
      std::vector<float> f(longest), d(longest), z(longest + 1);
      std::vector<int> v(longest);
      for (size_t l = lb; l < le; ++l) {
        const int i = int(l % a), j = int(l / a);
        size_t base;
        if (axis == 0)
          base = (size_t(j) * ny + i) * nx;  // (y=i, z=j)
        else if (axis == 1)
          base = size_t(j) * nx * ny + i;  // (x=i, z=j)
        else
          base = size_t(j) * nx + i;  // (x=i, y=j)
        for (int q = 0; q < len; ++q) f[q] = g[base + q * stride];
        envelope1d(f.data(), len, d.data(), nullptr, v.data(), z.data());
        for (int q = 0; q < len; ++q) g[base + q * stride] = d[q];
      }
    });
  };
  pass(0);
  pass(1);
  pass(2);
}

}  // namespace cb
