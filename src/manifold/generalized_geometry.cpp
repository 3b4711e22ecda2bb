#include "manifold/generalized_geometry.h"

#include <cmath>

#include "manifold/block_tridiagonal.h"
#include "manifold/manifold_walk.h"

namespace snell {

namespace {
// One thread's storage (as the walk's in manifold_walk.cpp): one evaluation per solution.
struct JacobianWorkspace {
    BlockTridiagonal m;
    BlockLU lu;
    std::vector<Vec2> c;
    std::vector<Mat2> rhs;
};
thread_local JacobianWorkspace t_jacobians;
}  // namespace

ChainJacobians chain_jacobians(const Vec3& x_b, const std::vector<ManifoldVertex>& chain, const TangentBasis& x_c) {
    ChainJacobians out;
    const size_t k = chain.size();
    if (k == 0) return out;
    BlockTridiagonal& m = t_jacobians.m;
    if (!build_constraints(x_b, chain, x_c, &m, &t_jacobians.c)) return out;
    BlockLU& lu = t_jacobians.lu;
    if (!lu.factor(m)) return out;
    out.dH_dX = lu.abs_det();  // Eq. 8: product of the pivots' determinants

    // Transfer: with H fixed, M dX + D dx_c = 0 where D is zero except its last block row,
    // C_{k} = dc_k/dx_c. So dX/dx_c = -M^-1 D, and only the first block dx_1/dx_c is needed.
    std::vector<Mat2>& dX = t_jacobians.rhs;
    dX.assign(k, Mat2());
    dX[k - 1] = m.C[k - 1] * -1.0;
    lu.solve_in_place(dX);

    // o_b = (x_1 - x_b) / |x_1 - x_b|; its differential in an orthonormal basis (e1, e2) of
    // the plane perpendicular to o_b: (I - o o^T) dx_1 / l.
    const Vec3 d = chain[0].p - x_b;
    const double l = length(d);
    const Vec3 o = d / l;
    const Frame f = Frame::from_normal(o);
    const auto col = [&](const Vec3& e) { return Vec2(dot(f.s, e), dot(f.t, e)) / l; };
    const Mat2 do_dx1 = Mat2::from_columns(col(chain[0].dp_ds), col(chain[0].dp_dt));
    out.do_b_dx_c = std::abs((do_dx1 * dX[0]).det());
    out.valid = std::isfinite(out.do_b_dx_c) && std::isfinite(out.dH_dX);
    return out;
}

}  // namespace snell
