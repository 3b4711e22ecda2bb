#pragma once
// 2x2 matrices and 2-vectors in double precision: the blocks A_i, B_i, C_i of the constraint
// derivative matrix (paper Eq. 4) and the pivots Lambda_i of its LU decomposition (Eq. 8).
#include <cmath>

#include "core/vector.h"

namespace snell {

struct Mat2 {
    double a = 0, b = 0, c = 0, d = 0;  // [[a, b], [c, d]]

    static Mat2 identity() { return {1, 0, 0, 1}; }
    /// Matrix with the given columns.
    static Mat2 from_columns(const Vec2& c0, const Vec2& c1) { return {c0.x, c1.x, c0.y, c1.y}; }

    double det() const { return a * d - b * c; }
    Mat2 inverse() const {
        const double id = 1.0 / det();
        return {d * id, -b * id, -c * id, a * id};
    }
    Mat2 operator*(const Mat2& o) const {
        return {a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d};
    }
    Vec2 operator*(const Vec2& v) const { return {a * v.x + b * v.y, c * v.x + d * v.y}; }
    Mat2 operator-(const Mat2& o) const { return {a - o.a, b - o.b, c - o.c, d - o.d}; }
    Mat2 operator+(const Mat2& o) const { return {a + o.a, b + o.b, c + o.c, d + o.d}; }
    Mat2 operator*(double s) const { return {a * s, b * s, c * s, d * s}; }
    /// Largest absolute entry (for relative singularity tests).
    double max_abs() const { return std::max(std::max(std::abs(a), std::abs(b)), std::max(std::abs(c), std::abs(d))); }
};

}  // namespace snell
