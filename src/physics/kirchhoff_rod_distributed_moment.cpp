// Distributed moment on a rod element (kirchhoff_rod_distributed_moment.hpp): the triad of the
// strains (point_strains) in jets over the 15 element coordinates gives ∂g_k/∂e and ∂²g_k/∂e².
#include "ancf/physics/kirchhoff_rod_distributed_moment.hpp"

#include <Eigen/Geometry>

#include "ancf/physics/jet.hpp"
#include "kirchhoff_rod_strains.hpp"

namespace ancf {
namespace {
using namespace rod_detail;

template <class J>
void add_moment(const RodElementReference& ref, const RodElementHistory& history, const Vec15& e,
                const Vec3& m, RodDistributedMomentLoad& out) {
  const auto x = to_array<J>(e);
  const ElementFrame<J> f = element_frame(history, x);
  Mat3 skew_m;  // [m]×
  skew_m << 0.0, -m.z(), m.y(), m.z(), 0.0, -m.x(), -m.y(), m.x(), 0.0;
  for (int p = 0; p < kRodGaussPoints; ++p) {
    PointTriad<J> t;
    point_strains(point_data(ref, p), f, x, &t);
    const double half_w = 0.5 * ref.weight[p];
    for (const V3<J>* g : {&t.g1, &t.g2, &t.g3}) {
      const Vec3 value(g->x.v, g->y.v, g->z.v);
      const Vec3 a = m.cross(value);    // m × g_k
      Eigen::Matrix<double, 3, 15> dg;  // ∂g_k/∂e
      dg.row(0) = g->x.g.transpose();
      dg.row(1) = g->y.g.transpose();
      dg.row(2) = g->z.g.transpose();
      out.force.noalias() += half_w * dg.transpose() * a;
      if constexpr (std::is_same_v<J, Jet<15, true>>) {
        out.jacobian.noalias() += half_w * dg.transpose() * skew_m * dg;
        out.jacobian.noalias() += (half_w * a.x()) * g->x.h;
        out.jacobian.noalias() += (half_w * a.y()) * g->y.h;
        out.jacobian.noalias() += (half_w * a.z()) * g->z.h;
      }
    }
  }
}

}  // namespace

void rod_distributed_moment(const RodElementReference& ref, const RodElementHistory& history,
                            const Vec15& e, const Vec3& moment_per_length, bool jacobian,
                            RodDistributedMomentLoad& out) {
  out.force.setZero();
  if (jacobian) {
    out.jacobian.setZero();
    add_moment<Jet<15, true>>(ref, history, e, moment_per_length, out);
  } else {
    add_moment<Jet<15, false>>(ref, history, e, moment_per_length, out);
  }
}

}  // namespace ancf
