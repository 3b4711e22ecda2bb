#include "manifold/block_tridiagonal.h"

#include <cmath>

namespace snell {

bool BlockLU::factor(const BlockTridiagonal& m) {
    m_m = &m;
    const size_t k = m.size();
    m_lambda_inv.resize(k);
    double det = 1.0;
    Mat2 lambda;
    for (size_t i = 0; i < k; ++i) {
        lambda = i == 0 ? m.B[0] : m.B[i] - m.A[i] * m_lambda_inv[i - 1] * m.C[i - 1];
        const double d = lambda.det();
        // Singular relative to the pivot's own scale (dimensionless test, scene-scale free).
        if (!(std::abs(d) > 1e-14 * sqr(lambda.max_abs())) || !std::isfinite(d)) return false;
        det *= std::abs(d);
        m_lambda_inv[i] = lambda.inverse();
    }
    m_abs_det = det;
    return true;
}

std::vector<Vec2> BlockLU::solve(const std::vector<Vec2>& rhs) const {
    const BlockTridiagonal& m = *m_m;
    const size_t k = m.size();
    // Forward sweep: y_i = rhs_i - A_i Lambda_{i-1}^-1 y_{i-1}.
    std::vector<Vec2> y(k);
    for (size_t i = 0; i < k; ++i) y[i] = i == 0 ? rhs[0] : rhs[i] - m.A[i] * (m_lambda_inv[i - 1] * y[i - 1]);
    // Back substitution: x_i = Lambda_i^-1 (y_i - C_i x_{i+1}).
    std::vector<Vec2> x(k);
    for (size_t j = k; j-- > 0;) x[j] = m_lambda_inv[j] * (j + 1 < k ? y[j] - m.C[j] * x[j + 1] : y[j]);
    return x;
}

std::vector<Mat2> BlockLU::solve(const std::vector<Mat2>& rhs) const {
    const size_t k = rhs.size();
    std::vector<Vec2> c0(k), c1(k);
    for (size_t i = 0; i < k; ++i) {
        c0[i] = {rhs[i].a, rhs[i].c};
        c1[i] = {rhs[i].b, rhs[i].d};
    }
    const std::vector<Vec2> x0 = solve(c0), x1 = solve(c1);
    std::vector<Mat2> out(k);
    for (size_t i = 0; i < k; ++i) out[i] = Mat2::from_columns(x0[i], x1[i]);
    return out;
}

bool solve_matrix_h_to_x(const BlockTridiagonal& m, const std::vector<Vec2>& c, std::vector<Vec2>* dx,
                         double* abs_det) {
    BlockLU lu;
    if (!lu.factor(m)) return false;
    std::vector<Vec2> rhs(c.size());
    for (size_t i = 0; i < c.size(); ++i) rhs[i] = c[i] * -1.0;
    *dx = lu.solve(rhs);
    if (abs_det) *abs_det = lu.abs_det();
    return true;
}

}  // namespace snell
