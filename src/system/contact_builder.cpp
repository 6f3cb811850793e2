// ModelBuilder: contact shapes and candidate pairs (DESIGN §5). Their coupling blocks are not in
// the model's pattern: a ContactPattern holds those of the pairs that are near.
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "ancf/core/error.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf {
namespace {

void require_radius(const std::string& pair, const std::string& cable, double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw ModelError("contact '" + pair + "': cable '" + cable +
                     "' needs a cross-section radius > 0 m, got " + std::to_string(radius));
}

void require_samples(const std::string& pair, int samples) {
  if (samples < 1)
    throw ModelError("contact '" + pair + "': samples per element must be >= 1, got " +
                     std::to_string(samples));
}

// Resolve a range against a cable of n elements: [first, first + count) within [0, n), count ≥ 1.
std::pair<Index, Index> resolve_range(const std::string& pair, const std::string& cable,
                                      ElementRange r, Index n) {
  return resolve_element_range("contact '" + pair + "'", cable, r, n);
}

}  // namespace

Index ModelBuilder::add_shape(ContactShapeData shape) {
  if (shape.name.empty()) throw ModelError("contact shape: a name is required");
  for (const auto& s : shapes_)
    if (s.name == shape.name)
      throw ModelError("contact shape name '" + shape.name + "' is used twice");
  validate_shape(shape.shape, "contact shape '" + shape.name + "'");
  shapes_.push_back(std::move(shape));
  return static_cast<Index>(shapes_.size()) - 1;
}

Index ModelBuilder::add_ground_shape(std::string name, const ContactShape& shape) {
  return add_shape({std::move(name), shape, ContactShapeData::Owner::ground, -1, -1});
}

Index ModelBuilder::add_frame_shape(std::string name, int frame, const ContactShape& shape) {
  if (frame < 0 || frame >= static_cast<int>(frames_.size()))
    throw ModelError("contact shape '" + name + "': no driven frame with index " +
                     std::to_string(frame));
  return add_shape({std::move(name), shape, ContactShapeData::Owner::frame, frame, -1});
}

Index ModelBuilder::add_body_shape(std::string name, Index body, const ContactShape& shape) {
  body_at(body, "add_body_shape");
  return add_shape({std::move(name), shape, ContactShapeData::Owner::body, body, -1});
}

void ModelBuilder::add_cable_shape_contact(std::string name, Index cable, Index shape,
                                           const ContactLaw& law, int samples_per_element,
                                           ElementRange range) {
  require_new_name(name, "contact");
  const PendingCable& c = cable_at(cable, "add_cable_shape_contact");
  if (shape < 0 || shape >= static_cast<Index>(shapes_.size()))
    throw ModelError("contact '" + name + "': no contact shape with index " +
                     std::to_string(shape));
  require_radius(name, c.name, c.section.radius);
  require_samples(name, samples_per_element);
  law.validate("contact '" + name + "'");
  CableShapeContactData d;
  std::tie(d.first, d.count) = resolve_range(name, c.name, range, c.reference.element_count());
  d.name = std::move(name);
  d.cable = cable;
  d.shape = shape;
  d.law = law;
  d.samples = samples_per_element;
  cable_shape_contacts_.push_back(std::move(d));
}

void ModelBuilder::add_cable_cable_contact(std::string name, Index cable_a, Index cable_b,
                                           const ContactLaw& law, int samples_per_element,
                                           ElementRange range_a, ElementRange range_b) {
  require_new_name(name, "contact");
  const PendingCable& a = cable_at(cable_a, "add_cable_cable_contact");
  const PendingCable& b = cable_at(cable_b, "add_cable_cable_contact");
  if (cable_a == cable_b)
    throw ModelError("contact '" + name + "': cable '" + a.name +
                     "' against itself (self-contact is not supported)");
  require_radius(name, a.name, a.section.radius);
  require_radius(name, b.name, b.section.radius);
  require_samples(name, samples_per_element);
  law.validate("contact '" + name + "'");
  CableCableContactData d;
  std::tie(d.first_a, d.count_a) =
      resolve_range(name, a.name, range_a, a.reference.element_count());
  std::tie(d.first_b, d.count_b) =
      resolve_range(name, b.name, range_b, b.reference.element_count());
  d.name = std::move(name);
  d.cable_a = cable_a;
  d.cable_b = cable_b;
  d.law = law;
  d.samples = samples_per_element;
  cable_cable_contacts_.push_back(std::move(d));
}

void ModelBuilder::finalize_contacts(const Offsets& o, Model& m) const {
  m.shapes_ = shapes_;
  for (ContactShapeData& s : m.shapes_)
    if (s.owner == ContactShapeData::Owner::body) s.body_coordinate = o.body(s.owner_index);
  m.cable_shape_contacts_ = cable_shape_contacts_;
  m.cable_cable_contacts_ = cable_cable_contacts_;
}

}  // namespace ancf
