#include "ida_vector_ops.hpp"

#include <nvector/nvector_serial.h>

#include <cmath>

namespace ancf::detail {
namespace {

using Real = realtype;
using Size = sunindextype;

Real* data(N_Vector v) {
  return NV_DATA_S(v);
}
Size length(N_Vector v) {
  return NV_LENGTH_S(v);
}

// SUNRsqrt of SUNDIALS 6.4: 0 for x ≤ 0, √x otherwise (NaN stays NaN).
Real root(Real x) {
  return x <= 0.0 ? 0.0 : std::sqrt(x);
}

// The special cases of N_VLinearSum (nvector_serial.c), decided once for a coefficient pair and
// the aliasing of z; each case is the expression SUNDIALS evaluates per element.
enum class Sum {
  axpy_y,
  axpy_x,
  sum,
  diff_xy,
  diff_yx,
  lin1_b,
  lin1_a,
  lin2_b,
  lin2_a,
  scale_sum,
  scale_diff,
  general
};

Sum classify(Real a, Real b, bool z_is_y, bool z_is_x) {
  if (b == 1.0 && z_is_y) return Sum::axpy_y;  // y ← a x + y
  if (a == 1.0 && z_is_x) return Sum::axpy_x;  // x ← b y + x
  if (a == 1.0 && b == 1.0) return Sum::sum;
  if (a == 1.0 && b == -1.0) return Sum::diff_xy;
  if (a == -1.0 && b == 1.0) return Sum::diff_yx;
  if (a == 1.0) return Sum::lin1_b;   // b y + x
  if (b == 1.0) return Sum::lin1_a;   // a x + y
  if (a == -1.0) return Sum::lin2_b;  // b y − x
  if (b == -1.0) return Sum::lin2_a;  // a x − y
  if (a == b) return Sum::scale_sum;
  if (a == -b) return Sum::scale_diff;
  return Sum::general;
}

// Vaxpy_Serial: y ← a x + y with a = ±1 as additions (x may be y: no __restrict).
void axpy(Real a, const Real* x, Real* y, Size n) {
  if (a == 1.0)
    for (Size i = 0; i < n; ++i) y[i] += x[i];
  else if (a == -1.0)
    for (Size i = 0; i < n; ++i) y[i] -= x[i];
  else
    for (Size i = 0; i < n; ++i) y[i] += a * x[i];
}

// z = a x + b y as N_VLinearSum_Serial computes it, for case `c` (x, y, z may alias as classify
// allows: the element loops read x[i], y[i] before writing z[i]).
void linear_sum(Sum c, Real a, const Real* x, Real b, const Real* y, Real* z, Size n) {
  switch (c) {
    case Sum::axpy_y:
      axpy(a, x, z, n);
      return;
    case Sum::axpy_x:
      axpy(b, y, z, n);
      return;
    case Sum::sum:
      for (Size i = 0; i < n; ++i) z[i] = x[i] + y[i];
      return;
    case Sum::diff_xy:
      for (Size i = 0; i < n; ++i) z[i] = x[i] - y[i];
      return;
    case Sum::diff_yx:
      for (Size i = 0; i < n; ++i) z[i] = y[i] - x[i];
      return;
    case Sum::lin1_b:
      for (Size i = 0; i < n; ++i) z[i] = b * y[i] + x[i];
      return;
    case Sum::lin1_a:
      for (Size i = 0; i < n; ++i) z[i] = a * x[i] + y[i];
      return;
    case Sum::lin2_b:
      for (Size i = 0; i < n; ++i) z[i] = b * y[i] - x[i];
      return;
    case Sum::lin2_a:
      for (Size i = 0; i < n; ++i) z[i] = a * x[i] - y[i];
      return;
    case Sum::scale_sum:
      for (Size i = 0; i < n; ++i) z[i] = a * (x[i] + y[i]);
      return;
    case Sum::scale_diff:
      for (Size i = 0; i < n; ++i) z[i] = a * (x[i] - y[i]);
      return;
    case Sum::general:
      for (Size i = 0; i < n; ++i) z[i] = (a * x[i]) + (b * y[i]);
      return;
  }
}

void op_linear_sum(Real a, N_Vector x, Real b, N_Vector y, N_Vector z) {
  linear_sum(classify(a, b, z == y, z == x), a, data(x), b, data(y), data(z), length(x));
}

void op_const(Real c, N_Vector z) {
  Real* zd = data(z);
  for (Size i = 0, n = length(z); i < n; ++i) zd[i] = c;
}

void op_prod(N_Vector x, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  for (Size i = 0, n = length(x); i < n; ++i) zd[i] = xd[i] * yd[i];
}

void op_div(N_Vector x, N_Vector y, N_Vector z) {
  const Real *xd = data(x), *yd = data(y);
  Real* zd = data(z);
  for (Size i = 0, n = length(x); i < n; ++i) zd[i] = xd[i] / yd[i];
}

// N_VScale_Serial: z = c x (c = 1 a copy, c = −1 a negation: the same bits as c·x).
void scale(Real c, const Real* x, Real* z, Size n) {
  if (z == x)
    for (Size i = 0; i < n; ++i) z[i] *= c;
  else if (c == 1.0)
    for (Size i = 0; i < n; ++i) z[i] = x[i];
  else if (c == -1.0)
    for (Size i = 0; i < n; ++i) z[i] = -x[i];
  else
    for (Size i = 0; i < n; ++i) z[i] = c * x[i];
}

void op_scale(Real c, N_Vector x, N_Vector z) {
  scale(c, data(x), data(z), length(x));
}

void op_abs(N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  for (Size i = 0, n = length(x); i < n; ++i) zd[i] = std::abs(xd[i]);
}

void op_inv(N_Vector x, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  for (Size i = 0, n = length(x); i < n; ++i) zd[i] = 1.0 / xd[i];
}

void op_add_const(N_Vector x, Real b, N_Vector z) {
  const Real* xd = data(x);
  Real* zd = data(z);
  for (Size i = 0, n = length(x); i < n; ++i) zd[i] = xd[i] + b;
}

Real dot(const Real* x, const Real* y, Size n) {
  Real sum = 0.0;
  for (Size i = 0; i < n; ++i) sum += x[i] * y[i];
  return sum;
}

Real op_dot(N_Vector x, N_Vector y) {
  return dot(data(x), data(y), length(x));
}

Real op_max_norm(N_Vector x) {
  const Real* xd = data(x);
  Real largest = 0.0;
  for (Size i = 0, n = length(x); i < n; ++i)
    if (std::abs(xd[i]) > largest) largest = std::abs(xd[i]);
  return largest;
}

Real squares(const Real* x, const Real* w, Size n) {
  Real sum = 0.0;
  for (Size i = 0; i < n; ++i) {
    const Real p = x[i] * w[i];
    sum += p * p;
  }
  return sum;
}

Real masked_squares(const Real* x, const Real* w, const Real* id, Size n) {
  Real sum = 0.0;
  for (Size i = 0; i < n; ++i) {
    if (id[i] > 0.0) {
      const Real p = x[i] * w[i];
      sum += p * p;
    }
  }
  return sum;
}

Real op_wsqrsum(N_Vector x, N_Vector w) {
  return squares(data(x), data(w), length(x));
}

Real op_wsqrsum_mask(N_Vector x, N_Vector w, N_Vector id) {
  return masked_squares(data(x), data(w), data(id), length(x));
}

Real op_wrms_norm(N_Vector x, N_Vector w) {
  return root(op_wsqrsum(x, w) / static_cast<Real>(length(x)));
}

Real op_wrms_norm_mask(N_Vector x, N_Vector w, N_Vector id) {
  return root(op_wsqrsum_mask(x, w, id) / static_cast<Real>(length(x)));
}

Real op_min(N_Vector x) {
  const Real* xd = data(x);
  Real smallest = xd[0];
  for (Size i = 1, n = length(x); i < n; ++i)
    if (xd[i] < smallest) smallest = xd[i];
  return smallest;
}

// ---- fused and vector-array operations (N_VLinearCombination_Serial & co.), one pass each ----

constexpr int kSuccess = 0, kFailure = -1;

int op_linear_combination(int nvec, Real* c, N_Vector* X, N_Vector z) {
  if (nvec < 1) return kFailure;
  if (nvec == 1) {
    op_scale(c[0], X[0], z);
    return kSuccess;
  }
  if (nvec == 2) {
    op_linear_sum(c[0], X[0], c[1], X[1], z);
    return kSuccess;
  }
  // Up to IDA's maximum order + 1 terms; longer combinations take the term-by-term loops.
  constexpr int kMaxTerms = 8;
  const Size n = length(z);
  Real* zd = data(z);
  const Real* xs[kMaxTerms];
  // One pass needs every later term distinct from z: SUNDIALS' term-by-term loops would read
  // such a term after z has been overwritten.
  bool one_pass = nvec <= kMaxTerms;
  for (int k = 1; k < nvec && one_pass; ++k) one_pass = X[k] != z;
  if (one_pass)
    for (int k = 0; k < nvec; ++k) xs[k] = data(X[k]);
  // Each element: z_j = c₀ x₀ⱼ (or z_j, or c₀ z_j), then + c_k x_kj for k = 1 … in order.
  const bool in_place = X[0] == z, unit_first = in_place && c[0] == 1.0;
  if (one_pass) {
    for (Size j = 0; j < n; ++j) {
      Real s = unit_first ? zd[j] : (in_place ? zd[j] * c[0] : c[0] * xs[0][j]);
      for (int k = 1; k < nvec; ++k) s += c[k] * xs[k][j];
      zd[j] = s;
    }
    return kSuccess;
  }
  if (!unit_first) {
    if (in_place)
      for (Size j = 0; j < n; ++j) zd[j] *= c[0];
    else
      for (Size j = 0; j < n; ++j) zd[j] = c[0] * data(X[0])[j];
  }
  for (int k = 1; k < nvec; ++k) {
    const Real* xd = data(X[k]);
    for (Size j = 0; j < n; ++j) zd[j] += c[k] * xd[j];
  }
  return kSuccess;
}

int op_scale_add_multi(int nvec, Real* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  if (nvec < 1) return kFailure;
  if (nvec == 1) {
    op_linear_sum(a[0], x, 1.0, Y[0], Z[0]);
    return kSuccess;
  }
  const Size n = length(x);
  const Real* xd = data(x);
  for (int k = 0; k < nvec; ++k) {
    Real* yd = data(Y[k]);
    if (Y == Z) {
      for (Size j = 0; j < n; ++j) yd[j] += a[k] * xd[j];
    } else {
      Real* zd = data(Z[k]);
      for (Size j = 0; j < n; ++j) zd[j] = a[k] * xd[j] + yd[j];
    }
  }
  return kSuccess;
}

int op_dot_multi(int nvec, N_Vector x, N_Vector* Y, Real* dots) {
  if (nvec < 1) return kFailure;
  for (int k = 0; k < nvec; ++k) dots[k] = dot(data(x), data(Y[k]), length(x));
  return kSuccess;
}

int op_linear_sum_array(int nvec, Real a, N_Vector* X, Real b, N_Vector* Y, N_Vector* Z) {
  if (nvec < 1) return kFailure;
  if (nvec == 1) {
    op_linear_sum(a, X[0], b, Y[0], Z[0]);
    return kSuccess;
  }
  // The array version decides its case on the arrays (Z == Y, Z == X), once for all vectors.
  const Sum c = classify(a, b, Z == Y, Z == X);
  for (int k = 0; k < nvec; ++k)
    linear_sum(c, a, data(X[k]), b, data(Y[k]), data(Z[k]), length(Z[0]));
  return kSuccess;
}

int op_scale_array(int nvec, Real* c, N_Vector* X, N_Vector* Z) {
  if (nvec < 1) return kFailure;
  if (nvec == 1) {
    op_scale(c[0], X[0], Z[0]);
    return kSuccess;
  }
  const Size n = length(Z[0]);
  for (int k = 0; k < nvec; ++k) {
    Real* xd = data(X[k]);
    if (X == Z) {
      for (Size j = 0; j < n; ++j) xd[j] *= c[k];
    } else {
      Real* zd = data(Z[k]);
      for (Size j = 0; j < n; ++j) zd[j] = c[k] * xd[j];
    }
  }
  return kSuccess;
}

int op_const_array(int nvec, Real c, N_Vector* Z) {
  if (nvec < 1) return kFailure;
  for (int k = 0; k < nvec; ++k) op_const(c, Z[k]);
  return kSuccess;
}

int op_wrms_norm_array(int nvec, N_Vector* X, N_Vector* W, Real* norms) {
  if (nvec < 1) return kFailure;
  for (int k = 0; k < nvec; ++k) norms[k] = op_wrms_norm(X[k], W[k]);
  return kSuccess;
}

int op_wrms_norm_mask_array(int nvec, N_Vector* X, N_Vector* W, N_Vector id, Real* norms) {
  if (nvec < 1) return kFailure;
  for (int k = 0; k < nvec; ++k) norms[k] = op_wrms_norm_mask(X[k], W[k], id);
  return kSuccess;
}

}  // namespace

void use_compiled_serial_ops(N_Vector v) {
  // SUNDIALS' fused operations first (this sets the entries we do not replace, e.g. the
  // vector-array forms of ScaleAddMulti and LinearCombination, which IDA does not use).
  N_VEnableFusedOps_Serial(v, SUNTRUE);
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = op_linear_sum;
  ops->nvconst = op_const;
  ops->nvprod = op_prod;
  ops->nvdiv = op_div;
  ops->nvscale = op_scale;
  ops->nvabs = op_abs;
  ops->nvinv = op_inv;
  ops->nvaddconst = op_add_const;
  ops->nvdotprod = op_dot;
  ops->nvdotprodlocal = op_dot;
  ops->nvmaxnorm = op_max_norm;
  ops->nvmaxnormlocal = op_max_norm;
  ops->nvwrmsnorm = op_wrms_norm;
  ops->nvwrmsnormmask = op_wrms_norm_mask;
  ops->nvwsqrsumlocal = op_wsqrsum;
  ops->nvwsqrsummasklocal = op_wsqrsum_mask;
  ops->nvmin = op_min;
  ops->nvminlocal = op_min;
  ops->nvlinearcombination = op_linear_combination;
  ops->nvscaleaddmulti = op_scale_add_multi;
  ops->nvdotprodmulti = op_dot_multi;
  ops->nvdotprodmultilocal = op_dot_multi;
  ops->nvlinearsumvectorarray = op_linear_sum_array;
  ops->nvscalevectorarray = op_scale_array;
  ops->nvconstvectorarray = op_const_array;
  ops->nvwrmsnormvectorarray = op_wrms_norm_array;
  ops->nvwrmsnormmaskvectorarray = op_wrms_norm_mask_array;
}

}  // namespace ancf::detail
