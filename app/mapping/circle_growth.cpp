#include "app/mapping/circle_growth.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cb {
namespace {

enum PixelClass : uint8_t { kGrey = 0, kWhite = 1, kEmpty = 2 };

// Largest value of p[0..n) (0 if none is larger; NaN never wins), with eight independent lanes
// so the reduction does not wait on one dependency chain.
float maxOf(const float* p, size_t n) {
  float lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (int k = 0; k < 8; ++k) lane[k] = std::max(lane[k], p[i + size_t(k)]);
  for (; i < n; ++i) lane[0] = std::max(lane[0], p[i]);
  float m = lane[0];
  for (int k = 1; k < 8; ++k) m = std::max(m, lane[k]);
  return m;
}

bool insideCircle(glm::vec2 c, int r, int x, int y) {
  double dx = double(x) - double(c.x), dy = double(y) - double(c.y);
  return dx * dx + dy * dy <= double(r) * double(r);
}

// Fast counter: per-row prefix sums of white (static: white is judged on the unmasked
// footprint) and of empty-or-covered (updated when a circle is masked out), kept only over the
// bounding box of the non-empty pixels; everything outside it is empty. The tables live in a
// per-thread workspace that keeps its memory between strokes: fresh multi-megabyte buffers
// cost more in page faults than the whole growth.
struct RowPrefixWorkspace {
  std::vector<uint8_t> cls;
  std::vector<int32_t> white, empty;
};

class RowPrefixCounter {
 public:
  // row_max[y]: the largest value of footprint row y.
  RowPrefixCounter(const Footprint& f, const CircleGrowthConfig& cfg,
                   const std::vector<float>& row_max)
      : w_(f.width),
        h_(f.height),
        cls_(workspace().cls),
        white_(workspace().white),
        empty_(workspace().empty),
        covered_(size_t(f.width) * f.height, 0) {
    // Bounding box of the non-empty pixels: a row's maximum first (a branch-free reduction),
    // then its ends only where the row has ink.
    int x0 = w_, x1 = -1, y0 = h_, y1 = -1;
    for (int y = 0; y < h_; ++y) {
      const float* row = &f.values[size_t(y) * w_];
      if (!(row_max[size_t(y)] > cfg.empty_threshold)) continue;
      int first = 0, last = w_ - 1;
      while (!(row[first] > cfg.empty_threshold)) ++first;
      while (!(row[last] > cfg.empty_threshold)) --last;
      x0 = std::min(x0, first);
      x1 = std::max(x1, last);
      y0 = std::min(y0, y);
      y1 = y;
    }
    if (x1 < 0) x0 = y0 = 0, x1 = y1 = -1;
    bx0_ = x0;
    by0_ = y0;
    bw_ = x1 - x0 + 1;
    bh_ = y1 - y0 + 1;
    const size_t stride = size_t(bw_) + 1;
    cls_.assign(size_t(bw_) * bh_, kEmpty);
    white_.assign(stride * bh_, 0);
    empty_.assign(stride * bh_, 0);
    for (int y = 0; y < bh_; ++y) {
      const float* src = &f.values[size_t(y + by0_) * w_ + bx0_];
      uint8_t* cls = &cls_[size_t(y) * bw_];
      int32_t* wp = &white_[y * stride];
      int32_t* ep = &empty_[y * stride];
      for (int x = 0; x < bw_; ++x) {
        const float v = src[x];
        cls[x] = v >= cfg.white_threshold ? kWhite : (v <= cfg.empty_threshold ? kEmpty : kGrey);
        wp[x + 1] = wp[x] + (cls[x] == kWhite);
        ep[x + 1] = ep[x] + (cls[x] == kEmpty);
      }
    }
  }

