#pragma once
// Small vector types. The renderer computes in double throughout (the paper asks for
// double precision in determinants and the generalized geometry term, Sec. 3.3; scalar
// double costs about as much as float on x86). Only mesh storage handed to Embree is float.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace snell {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInvPi = 1.0 / kPi;
constexpr double kInv2Pi = 1.0 / (2.0 * kPi);
constexpr double kInv4Pi = 1.0 / (4.0 * kPi);
constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Vec2 {
    double x = 0, y = 0;
    constexpr Vec2() = default;
    constexpr Vec2(double x_, double y_) : x(x_), y(y_) {}
    constexpr double operator[](int i) const { return i == 0 ? x : y; }
    double& operator[](int i) { return i == 0 ? x : y; }
    constexpr Vec2 operator+(const Vec2& o) const { return {x + o.x, y + o.y}; }
    constexpr Vec2 operator-(const Vec2& o) const { return {x - o.x, y - o.y}; }
    constexpr Vec2 operator*(double s) const { return {x * s, y * s}; }
    constexpr Vec2 operator/(double s) const { return {x / s, y / s}; }
    Vec2& operator+=(const Vec2& o) {
        x += o.x;
        y += o.y;
        return *this;
    }
    Vec2& operator-=(const Vec2& o) {
        x -= o.x;
        y -= o.y;
        return *this;
    }
    constexpr bool operator==(const Vec2& o) const { return x == o.x && y == o.y; }
};
constexpr Vec2 operator*(double s, const Vec2& v) { return v * s; }
inline double dot(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }
inline double length(const Vec2& a) { return std::sqrt(dot(a, a)); }

struct Vec3 {
    double x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3(double s) : x(s), y(s), z(s) {}
    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    Vec3& operator+=(const Vec3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    Vec3& operator-=(const Vec3& o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    Vec3& operator*=(double s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    Vec3& operator/=(double s) {
        x /= s;
        y /= s;
        z /= s;
        return *this;
    }
    constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
    constexpr bool operator!=(const Vec3& o) const { return !(*this == o); }
};
constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }
constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double abs_dot(const Vec3& a, const Vec3& b) { return std::abs(dot(a, b)); }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length_squared(const Vec3& a) { return dot(a, a); }
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(const Vec3& a) { return a / length(a); }
inline Vec3 vmin(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3 vmax(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline double max_component(const Vec3& a) { return std::max(a.x, std::max(a.y, a.z)); }
/// Largest coordinate magnitude: the scale of a point's floating-point rounding.
inline double max_abs_component(const Vec3& a) {
    return std::max(std::abs(a.x), std::max(std::abs(a.y), std::abs(a.z)));
}
inline bool is_finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
/// Flip `v` to the hemisphere of `ref`.
inline Vec3 face_forward(const Vec3& v, const Vec3& ref) { return dot(v, ref) < 0 ? -v : v; }

/// Float triple, used only for mesh storage shared with Embree.
struct Vec3f {
    float x = 0, y = 0, z = 0;
    Vec3f() = default;
    Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    explicit Vec3f(const Vec3& v) : x(float(v.x)), y(float(v.y)), z(float(v.z)) {}
    Vec3 to_double() const { return {x, y, z}; }
};

/// Axis-aligned bounding box.
struct Bounds3 {
    Vec3 lo{kInfinity}, hi{-kInfinity};
    void expand(const Vec3& p) {
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    void expand(const Bounds3& b) {
        lo = vmin(lo, b.lo);
        hi = vmax(hi, b.hi);
    }
    bool valid() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }
    Vec3 center() const { return (lo + hi) * 0.5; }
    Vec3 extent() const { return hi - lo; }
};

template <typename T>
constexpr T sqr(T v) {
    return v * v;
}
inline double clamp(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
inline double safe_sqrt(double v) { return std::sqrt(std::max(0.0, v)); }
inline double lerp(double t, double a, double b) { return (1 - t) * a + t * b; }

/// A ray o + t d for t in (tmin, tmax). `d` need not be unit length but usually is.
struct Ray {
    Vec3 o, d;
    double tmin = 0.0, tmax = kInfinity;
    Vec3 at(double t) const { return o + d * t; }
};

}  // namespace snell
