#include "ancf/physics/driven_frame.hpp"

#include <Eigen/Geometry>

namespace ancf {

FrameKinematics DrivenFrame::at(double t) const {
  FrameKinematics k;
  k.r = origin;
  const AngleState s = law.at(t);
  const Vec3 n = axis.normalized();
  k.a = Eigen::AngleAxisd(s.angle, n).toRotationMatrix() * initial_rotation;
  Mat3 nx;
  nx << 0, -n.z(), n.y(), n.z(), 0, -n.x(), -n.y(), n.x(), 0;
  k.a_dot = s.rate * nx * k.a;
  k.a_ddot = (s.acceleration * nx + s.rate * s.rate * nx * nx) * k.a;
  return k;
}

}  // namespace ancf