  // Circles have integer centres here, so row half-widths come from a table:
  // half_width(r, |dy|) = floor(sqrt(r² − dy²)), the same pixels as circleRowSpan.
  CircleCounts count(glm::vec2 centre, int r) const {
    CircleCounts n;
    const int cx = int(centre.x), cy = int(centre.y);
    const int* hw = halfWidths(r);
    const size_t stride = size_t(bw_) + 1;
    for (int dy = -r; dy <= r; ++dy) {
      const int half = hw[dy < 0 ? -dy : dy];
      const int x0 = cx - half, x1 = cx + half;
      const long long span = 2 * half + 1;
      n.pixels += span;
      const int by = cy + dy - by0_;
      if (by < 0 || by >= bh_) {
        n.empty += span;
        continue;
      }
      const int a = std::max(x0 - bx0_, 0), b = std::min(x1 - bx0_, bw_ - 1);
      const long long inside = b >= a ? b - a + 1 : 0;
      n.empty += span - inside;
      if (inside) {
        const int32_t* wp = &white_[by * stride];
        const int32_t* ep = &empty_[by * stride];
        n.white += wp[b + 1] - wp[a];
        n.empty += ep[b + 1] - ep[a];
      }
    }
    return n;
  }

  void mask(glm::vec2 centre, int r) {
    const int cx = int(centre.x), cy = int(centre.y);
    const int* hw = halfWidths(r);
    for (int dy = -r; dy <= r; ++dy) {
      const int y = cy + dy;
      if (y < 0 || y >= h_) continue;
      const int half = hw[dy < 0 ? -dy : dy];
      const int x0 = std::max(cx - half, 0), x1 = std::min(cx + half, w_ - 1);
      if (x1 < x0) continue;
      std::fill(covered_.begin() + size_t(y) * w_ + x0, covered_.begin() + size_t(y) * w_ + x1 + 1,
                uint8_t(1));
      rebuildEmptyRow(y, x0, x1);
    }
  }

  uint8_t pixelClass(int x, int y) const {
    const int bx = x - bx0_, by = y - by0_;
    if (bx < 0 || by < 0 || bx >= bw_ || by >= bh_) return kEmpty;
    return cls_[size_t(by) * bw_ + bx];
  }
  bool covered(int x, int y) const { return covered_[size_t(y) * w_ + x] != 0; }
  std::vector<uint8_t> takeCovered() { return std::move(covered_); }

 private:
  // Pixels [x0, x1] of image row y were just covered: recount the row's prefix over the span,
  // then shift the rest of the row by the change.
  void rebuildEmptyRow(int y, int x0, int x1) {
    const int by = y - by0_;
    if (by < 0 || by >= bh_) return;
    const int a = std::max(x0 - bx0_, 0), b = std::min(x1 - bx0_, bw_ - 1);
    if (b < a) return;
    int32_t* ep = &empty_[by * (size_t(bw_) + 1)];
    const uint8_t* cls = &cls_[size_t(by) * bw_];
    const uint8_t* cov = &covered_[size_t(y) * w_ + bx0_];
    const int32_t before = ep[b + 1];
    for (int x = a; x <= b; ++x) ep[x + 1] = ep[x] + (cls[x] == kEmpty || cov[x] != 0);
    const int32_t delta = ep[b + 1] - before;
    if (delta)
      for (int x = b + 2; x <= bw_; ++x) ep[x] += delta;
  }

  // Row half-widths of the integer circle of radius r, built on first use.
  const int* halfWidths(int r) const {
    if (size_t(r) >= half_widths_.size()) half_widths_.resize(size_t(r) + 1);
    std::vector<int>& t = half_widths_[size_t(r)];
    if (t.empty()) {
      t.resize(size_t(r) + 1);
      for (int dy = 0; dy <= r; ++dy) {
        int h = int(std::sqrt(double(r) * r - double(dy) * dy));
        while (h * h + dy * dy > r * r) --h;
        while ((h + 1) * (h + 1) + dy * dy <= r * r) ++h;
        t[size_t(dy)] = h;
      }
    }
    return t.data();
  }

