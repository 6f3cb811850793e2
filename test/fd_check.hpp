// Central finite-difference checks of analytic derivatives, with a tolerance DERIVED from an
// estimate of the finite-difference error (DESIGN §8: "an error estimate for finite differences").
//
// For column j the central difference D(h) = (f(x + h e_j) − f(x − h e_j)) / 2h has
//   truncation error  D(h) − J = c h² + O(h⁴)   (c = f'''/6),
//   rounding error    ≈ eps · |f| / h           (f is evaluated to about eps · |f|).
// Richardson: D(2h) − J = 4c h² + …, so |D(h) − D(2h)| / 3 estimates the truncation error of D(h)
// (it also carries the rounding noise of both differences, which only makes it more conservative).
// h = cbrt(eps) · max(1, |x_j|) balances the two terms (h² ~ eps / h). Each entry passes if
//   |D(h) − J| ≤ safety · (truncation + 4 eps · f_scale / h) + 4 eps · ‖J‖_F,
// the last term a floor for round-off in J itself where both estimates happen to vanish.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace fdcheck {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;
using Function = std::function<Vec(const Vec&)>;

struct Options {
  double safety = 10.0;  ///< multiplies the estimated error
  /// Magnitude of the terms that make up f (its rounding error is ~eps·f_scale). 0: use max |f|
  /// over the evaluations of the column, right unless f is a small difference of large terms.
  double f_scale = 0.0;
};

struct Result {
  double max_ratio = 0.0;  ///< max |D − J| / tolerance over all entries; the check passes if < 1
  double max_rel = 0.0;    ///< max |D − J| / max |J|, for reporting
  double max_tol_rel = 0.0;  ///< max tolerance / max |J|: the smallest error the check can see
  Eigen::Index row = -1, col = -1;             ///< entry with the largest ratio
  double analytic = 0.0, fd = 0.0, tol = 0.0;  ///< that entry
  [[nodiscard]] bool ok() const { return max_ratio < 1.0; }
  void merge(const Result& o) {  // keep the worst case over several checks
    const double rel = std::max(max_rel, o.max_rel), tol_rel = std::max(max_tol_rel, o.max_tol_rel);
    if (o.max_ratio > max_ratio) *this = o;
    max_rel = rel;
    max_tol_rel = tol_rel;
  }
};

/// Compare the analytic Jacobian `jac` (rows: f, cols: x) with central differences of f at x.
inline Result check_jacobian(const Function& f, const Vec& x, const Mat& jac, Options opt = {}) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double floor = 4.0 * eps * jac.norm();
  const double jac_max = std::max(jac.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  Result r;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double h = std::cbrt(eps) * std::max(1.0, std::abs(x[j]));
    // Central difference with the steps actually taken ((x+h) − x is exact by Sterbenz).
    Vec lo = x, hi = x;
    auto difference = [&](double step, double& f_max) {
      hi[j] = x[j] + step;
      lo[j] = x[j] - step;
      const Vec fh = f(hi), fl = f(lo);
      f_max = std::max({f_max, fh.cwiseAbs().maxCoeff(), fl.cwiseAbs().maxCoeff()});
      return Vec((fh - fl) / (hi[j] - lo[j]));
    };
    double f_max = 0.0;
    const Vec d1 = difference(h, f_max);
    const Vec d2 = difference(2.0 * h, f_max);
    const double rounding = 4.0 * eps * (opt.f_scale > 0.0 ? opt.f_scale : f_max) / h;
    for (Eigen::Index i = 0; i < jac.rows(); ++i) {
      const double truncation = std::abs(d1[i] - d2[i]) / 3.0;
      const double tol = opt.safety * (truncation + rounding) + floor;
      const double err = std::abs(d1[i] - jac(i, j));
      const double ratio = err == 0.0 ? 0.0 : err / tol;  // tol = 0 and err > 0: inf
      r.max_rel = std::max(r.max_rel, err / jac_max);
      r.max_tol_rel = std::max(r.max_tol_rel, tol / jac_max);
      if (r.row < 0 || ratio > r.max_ratio) {
        r.max_ratio = ratio;
        r.row = i;
        r.col = j;
        r.analytic = jac(i, j);
        r.fd = d1[i];
        r.tol = tol;
      }
    }
  }
  return r;
}

/// Compare the analytic gradient of a scalar function with central differences (a 1-row Jacobian).
inline Result check_gradient(const std::function<double(const Vec&)>& u, const Vec& x,
                             const Vec& grad, Options opt = {}) {
  const Function as_vector = [&](const Vec& y) { return Vec::Constant(1, u(y)); };
  return check_jacobian(as_vector, x, grad.transpose(), opt);
}

}  // namespace fdcheck
