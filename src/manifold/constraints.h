#pragma once
// Half-vector constraints of a specular/rough chain and their derivative blocks (paper Eq. 4,
// after Jakob 2013 and Kaplanyan et al. 2014): for vertex i the constraint is the generalised
// half vector h_i projected onto the vertex's constraint frame, minus the target:
//     c_i = (h_i . s_i, h_i . t_i) - h_target_i,
// and A_i = dc_i/dx_{i-1}, B_i = dc_i/dx_i, C_i = dc_i/dx_{i+1}, each a 2x2 block with respect
// to the orthonormal tangent coordinates of the vertex that moves (so determinants are in
// area measure on the positions and projected solid angle on the half vectors).
#include "manifold/manifold_vertex.h"

namespace snell {

/// Tangent basis of a neighbouring vertex (endpoints x_b and x_c included).
struct TangentBasis {
    Vec3 p;
    Vec3 dp_ds, dp_dt;
};

struct ConstraintBlocks {
    Vec2 value;  ///< c_i
    Mat2 A, B, C;
    bool valid = true;  ///< false for degenerate configurations (coincident vertices)
};

/// Constraint value and derivative blocks of vertex `v` between neighbours `prev` and `next`.
ConstraintBlocks half_vector_constraint(const TangentBasis& prev, const ManifoldVertex& v, const TangentBasis& next);

/// Constraint value only (cheaper; used to measure the walk's error after each step).
Vec2 half_vector_constraint_value(const Vec3& prev, const ManifoldVertex& v, const Vec3& next);

/// Tangential components of a unit half vector h in v's constraint frame.
inline Vec2 tangential(const ManifoldVertex& v, const Vec3& h) { return {dot(h, v.s), dot(h, v.t)}; }

}  // namespace snell
