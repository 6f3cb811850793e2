#include "ancf/scenes/elastic_catenary.hpp"

#include <cmath>
#include <stdexcept>

#include "ancf/system/model_builder.hpp"
#include "ancf/system/static_model_problem.hpp"

namespace ancf {

namespace {

// Horizontal end coordinate x(L₀) of Irvine's elastic catenary for a trial H (REFERENCES §3).
double span_for_horizontal_tension(const ElasticCatenarySpec& c, double h) {
  const double w = c.mass_per_length * c.gravity, v = 0.5 * w * c.length;
  return h * c.length / c.axial_stiffness + 2.0 * h / w * std::asinh(v / h);
}

}  // namespace

CatenaryValues irvine_catenary(const ElasticCatenarySpec& c) {
  if (!(c.span > 0.0 && c.span < c.length))
    throw std::invalid_argument("catenary: need 0 < D < L0");
  const double w = c.mass_per_length * c.gravity, v = 0.5 * w * c.length;
  // x(L₀) grows monotonically with H from 0; bracket the root, then bisect to round-off (a few
  // hundred cheap evaluations; no derivative needed).
  double lo = 0.0, hi = w * c.length;
  while (span_for_horizontal_tension(c, hi) < c.span) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-16 * hi; ++i) {
    const double h = 0.5 * (lo + hi);
    (span_for_horizontal_tension(c, h) < c.span ? lo : hi) = h;
  }
  CatenaryValues out;
  const double h = 0.5 * (lo + hi), s = 0.5 * c.length;
  out.horizontal_tension = h;
  // z(s) at s = L₀/2, where V − w s = 0.
  out.sag = w * s / c.axial_stiffness * (v / w - 0.5 * s) +
            h / w * (std::sqrt(1.0 + (v / h) * (v / h)) - 1.0);
  out.support_tension = std::hypot(h, v);
  return out;
}

double catenary_parameter(double span, double length) {
  double lo = 1e-3, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double a = 0.5 * (lo + hi);
    (2 * a * std::sinh(span / (2 * a)) > length ? lo : hi) = a;
  }
  return 0.5 * (lo + hi);
}

CableGeometry catenary_guess(const ElasticCatenarySpec& c, Index elements, double stretch) {
  const double a = catenary_parameter(c.span, c.length * stretch);
  CableGeometry g;
  for (Index k = 0; k <= elements; ++k) {
    const double s = c.length * stretch * static_cast<double>(k) / static_cast<double>(elements);
    const double xc = a * std::asinh(s / a - std::sinh(c.span / (2 * a)));  // from the vertex
    NodeCoordinates n;
    n << xc + 0.5 * c.span, 0.0, a * (std::cosh(xc / a) - std::cosh(c.span / (2 * a))),
        stretch / std::cosh(xc / a), 0.0, stretch * std::tanh(xc / a);
    g.nodes.push_back(n);
  }
  g.element_lengths.assign(static_cast<std::size_t>(elements),
                           c.length / static_cast<double>(elements));
  return g;
}

Model elastic_catenary_model(const ElasticCatenarySpec& c, Index elements) {
  ModelBuilder b;
  CableSection s;
  s.strain = StrainMeasure::elastic_line;
  s.axial_stiffness = c.axial_stiffness;
  s.mass_per_length = c.mass_per_length;
  const Index cable =
      b.add_cable("catenary", straight_cable(Vec3::Zero(), c.length * Vec3::UnitX(), elements), s);
  b.set_initial_configuration(cable, catenary_guess(c, elements, 1.001));
  b.set_gravity({0.0, 0.0, -c.gravity});
  b.pin("left support", {cable, 0}, Vec3::Zero());
  b.pin("right support", {cable, -1}, c.span * Vec3::UnitX());
  return b.finalize();
}

CatenarySolution solve_elastic_catenary(const ElasticCatenarySpec& c, Index elements) {
  if (elements % 2 != 0) throw std::invalid_argument("catenary: mid-span node needs even elements");
  const Model model = elastic_catenary_model(c, elements);
  StaticModelProblem problem(model);
  StaticSolver solver(problem);
  VecX y = problem.initial_guess();
  CatenarySolution out;
  out.stats = solver.solve(y);
  out.sag = -y[model.node_coordinate(0, elements / 2) + 2];
  // The pin's multiplier is minus the support reaction on the cable: |λ| = T at the support.
  out.tension_left = y.segment<3>(model.coordinate_count()).norm();
  out.tension_right = y.segment<3>(model.coordinate_count() + 3).norm();
  return out;
}

}  // namespace ancf
