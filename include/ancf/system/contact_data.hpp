// Contact data of a Model (DESIGN §5): named shapes with their owner, and the candidate pairs the
// scene declared. The coupling blocks of the pairs that are near live in a ContactPattern.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "ancf/core/types.hpp"
#include "ancf/physics/contact_law.hpp"
#include "ancf/physics/contact_shapes.hpp"
#include "ancf/system/element_range.hpp"

namespace ancf {

/// A shape and what carries it. Shape data are in the owner's frame (global for ground).
struct ContactShapeData {
  enum class Owner { ground, frame, body };
  std::string name;
  ContactShape shape;
  Owner owner = Owner::ground;
  Index owner_index = -1;      ///< driven-frame or body index (not used for ground)
  Index body_coordinate = -1;  ///< first coordinate of the owning body (Owner::body)
};

/// Slots of a 12×12 coupling block, column-major (slots[12·col + row]).
using BlockSlots = std::array<Index, 144>;

/// Cable `cable` against shape `shape`: `samples` points per element at ξ = (k + ½)/samples, each
/// weighing l/samples, on elements [first, first + count). For a body-owned shape, element
/// first + j couples to the body (ContactCoupling::shape_block).
struct CableShapeContactData {
  std::string name;
  Index cable = 0, shape = 0;
  Index first = 0, count = 0;  ///< candidate elements (resolved range)
  ContactLaw law;
  int samples = 1;
};

/// Samples of cable a (elements [first_a, first_a + count_a)) against the closest point of cable b
/// (elements [first_b, first_b + count_b)). Element pair (first_a + i, first_b + j) couples
/// through ContactCoupling::cable_block[pair][i·count_b + j].
struct CableCableContactData {
  std::string name;
  Index cable_a = 0, cable_b = 0;
  Index first_a = 0, count_a = 0, first_b = 0, count_b = 0;  ///< candidate elements
  ContactLaw law;
  int samples = 1;
};

}  // namespace ancf
