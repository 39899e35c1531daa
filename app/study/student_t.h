// The Student t distribution's CDF, for the paired t-test of the study report.
//
//   I_x(a, b), the regularised incomplete beta function, by its continued fraction (DLMF 8.17.22;
//   evaluated with the modified Lentz method, Press et al., Numerical Recipes 3rd ed., §5.2 and
//   §6.4, using the symmetry I_x(a,b) = 1 − I_{1−x}(b,a) where x > (a+1)/(a+b+2) so the fraction
//   converges fast).
//   For ν degrees of freedom: P(T ≤ t) = 1 − ½·I_{ν/(ν+t²)}(ν/2, ½) for t ≥ 0, and ½·I_{...}
//   for t < 0 (Abramowitz & Stegun 26.7.1 with 26.5.27; DLMF 8.17.1).
#pragma once

namespace cb {

// a, b > 0 and 0 ≤ x ≤ 1; NaN otherwise. Relative accuracy about 1e-14.
double regularizedIncompleteBeta(double a, double b, double x);
// ν > 0; NaN otherwise.
double studentTCdf(double t, double nu);

}  // namespace cb
