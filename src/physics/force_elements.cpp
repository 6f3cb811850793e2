#include "ancf/physics/force_elements.hpp"

namespace ancf {}  // namespace ancf
