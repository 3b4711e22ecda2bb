#pragma once
// Jacobians of an admissible chain (paper Sec. 3.3): the generalised geometry term
// |do_b/dx_c| (how the direction leaving x_b turns when the light point x_c moves while all
// half vectors stay fixed) and |dH/dX| (Eq. 8). Both in double precision as the paper asks.
#include <vector>

#include "manifold/constraints.h"
#include "manifold/manifold_vertex.h"

namespace snell {

struct ChainJacobians {
    double dH_dX = 0;      ///< |dH/dX|: half vectors (projected solid angle) per vertex area (Eq. 8)
    double do_b_dx_c = 0;  ///< |do_b/dx_c|: solid angle at x_b per unit area of x_c (transfer matrix)
    bool valid = false;
};

/// Computes both Jacobians at the (converged) chain. x_c's basis spans the light surface's
/// tangent plane (orthonormal, so the result is per unit area of the light).
ChainJacobians chain_jacobians(const Vec3& x_b, const std::vector<ManifoldVertex>& chain, const TangentBasis& x_c);

}  // namespace snell
