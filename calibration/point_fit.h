// N-point calibration fit: the transform that takes where the pen was seen (source points) to
// where the targets were drawn (target points), by least squares, with the residual of every
// point in pixels.
//
// Affine (6 parameters, >= 3 points): ordinary least squares, x' = a x + b y + c,
// y' = d x + e y + f, solved per output through the 3x3 normal equations.
// Homography (8 parameters, >= 4 points): the normalized direct linear transform (Hartley &
// Zisserman, "Multiple View Geometry", 2nd ed., Alg. 4.2): both point sets are translated to
// their centroid and scaled to mean distance sqrt(2), each correspondence gives two rows of
// A h = 0, h is the right singular vector of A with the smallest singular value (here: the
// eigenvector of A^T A with the smallest eigenvalue, by Jacobi rotations), and the
// normalisation is undone: H = T'^-1 H~ T.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace cb {

enum class PointFitKind { kNone, kAffine, kHomography };

const char* pointFitKindName(PointFitKind kind);  // "none", "affine", "homography"
bool parsePointFitKind(const std::string& text, PointFitKind* out);

struct PointFitResult {
  bool ok = false;
  std::string error;              // why not ok (too few points, degenerate layout)
  glm::dmat3 transform{1.0};      // homogeneous, column-major (glm), source -> target
  std::vector<double> residuals;  // per point, in target units (px)
  double rms = 0.0, max_residual = 0.0;
};

// Applies a homogeneous 3x3 transform to a point (divides by w).
glm::dvec2 applyTransform(const glm::dmat3& m, glm::dvec2 p);

PointFitResult fitAffine(const std::vector<glm::dvec2>& source,
                         const std::vector<glm::dvec2>& target);
PointFitResult fitHomography(const std::vector<glm::dvec2>& source,
                             const std::vector<glm::dvec2>& target);
PointFitResult fitPoints(PointFitKind kind, const std::vector<glm::dvec2>& source,
                         const std::vector<glm::dvec2>& target);

}  // namespace cb
