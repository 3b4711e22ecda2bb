#pragma once
#include <array>

#include "core/vector.h"

namespace snell {

/// 4x4 affine/projective transform with its inverse kept alongside (double precision).
class Transform {
public:
    using Mat = std::array<std::array<double, 4>, 4>;

    Transform();  ///< identity
    explicit Transform(const Mat& m);
    Transform(const Mat& m, const Mat& inv) : m_m(m), m_inv(inv) {}

    static Transform translate(const Vec3& t);
    static Transform scale(const Vec3& s);
    /// Rotation by `angle_deg` degrees about `axis` (right-handed, like Mitsuba).
    static Transform rotate(const Vec3& axis, double angle_deg);
    /// Camera-to-world transform looking from `origin` at `target` (Mitsuba's lookat).
    static Transform look_at(const Vec3& origin, const Vec3& target, const Vec3& up);

    Transform operator*(const Transform& o) const;  ///< this after o
    Transform inverse() const { return Transform(m_inv, m_m); }
    bool is_identity() const;

    Vec3 point(const Vec3& p) const;
    Vec3 vector(const Vec3& v) const;
    /// Normals transform with the inverse transpose.
    Vec3 normal(const Vec3& n) const;

    const Mat& matrix() const { return m_m; }
    const Mat& inverse_matrix() const { return m_inv; }
    /// Determinant of the upper 3x3 block; < 0 means handedness flips.
    double det3() const;

private:
    Mat m_m, m_inv;
};

}  // namespace snell
