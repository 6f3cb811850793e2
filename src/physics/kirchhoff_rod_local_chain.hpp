// Private to the physics layer: the Kirchhoff rod kernel RodKernel::local_chain
// (kirchhoff_rod_local_chain.cpp), called by evaluate_rod_element.
#pragma once

#include "ancf/physics/kirchhoff_rod_element.hpp"

namespace ancf::rod_detail {

// Adds to out (zeroed by the caller).
void evaluate_with_local_chain(const RodSection& section, const RodElementReference& ref,
                               const RodElementHistory& history, const Vec15& e, const Vec15& e_dot,
                               const RodEvalRequest& request, RodElementResult& out);

}  // namespace ancf::rod_detail