  static RowPrefixWorkspace& workspace() {
    thread_local RowPrefixWorkspace ws;
    return ws;
  }

  int w_, h_;
  int bx0_ = 0, by0_ = 0, bw_ = 0, bh_ = 0;  // bounding box of the non-empty pixels
  std::vector<uint8_t>& cls_;
  std::vector<int32_t>&white_, &empty_;
  std::vector<uint8_t> covered_;
  mutable std::vector<std::vector<int>> half_widths_;
};

// Straightforward counter (Algorithm 7): traverses the circle's bounding block pixel by pixel.
class BlockTraversalCounter {
 public:
  BlockTraversalCounter(const Footprint& f, const CircleGrowthConfig& cfg,
                        const std::vector<float>& /*row_max*/)
      : f_(f), cfg_(cfg), covered_(f.values.size(), 0) {}

  CircleCounts count(glm::vec2 c, int r) const { return countCircle(f_, &covered_, c, r, cfg_); }

  void mask(glm::vec2 c, int r) {
    for (int y = std::max(0, int(std::floor(c.y - r))); y <= std::min(f_.height - 1, int(c.y + r));
         ++y)
      for (int x = std::max(0, int(std::floor(c.x - r))); x <= std::min(f_.width - 1, int(c.x + r));
           ++x)
        if (insideCircle(c, r, x, y)) covered_[size_t(y) * f_.width + x] = 1;
  }

  uint8_t pixelClass(int x, int y) const {
    const float v = f_.at(x, y);
    return v >= cfg_.white_threshold ? kWhite : (v <= cfg_.empty_threshold ? kEmpty : kGrey);
  }
  bool covered(int x, int y) const { return covered_[size_t(y) * f_.width + x] != 0; }
  std::vector<uint8_t> takeCovered() { return std::move(covered_); }

