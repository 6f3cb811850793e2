#include "ancf/system/cable_geometry.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

Vec12 CableGeometry::element_coordinates(Index j) const {
  Vec12 e;
  e << nodes[j], nodes[j + 1];
  return e;
}

namespace {
void require_elements(Index n, const char* what) {
  if (n < 1)
    throw ModelError(std::string(what) + ": element count must be >= 1, got " + std::to_string(n));
}

/// Node fractions along the arc length: given ones, or k/n (equal elements, bit for bit as before
/// graded meshes existed).
class Fractions {
 public:
  Fractions(Index n, std::span<const double> given, const char* what) : n_(n), given_(given) {
    require_elements(n, what);
    if (given.empty()) return;
    if (given.size() != static_cast<std::size_t>(n) + 1 || given.front() != 0.0 ||
        given.back() != 1.0)
      throw ModelError(std::string(what) + ": expected n + 1 node fractions from 0 to 1");
    for (Index k = 0; k < n; ++k)
      if (!(given[k + 1] > given[k]))
        throw ModelError(std::string(what) + ": node fractions must increase");
  }
  [[nodiscard]] double at(Index k) const {
    return given_.empty() ? static_cast<double>(k) / n_ : given_[k];
  }
  void set_lengths(CableGeometry& g, double length) const {
    if (given_.empty()) {
      g.element_lengths.assign(n_, length / n_);
      return;
    }
    g.element_lengths.resize(n_);
    for (Index k = 0; k < n_; ++k) g.element_lengths[k] = length * (given_[k + 1] - given_[k]);
  }

 private:
  Index n_;
  std::span<const double> given_;
};
}  // namespace

CableGeometry straight_cable(const Vec3& start, const Vec3& end, Index elements,
                             std::span<const double> fractions) {
  const Fractions f(elements, fractions, "straight_cable");
  const double length = (end - start).norm();
  if (!(length > 0.0)) throw ModelError("straight_cable: start and end coincide (zero length)");
  const Vec3 t = (end - start) / length;
  CableGeometry g;
  for (Index k = 0; k <= elements; ++k) {
    NodeCoordinates n;
    n << start + f.at(k) * (end - start), t;
    g.nodes.push_back(n);
  }
  f.set_lengths(g, length);
  return g;
}

CableGeometry arc_cable(const Vec3& centre, const Vec3& u, const Vec3& w, double radius,
                        double angle, Index elements, std::span<const double> fractions) {
  const Fractions f(elements, fractions, "arc_cable");
  if (!(radius > 0.0) || !(std::abs(angle) > 0.0))
    throw ModelError("arc_cable: radius and angle must be non-zero");
  const Vec3 e1 = u.normalized(), e2 = (w - w.dot(e1) * e1).normalized();
  CableGeometry g;
  for (Index k = 0; k <= elements; ++k) {
    const double phi = angle * f.at(k);
    NodeCoordinates n;
    n << centre + radius * (std::cos(phi) * e1 + std::sin(phi) * e2),
        -std::sin(phi) * e1 + std::cos(phi) * e2;
    g.nodes.push_back(n);
  }
  f.set_lengths(g, radius * std::abs(angle));
  return g;
}

CableGeometry helix_cable(const Vec3& base, const Vec3& axis, const Vec3& u, double radius,
                          double phi0, double twist, double rise, Index elements,
                          std::span<const double> fractions) {
  const Fractions f(elements, fractions, "helix_cable");
  const Vec3 ez = axis.normalized();
  const Vec3 ex = (u - u.dot(ez) * ez).normalized();
  const Vec3 ey = ez.cross(ex);
  const double length = std::hypot(radius * twist, rise);
  if (!(radius > 0.0) || !(length > 0.0)) throw ModelError("helix_cable: zero radius or length");
  CableGeometry g;
  for (Index k = 0; k <= elements; ++k) {
    const double s = f.at(k);
    const double phi = phi0 + twist * s;
    NodeCoordinates n;
    const Vec3 r = base + radius * (std::cos(phi) * ex + std::sin(phi) * ey) + rise * s * ez;
    const Vec3 dr = radius * twist * (-std::sin(phi) * ex + std::cos(phi) * ey) + rise * ez;
    n << r, dr / length;
    g.nodes.push_back(n);
  }
  f.set_lengths(g, length);
  return g;
}

namespace {
Mat3 frame_from_normal(const Vec3& t, const Vec3& normal, Index node) {
  const Vec3 g = t.normalized();
  const Vec3 d2 = normal - normal.dot(g) * g;
  if (!(d2.norm() > 1e-8 * normal.norm()))
    throw ModelError("rod reference frame: the normal is parallel to the tangent at node " +
                     std::to_string(node));
  Mat3 f;
  f.col(0) = g;
  f.col(1) = d2.normalized();
  f.col(2) = g.cross(f.col(1));
  return f;
}
}  // namespace

std::vector<Mat3> rod_frames_with_normal(const CableGeometry& g, const Vec3& normal) {
  std::vector<Mat3> out;
  for (Index k = 0; k < g.node_count(); ++k)
    out.push_back(frame_from_normal(g.nodes[k].tail<3>(), normal, k));
  return out;
}

std::vector<Mat3> rod_frames_toward_axis(const CableGeometry& g, const Vec3& point,
                                         const Vec3& axis) {
  const Vec3 a = axis.normalized();
  std::vector<Mat3> out;
  for (Index k = 0; k < g.node_count(); ++k) {
    const Vec3 r = g.nodes[k].head<3>() - point;
    out.push_back(frame_from_normal(g.nodes[k].tail<3>(), -(r - r.dot(a) * a), k));
  }
  return out;
}

}  // namespace ancf
