#include "calibration/point_fit.h"

#include <array>
#include <cmath>
#include <utility>

namespace cb {
namespace {

// Similarity that moves the centroid to the origin and the mean distance to sqrt(2).
bool normalisingTransform(const std::vector<glm::dvec2>& pts, glm::dmat3* t) {
  glm::dvec2 c(0.0);
  for (const auto& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  double mean = 0.0;
  for (const auto& p : pts) mean += glm::length(p - c);
  mean /= static_cast<double>(pts.size());
  if (!(mean > 1e-12)) return false;
  const double s = std::sqrt(2.0) / mean;
  *t = glm::dmat3(1.0);
  (*t)[0][0] = s;
  (*t)[1][1] = s;
  (*t)[2][0] = -s * c.x;
  (*t)[2][1] = -s * c.y;
  return true;
}

// Eigen-decomposition of a symmetric n x n matrix by cyclic Jacobi rotations. On return the
// diagonal of `a` holds the eigenvalues and the columns of `v` the eigenvectors.
template <int N>
void jacobiEigen(std::array<std::array<double, N>, N>& a, std::array<std::array<double, N>, N>& v) {
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) v[i][j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < N; ++p)
      for (int q = p + 1; q < N; ++q) off += a[p][q] * a[p][q];
    if (off < 1e-30) break;
    for (int p = 0; p < N; ++p) {
      for (int q = p + 1; q < N; ++q) {
        if (std::abs(a[p][q]) < 1e-300) continue;
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
            (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1.0 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < N; ++k) {  // A <- A J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < N; ++k) {  // A <- J^T A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < N; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
}

std::string checkInput(const std::vector<glm::dvec2>& source, const std::vector<glm::dvec2>& target,
                       size_t min_points, const char* what) {
  if (source.size() != target.size()) {
    return std::string(what) + ": " + std::to_string(source.size()) + " source points but " +
           std::to_string(target.size()) + " targets";
  }
  if (source.size() < min_points) {
    return std::string(what) + " needs at least " + std::to_string(min_points) + " points, got " +
           std::to_string(source.size());
  }
  for (size_t i = 0; i < source.size(); ++i) {
    if (!std::isfinite(source[i].x) || !std::isfinite(source[i].y) || !std::isfinite(target[i].x) ||
        !std::isfinite(target[i].y)) {
      return std::string(what) + ": point " + std::to_string(i) + " is not finite";
    }
  }
  return {};
}

void computeResiduals(const std::vector<glm::dvec2>& source, const std::vector<glm::dvec2>& target,
                      PointFitResult* r) {
  r->residuals.clear();
  double sum2 = 0.0;
  r->max_residual = 0.0;
  for (size_t i = 0; i < source.size(); ++i) {
    const double e = glm::length(applyTransform(r->transform, source[i]) - target[i]);
    r->residuals.push_back(e);
    sum2 += e * e;
    r->max_residual = std::max(r->max_residual, e);
  }
  r->rms = source.empty() ? 0.0 : std::sqrt(sum2 / source.size());
}

// Smallest |eigenvalue| of the normal matrix relative to the largest: near zero when the
// points are collinear (or coincide) in the normalised frame.
constexpr double kDegenerate = 1e-10;

}  // namespace

const char* pointFitKindName(PointFitKind kind) {
  switch (kind) {
    case PointFitKind::kAffine:
      return "affine";
    case PointFitKind::kHomography:
      return "homography";
    case PointFitKind::kNone:
      break;
  }
  return "none";
}

bool parsePointFitKind(const std::string& text, PointFitKind* out) {
  if (text == "none")
    *out = PointFitKind::kNone;
  else if (text == "affine")
    *out = PointFitKind::kAffine;
  else if (text == "homography")
    *out = PointFitKind::kHomography;
  else
    return false;
  return true;
}

glm::dvec2 applyTransform(const glm::dmat3& m, glm::dvec2 p) {
  const glm::dvec3 h = m * glm::dvec3(p, 1.0);
  return glm::dvec2(h.x / h.z, h.y / h.z);
}

PointFitResult fitAffine(const std::vector<glm::dvec2>& source,
                         const std::vector<glm::dvec2>& target) {
  PointFitResult r;
  r.error = checkInput(source, target, 3, "affine fit");
  if (!r.error.empty()) return r;
  glm::dmat3 ts, tt;
  if (!normalisingTransform(source, &ts) || !normalisingTransform(target, &tt)) {
    r.error = "affine fit: all points coincide";
    return r;
  }
  // Normal equations M^T M p = M^T b with rows (x, y, 1) in the normalised frames.
  glm::dmat3 mtm(0.0);  // symmetric, so column-major vs row-major does not matter
  glm::dvec3 mtbx(0.0), mtby(0.0);
  for (size_t i = 0; i < source.size(); ++i) {
    const glm::dvec3 s = ts * glm::dvec3(source[i], 1.0);
    const glm::dvec3 t = tt * glm::dvec3(target[i], 1.0);
    mtm += glm::outerProduct(s, s);
    mtbx += s * t.x;
    mtby += s * t.y;
  }
  const double scale = std::abs(mtm[0][0]) + std::abs(mtm[1][1]) + std::abs(mtm[2][2]);
  if (std::abs(glm::determinant(mtm)) < kDegenerate * scale * scale * scale) {
    r.error = "affine fit: the points are collinear, spread them over the screen";
    return r;
  }
  const glm::dmat3 inv = glm::inverse(mtm);
  const glm::dvec3 px = inv * mtbx, py = inv * mtby;
  glm::dmat3 a(1.0);  // rows (px), (py), (0 0 1); glm is column-major: a[col][row]
  for (int c = 0; c < 3; ++c) {
    a[c][0] = px[c];
    a[c][1] = py[c];
    a[c][2] = c == 2 ? 1.0 : 0.0;
  }
  r.transform = glm::inverse(tt) * a * ts;
  r.ok = true;
  computeResiduals(source, target, &r);
  return r;
}

PointFitResult fitHomography(const std::vector<glm::dvec2>& source,
                             const std::vector<glm::dvec2>& target) {
  PointFitResult r;
  r.error = checkInput(source, target, 4, "homography fit");
  if (!r.error.empty()) return r;
  glm::dmat3 ts, tt;
  if (!normalisingTransform(source, &ts) || !normalisingTransform(target, &tt)) {
    r.error = "homography fit: all points coincide";
    return r;
  }
  // A^T A accumulated from the two DLT rows of each correspondence (x,y) -> (u,v):
  //   [ 0 0 0  -x -y -1   v x  v y  v ]
  //   [ x y 1   0  0  0  -u x -u y -u ]
  std::array<std::array<double, 9>, 9> ata{};
  for (size_t i = 0; i < source.size(); ++i) {
    const glm::dvec3 s = ts * glm::dvec3(source[i], 1.0);
    const glm::dvec3 t = tt * glm::dvec3(target[i], 1.0);
    const double x = s.x, y = s.y, u = t.x, v = t.y;
    const std::array<double, 9> r1 = {0, 0, 0, -x, -y, -1, v * x, v * y, v};
    const std::array<double, 9> r2 = {x, y, 1, 0, 0, 0, -u * x, -u * y, -u};
    for (int a = 0; a < 9; ++a)
      for (int b = 0; b < 9; ++b) ata[a][b] += r1[a] * r1[b] + r2[a] * r2[b];
  }
  std::array<std::array<double, 9>, 9> vecs{};
  jacobiEigen<9>(ata, vecs);
  int smallest = 0, second = -1;
  double largest = 0.0;
  for (int i = 0; i < 9; ++i) {
    largest = std::max(largest, std::abs(ata[i][i]));
    if (ata[i][i] < ata[smallest][smallest]) smallest = i;
  }
  for (int i = 0; i < 9; ++i) {
    if (i != smallest && (second < 0 || ata[i][i] < ata[second][second])) second = i;
  }
  // A unique solution needs a one-dimensional null space: the second smallest eigenvalue must
  // stand clear of zero (it does not when three or more points are collinear and N = 4).
  if (!(ata[second][second] > kDegenerate * largest)) {
    r.error =
        "homography fit: the points do not determine a homography (three or more are "
        "collinear); spread them over the screen";
    return r;
  }
  glm::dmat3 hn;  // h is row-major: h0 h1 h2 / h3 h4 h5 / h6 h7 h8
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) hn[col][row] = vecs[row * 3 + col][smallest];
  glm::dmat3 h = glm::inverse(tt) * hn * ts;
  if (std::abs(h[2][2]) < 1e-300) {
    r.error = "homography fit: the solution maps the origin to infinity";
    return r;
  }
  h /= h[2][2];
  r.transform = h;
  r.ok = true;
  computeResiduals(source, target, &r);
  return r;
}

PointFitResult fitPoints(PointFitKind kind, const std::vector<glm::dvec2>& source,
                         const std::vector<glm::dvec2>& target) {
  switch (kind) {
    case PointFitKind::kAffine:
      return fitAffine(source, target);
    case PointFitKind::kHomography:
      return fitHomography(source, target);
    case PointFitKind::kNone:
      break;
  }
  PointFitResult r;
  r.ok = true;
  computeResiduals(source, target, &r);
  return r;
}

}  // namespace cb