 private:
  const Footprint& f_;
  const CircleGrowthConfig& cfg_;
  std::vector<uint8_t> covered_;
};

bool passes(const CircleCounts& n, const CircleGrowthConfig& cfg) {
  return n.whiteRatio() >= cfg.accept_white_ratio && n.emptyRatio() <= cfg.drop_empty_ratio;
}

// Returns the accepted radius at `centre`, or 0 when the direction is dropped or nothing fits.
// A radius passes when R_w >= accept and R_e <= drop. The Empty Test (§6.3.3) runs first, on the
// initial circle (the thesis) or on the smallest one (config empty_test_on_smallest): if it is
// more than half empty the direction is dropped. After it, a too-empty circle is just too big,
// like a too-grey one.
template <typename Counter>
int searchRadius(const Counter& counter, glm::vec2 centre, const CircleGrowthConfig& cfg,
                 RadiusSearch search, bool empty_test_on_smallest, long long* attempts) {
  const int r0 = cfg.initial_diameter_px / 2;
  const int rmin = std::min(cfg.min_radius_px, r0);
  ++*attempts;
  CircleCounts smallest = counter.count(centre, rmin);
  if (smallest.emptyRatio() > cfg.drop_empty_ratio) return 0;  // Empty Test (§6.3.3)
  if (!empty_test_on_smallest && r0 > rmin) {
    ++*attempts;
    CircleCounts initial = counter.count(centre, r0);
    if (initial.emptyRatio() > cfg.drop_empty_ratio) return 0;
    if (initial.whiteRatio() >= cfg.accept_white_ratio) return r0;
  }
  if (search == RadiusSearch::kLinearStep4) {
    // Algorithm 6: from the initial radius down, 4 px per attempt.
    for (int r = r0; r > rmin; r -= 4) {
      ++*attempts;
      if (passes(counter.count(centre, r), cfg)) return r;
    }
    return passes(smallest, cfg) ? rmin : 0;
  }
  // Binary search for the largest passing radius in [rmin, r0] (§6.4.6).
  if (!passes(smallest, cfg)) return 0;
  int lo = rmin + 1, hi = r0, best = rmin;
  while (lo <= hi) {
    int mid = lo + (hi - lo + 1) / 2;
    ++*attempts;
    if (passes(counter.count(centre, mid), cfg)) {
      best = mid;
      lo = mid + 1;
    } else {
      hi = mid - 1;
    }
  }
  return best;
}

// Path points ordered from the middle of the stroke outwards (by index along the path).
std::vector<glm::ivec2> seedOrder(const Footprint& f, const std::vector<StrokePoint>& path) {
  std::vector<glm::ivec2> order;
  const int n = int(path.size());
  const int mid = n / 2;
  for (int k = 0; k < n; ++k) {
    int i = (k % 2 == 0) ? mid + k / 2 : mid - (k + 1) / 2;
    if (i < 0 || i >= n) continue;
    glm::ivec2 p(int(std::lround(path[i].footprint_px.x)),
                 int(std::lround(path[i].footprint_px.y)));
    if (f.inside(p.x, p.y)) order.push_back(p);
  }
  return order;
}

// Thresholds for this footprint from its row maxima (see effectiveCircleConfig).
CircleGrowthConfig thresholdsFor(const CircleGrowthConfig& config, float peak) {
  CircleGrowthConfig c = config;
  if (!c.white_relative_to_peak) return c;
  peak = std::min(peak, 1.0f);
  c.white_threshold = std::max(c.white_threshold * peak, std::nextafter(c.empty_threshold, 2.0f));
  return c;
}

template <typename Counter>
CircleGrowthResult grow(const Footprint& f, const std::vector<StrokePoint>& path,
                        const CircleGrowthConfig& config, RadiusSearch search) {
  CircleGrowthResult result;
  if (f.width <= 0 || f.height <= 0 || f.values.size() != size_t(f.width) * f.height) return result;
  // One pass over the footprint: each row's maximum gives the peak and the rows with ink.
  std::vector<float> row_max(size_t(f.height));
  float peak = 0.0f;
  for (int y = 0; y < f.height; ++y) {
    row_max[size_t(y)] = maxOf(&f.values[size_t(y) * f.width], size_t(f.width));
    peak = std::max(peak, row_max[size_t(y)]);
  }
  const CircleGrowthConfig cfg = thresholdsFor(config, peak);
  Counter counter(f, cfg, row_max);

  std::vector<glm::vec2> dirs(cfg.directions);
  for (int j = 0; j < cfg.directions; ++j) {
    double a = 2.0 * std::numbers::pi * j / cfg.directions;
    dirs[j] = glm::vec2(float(std::cos(a)), float(std::sin(a)));
  }

  auto accept = [&](glm::vec2 c, int r, int step) {
    result.circles.push_back({c, r, step});
    counter.mask(c, r);
  };

  // Algorithm 6: grow step by step from the circles accepted in the previous step.
  auto growFrom = [&](size_t first_circle) {
    size_t begin = first_circle, end = result.circles.size();
    int step = 1;
    while (begin < end) {
      for (size_t i = begin; i < end; ++i) {
        const Circle parent = result.circles[i];
        for (const glm::vec2& d : dirs) {
          // Candidate centres snap to pixel centres (integer), so circle tests use row tables.
          glm::vec2 c = glm::round(parent.centre + d * float(parent.radius));
          if (c.x < 0 || c.y < 0 || c.x > f.width - 1 || c.y > f.height - 1) continue;
          if (int r = searchRadius(counter, c, cfg, search, cfg.empty_test_on_smallest,
                                   &result.attempts))
            accept(c, r, step);
        }
      }
      ++result.steps;
      ++step;
      begin = end;
      end = result.circles.size();
    }
  };

  auto trySeed = [&](glm::ivec2 p) {
    if (counter.pixelClass(p.x, p.y) != kWhite || counter.covered(p.x, p.y)) return false;
    glm::vec2 c(p);
    // A seed lies on the drawn path, inside the stroke: only its own circle's emptiness
    // matters, so a stroke thinner than the initial diameter still gets circles along it.
    int r =
        searchRadius(counter, c, cfg, search, /*empty_test_on_smallest=*/true, &result.attempts);
    if (!r) return false;
    size_t first = result.circles.size();
    accept(c, r, 0);
    ++result.seeds;
    growFrom(first);
    return true;
  };

  std::vector<glm::ivec2> seeds = seedOrder(f, path);
  if (seeds.empty()) {
    // No usable path: the white pixel nearest the centroid of the white pixels.
    double sx = 0, sy = 0;
    long long nw = 0;
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x)
        if (counter.pixelClass(x, y) == kWhite) sx += x, sy += y, ++nw;
    if (nw) {
      glm::dvec2 centroid(sx / nw, sy / nw);
      double best = 1e300;
      glm::ivec2 pick(0);
      for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
          if (counter.pixelClass(x, y) != kWhite) continue;
          double d = glm::dot(glm::dvec2(x, y) - centroid, glm::dvec2(x, y) - centroid);
          if (d < best) best = d, pick = {x, y};
        }
      seeds.push_back(pick);
    }
  }
  for (const glm::ivec2& p : seeds)
    if (trySeed(p) && !cfg.reseed_along_path) break;

  result.covered = counter.takeCovered();
  return result;
}

}  // namespace

