#include "core/transform.h"

#include <stdexcept>

namespace snell {

namespace {
using Mat = Transform::Mat;

Mat identity() {
    Mat m{};
    for (int i = 0; i < 4; ++i) m[i][i] = 1.0;
    return m;
}

Mat mul(const Mat& a, const Mat& b) {
    Mat r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) r[i][j] += a[i][k] * b[k][j];
    return r;
}

// Gauss-Jordan with partial pivoting.
Mat invert(const Mat& m) {
    double a[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? m[i][j] : (j - 4 == i ? 1.0 : 0.0);
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
        if (std::abs(a[piv][c]) < 1e-300) throw std::runtime_error("singular transform matrix");
        if (piv != c)
            for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[piv][j]);
        const double inv = 1.0 / a[c][c];
        for (int j = 0; j < 8; ++j) a[c][j] *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            const double f = a[r][c];
            if (f != 0)
                for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
        }
    }
    Mat r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r[i][j] = a[i][j + 4];
    return r;
}
}  // namespace

Transform::Transform() : m_m(identity()), m_inv(identity()) {}
Transform::Transform(const Mat& m) : m_m(m), m_inv(invert(m)) {}

Transform Transform::translate(const Vec3& t) {
    Mat m = identity(), inv = identity();
    for (int i = 0; i < 3; ++i) {
        m[i][3] = t[i];
        inv[i][3] = -t[i];
    }
    return {m, inv};
}

Transform Transform::scale(const Vec3& s) {
    Mat m = identity(), inv = identity();
    for (int i = 0; i < 3; ++i) {
        m[i][i] = s[i];
        inv[i][i] = 1.0 / s[i];
    }
    return {m, inv};
}

Transform Transform::rotate(const Vec3& axis, double angle_deg) {
    const Vec3 a = normalize(axis);
    const double th = angle_deg * kPi / 180.0, s = std::sin(th), c = std::cos(th);
    Mat m = identity();
    m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
    m[0][1] = a.x * a.y * (1 - c) - a.z * s;
    m[0][2] = a.x * a.z * (1 - c) + a.y * s;
    m[1][0] = a.x * a.y * (1 - c) + a.z * s;
    m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
    m[1][2] = a.y * a.z * (1 - c) - a.x * s;
    m[2][0] = a.x * a.z * (1 - c) - a.y * s;
    m[2][1] = a.y * a.z * (1 - c) + a.x * s;
    m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
    Mat inv = identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) inv[i][j] = m[j][i];
    return {m, inv};
}

Transform Transform::look_at(const Vec3& origin, const Vec3& target, const Vec3& up) {
    // Mitsuba convention: camera looks down +z, x to the left, y up.
    const Vec3 dir = normalize(target - origin);
    Vec3 left = cross(normalize(up), dir);
    if (length(left) < 1e-12) throw std::runtime_error("lookat: 'up' is parallel to the view direction");
    left = normalize(left);
    const Vec3 new_up = cross(dir, left);
    Mat m = identity();
    for (int i = 0; i < 3; ++i) {
        m[i][0] = left[i];
        m[i][1] = new_up[i];
        m[i][2] = dir[i];
        m[i][3] = origin[i];
    }
    return Transform(m);
}

Transform Transform::operator*(const Transform& o) const { return {mul(m_m, o.m_m), mul(o.m_inv, m_inv)}; }

bool Transform::is_identity() const { return m_m == identity(); }

Vec3 Transform::point(const Vec3& p) const {
    Vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = m_m[i][0] * p.x + m_m[i][1] * p.y + m_m[i][2] * p.z + m_m[i][3];
    const double w = m_m[3][0] * p.x + m_m[3][1] * p.y + m_m[3][2] * p.z + m_m[3][3];
    return w == 1.0 ? r : r / w;
}

Vec3 Transform::vector(const Vec3& v) const {
    Vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = m_m[i][0] * v.x + m_m[i][1] * v.y + m_m[i][2] * v.z;
    return r;
}

Vec3 Transform::normal(const Vec3& n) const {
    Vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = m_inv[0][i] * n.x + m_inv[1][i] * n.y + m_inv[2][i] * n.z;
    return r;
}

double Transform::det3() const {
    const Mat& m = m_m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

}  // namespace snell
