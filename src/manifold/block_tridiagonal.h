#pragma once
// The block-tridiagonal constraint derivative matrix of a chain and its LU solve, the routine
// `solve_matrix_h_to_x` of Kaplanyan et al. 2014 (supplement, Fig. 2), as used by the paper in
// Sec. 3.3-3.4. The determinant |dH/dX| falls out of the forward sweep as the product of the
// pivot determinants (paper Eq. 8, after Molinari 2008).
#include <vector>

#include "manifold/mat2.h"

namespace snell {

/// Row i holds A_i (left of the diagonal, unused for i = 0), B_i (diagonal) and C_i (right,
/// unused for the last row).
struct BlockTridiagonal {
    std::vector<Mat2> A, B, C;
    size_t size() const { return B.size(); }
    void resize(size_t k) {
        A.assign(k, Mat2());
        B.assign(k, Mat2());
        C.assign(k, Mat2());
    }
};

/// LU factorisation: pivots Lambda_i = B_i - A_i Lambda_{i-1}^-1 C_{i-1}.
class BlockLU {
public:
    /// Factorises m. Returns false if a pivot is singular relative to the size of its entries.
    bool factor(const BlockTridiagonal& m);
    /// |dH/dX| = prod_i |det Lambda_i| (Eq. 8), in double precision.
    double abs_det() const { return m_abs_det; }
    /// Solves M x = rhs (one 2-vector per block row).
    std::vector<Vec2> solve(const std::vector<Vec2>& rhs) const;
    /// Solves M X = R for a 2-column right-hand side given per block row as a 2x2 matrix.
    std::vector<Mat2> solve(const std::vector<Mat2>& rhs) const;
    /// The same solves in place: v holds the right-hand side and receives the solution. Both
    /// sweeps read only the row they write and its already-swept neighbour, so no second array is
    /// needed, and a walk's iterations reuse one buffer (no allocation per Newton step).
    void solve_in_place(std::vector<Vec2>& v) const;
    void solve_in_place(std::vector<Mat2>& v) const;

private:
    template <class T>
    void sweep(std::vector<T>& v) const;

    const BlockTridiagonal* m_m = nullptr;
    std::vector<Mat2> m_lambda_inv;
    double m_abs_det = 0;
};

/// Newton step of the manifold walk: the tangent offsets dX with M dX = -c (h_to_x).
/// Returns false when the matrix is singular. `abs_det` receives |dH/dX| (Eq. 8) if non-null.
/// `lu`, if given, is the factorisation's storage, kept by a caller that solves again and again.
bool solve_matrix_h_to_x(const BlockTridiagonal& m, const std::vector<Vec2>& c, std::vector<Vec2>* dx,
                         double* abs_det = nullptr, BlockLU* lu = nullptr);

}  // namespace snell
