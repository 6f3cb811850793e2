#include "ancf/physics/joints.hpp"

namespace ancf {}  // namespace ancf
