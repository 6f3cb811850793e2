// Private to the physics layer: the Kirchhoff rod kernel RodKernel::local_chain
// (kirchhoff_rod_local_chain.cpp), called by evaluate_rod_element.
#pragma once

#include "ancf/physics/kirchhoff_rod_element.hpp"
#include "kirchhoff_rod_torsion.hpp"

namespace ancf::rod_detail {

// Adds the strains taken at the Gauss points (strain_at_gauss_points) to out (zeroed by the
// caller); with `torsion` given, fills it with K₁ and its derivatives at each point.
void evaluate_with_local_chain(const RodSection& section, const RodElementReference& ref,
                               const RodElementHistory& history, const Vec15& e, const Vec15& e_dot,
                               const RodEvalRequest& request, RodElementResult& out,
                               TorsionPoints* torsion);

}  // namespace ancf::rod_detail
