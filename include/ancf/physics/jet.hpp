// Second-order forward-mode differentiation with fixed-size storage: a scalar carrying its value,
// gradient and Hessian with respect to N independent variables ("jet"), closed under the
// operations the rod element needs (+, −, ×, ÷, sqrt, sin, cos, atan2).
//
// Why: the Kirchhoff rod's strains are compositions of smallest-rotation maps whose hand-expanded
// second derivatives are long and error-prone (4C differentiates the same element with forward AD,
// docs/rod.md). Propagating exact first and second derivatives through each elementary operation
// by the chain rule gives the internal force and tangent stiffness to round-off, with no finite
// differences; test_kirchhoff_rod_element checks them against central differences.
//
// With kSecond = false only value and gradient are carried (residual-only evaluations).
// All storage is fixed-size Eigen: no heap allocation.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <type_traits>

namespace ancf {

template <int N, bool kSecond = true>
struct Jet {
  using Grad = Eigen::Matrix<double, N, 1>;
  // Without second derivatives the Hessian slot is a 1×1 placeholder, so that a first-order jet
  // is not copied with 8N² dead bytes on every operation (measured: ~3× on the rod's force).
  using Hess =
      std::conditional_t<kSecond, Eigen::Matrix<double, N, N>, Eigen::Matrix<double, 1, 1>>;
  double v = 0.0;
  Grad g = Grad::Zero();
  Hess h;  // valid only if kSecond (left uninitialised otherwise)

  Jet() {
    if constexpr (kSecond) h.setZero();
  }
  Jet(double value) : v(value) {  // NOLINT: implicit constants are the point of a scalar type
    if constexpr (kSecond) h.setZero();
  }
  /// Independent variable number i with value x.
  static Jet variable(double x, int i) {
    Jet j(x);
    j.g[i] = 1.0;
    return j;
  }

  Jet& operator+=(const Jet& o) {
    v += o.v;
    g += o.g;
    if constexpr (kSecond) h += o.h;
    return *this;
  }
  Jet& operator-=(const Jet& o) {
    v -= o.v;
    g -= o.g;
    if constexpr (kSecond) h -= o.h;
    return *this;
  }
  Jet& operator*=(double s) {
    v *= s;
    g *= s;
    if constexpr (kSecond) h *= s;
    return *this;
  }
};

template <int N, bool S>
Jet<N, S> operator+(Jet<N, S> a, const Jet<N, S>& b) {
  return a += b;
}
template <int N, bool S>
Jet<N, S> operator-(Jet<N, S> a, const Jet<N, S>& b) {
  return a -= b;
}
template <int N, bool S>
Jet<N, S> operator-(Jet<N, S> a) {
  return a *= -1.0;
}
template <int N, bool S>
Jet<N, S> operator+(Jet<N, S> a, double b) {
  a.v += b;
  return a;
}
template <int N, bool S>
Jet<N, S> operator+(double b, Jet<N, S> a) {
  a.v += b;
  return a;
}
template <int N, bool S>
Jet<N, S> operator-(Jet<N, S> a, double b) {
  a.v -= b;
  return a;
}
template <int N, bool S>
Jet<N, S> operator-(double b, Jet<N, S> a) {
  a *= -1.0;
  a.v += b;
  return a;
}
template <int N, bool S>
Jet<N, S> operator*(Jet<N, S> a, double s) {
  return a *= s;
}
template <int N, bool S>
Jet<N, S> operator*(double s, Jet<N, S> a) {
  return a *= s;
}
template <int N, bool S>
Jet<N, S> operator/(Jet<N, S> a, double s) {
  return a *= 1.0 / s;
}

// The Hessian updates below run column by column (vectorised fixed-size columns) instead of Eigen
// outer-product expressions, which compiled to out-of-line calls and temporaries (callgrind: half
// of the rod tangent's instructions). Entry (i, j) adds b_j a_i + a_j b_i, entry (j, i) the same
// two products in the same order, so a symmetric Hessian stays exactly symmetric.

// (ab)'' = a b'' + b a'' + a' b'ᵀ + b' a'ᵀ
template <int N, bool S>
Jet<N, S> operator*(const Jet<N, S>& a, const Jet<N, S>& b) {
  Jet<N, S> c;
  c.v = a.v * b.v;
  c.g = a.v * b.g + b.v * a.g;
  if constexpr (S) {
    for (int j = 0; j < N; ++j)
      c.h.col(j) = a.v * b.h.col(j) + b.v * a.h.col(j) + (b.g[j] * a.g + a.g[j] * b.g);
  }
  return c;
}

/// f(u) from f(u.v), f′ and f″: (f∘u)″ = f′ u″ + f″ u′u′ᵀ.
template <int N, bool S>
Jet<N, S> chain(const Jet<N, S>& u, double f, double f1, double f2) {
  Jet<N, S> c;
  c.v = f;
  c.g = f1 * u.g;
  if constexpr (S) {
    const typename Jet<N, S>::Grad fg = f2 * u.g;
    for (int j = 0; j < N; ++j) c.h.col(j) = f1 * u.h.col(j) + u.g[j] * fg;
  }
  return c;
}

template <int N, bool S>
Jet<N, S> inverse(const Jet<N, S>& u) {
  const double i = 1.0 / u.v;
  return chain(u, i, -i * i, 2.0 * i * i * i);
}
template <int N, bool S>
Jet<N, S> operator/(const Jet<N, S>& a, const Jet<N, S>& b) {
  return a * inverse(b);
}
template <int N, bool S>
Jet<N, S> operator/(double a, const Jet<N, S>& b) {
  return a * inverse(b);
}
template <int N, bool S>
Jet<N, S> sqrt(const Jet<N, S>& u) {
  const double s = std::sqrt(u.v);
  return chain(u, s, 0.5 / s, -0.25 / (s * u.v));
}
template <int N, bool S>
Jet<N, S> sin(const Jet<N, S>& u) {
  const double s = std::sin(u.v);
  return chain(u, s, std::cos(u.v), -s);
}
template <int N, bool S>
Jet<N, S> cos(const Jet<N, S>& u) {
  const double c = std::cos(u.v);
  return chain(u, c, -std::sin(u.v), -c);
}

/// atan2(y, x) with ∂/∂x = −y/ρ², ∂/∂y = x/ρ², ∂²/∂x² = 2xy/ρ⁴ = −∂²/∂y², ∂²/∂x∂y = (y²−x²)/ρ⁴.
template <int N, bool S>
Jet<N, S> atan2(const Jet<N, S>& y, const Jet<N, S>& x) {
  const double r2 = x.v * x.v + y.v * y.v, r4 = r2 * r2;
  const double fx = -y.v / r2, fy = x.v / r2;
  Jet<N, S> c;
  c.v = std::atan2(y.v, x.v);
  c.g = fx * x.g + fy * y.g;
  if constexpr (S) {
    const double fxx = 2.0 * x.v * y.v / r4, fxy = (y.v * y.v - x.v * x.v) / r4;
    for (int j = 0; j < N; ++j)
      for (int i = j; i < N; ++i)
        c.h(j, i) = c.h(i, j) = fx * x.h(i, j) + fy * y.h(i, j) +
                                fxx * (x.g[i] * x.g[j] - y.g[i] * y.g[j]) +
                                fxy * (x.g[i] * y.g[j] + y.g[i] * x.g[j]);
  }
  return c;
}

/// Value of a jet or of a plain double (templated kernels use both).
inline double value_of(double x) {
  return x;
}
template <int N, bool S>
double value_of(const Jet<N, S>& x) {
  return x.v;
}

}  // namespace ancf