bool circleRowSpan(glm::vec2 c, int r, int y, int* x0, int* x1) {
  double dy = double(y) - double(c.y);
  double rem = double(r) * double(r) - dy * dy;
  if (rem < 0.0) return false;
  double half = std::sqrt(rem);
  int a = int(std::ceil(double(c.x) - half)), b = int(std::floor(double(c.x) + half));
  // Make the span agree exactly with the per-pixel predicate.
  while (a <= b && !insideCircle(c, r, a, y)) ++a;
  while (insideCircle(c, r, a - 1, y)) --a;
  while (b >= a && !insideCircle(c, r, b, y)) --b;
  while (insideCircle(c, r, b + 1, y)) ++b;
  if (b < a) return false;
  *x0 = a;
  *x1 = b;
  return true;
}

CircleCounts countCircle(const Footprint& f, const std::vector<uint8_t>* covered, glm::vec2 c,
                         int r, const CircleGrowthConfig& cfg) {
  CircleCounts n;
  for (int y = int(std::floor(c.y - r)); y <= int(std::ceil(c.y + r)); ++y)
    for (int x = int(std::floor(c.x - r)); x <= int(std::ceil(c.x + r)); ++x) {
      if (!insideCircle(c, r, x, y)) continue;
      ++n.pixels;
      if (!f.inside(x, y)) {
        ++n.empty;
        continue;
      }
      float v = f.at(x, y);
      bool is_covered = covered && (*covered)[size_t(y) * f.width + x];
      if (v >= cfg.white_threshold) ++n.white;
      if (v <= cfg.empty_threshold || is_covered) ++n.empty;
    }
  return n;
}

CircleGrowthConfig effectiveCircleConfig(const Footprint& f, const CircleGrowthConfig& config) {
  return thresholdsFor(config, maxOf(f.values.data(), f.values.size()));
}

CircleGrowthResult growCircles(const Footprint& footprint, const std::vector<StrokePoint>& path,
                               const CircleGrowthConfig& config) {
  return grow<RowPrefixCounter>(footprint, path, config, RadiusSearch::kBinary);
}

CircleGrowthResult growCirclesStraightforward(const Footprint& footprint,
                                              const std::vector<StrokePoint>& path,
                                              const CircleGrowthConfig& config) {
  return grow<BlockTraversalCounter>(footprint, path, config, RadiusSearch::kLinearStep4);
}

}  // namespace cb
