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

template <class T>
void BlockLU::sweep(std::vector<T>& v) const {
    const BlockTridiagonal& m = *m_m;
    const size_t k = m.size();
    // Forward sweep: y_i = rhs_i - A_i Lambda_{i-1}^-1 y_{i-1}.
    for (size_t i = 1; i < k; ++i) v[i] = v[i] - m.A[i] * (m_lambda_inv[i - 1] * v[i - 1]);
    // Back substitution: x_i = Lambda_i^-1 (y_i - C_i x_{i+1}).
    for (size_t j = k; j-- > 0;) v[j] = m_lambda_inv[j] * (j + 1 < k ? v[j] - m.C[j] * v[j + 1] : v[j]);
}

void BlockLU::solve_in_place(std::vector<Vec2>& v) const { sweep(v); }

// A 2-column right-hand side sweeps as two 2-vectors at once: Mat2 products act column by column.
void BlockLU::solve_in_place(std::vector<Mat2>& v) const { sweep(v); }

std::vector<Vec2> BlockLU::solve(const std::vector<Vec2>& rhs) const {
    std::vector<Vec2> x = rhs;
    solve_in_place(x);
    return x;
}

std::vector<Mat2> BlockLU::solve(const std::vector<Mat2>& rhs) const {
    std::vector<Mat2> x = rhs;
    solve_in_place(x);
    return x;
}

bool solve_matrix_h_to_x(const BlockTridiagonal& m, const std::vector<Vec2>& c, std::vector<Vec2>* dx, double* abs_det,
                         BlockLU* lu) {
    BlockLU local;
    BlockLU& f = lu ? *lu : local;
    if (!f.factor(m)) return false;
    dx->resize(c.size());
    for (size_t i = 0; i < c.size(); ++i) (*dx)[i] = c[i] * -1.0;
    f.solve_in_place(*dx);
    if (abs_det) *abs_det = f.abs_det();
    return true;
}

}  // namespace snell
