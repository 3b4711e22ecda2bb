#include "manifold/constraints.h"

namespace snell {

namespace {

// (I - w w^T) e / l: derivative of the unit vector w = d/|d| when d's tip moves by e, l = |d|.
Vec3 unit_derivative(const Vec3& w, double l, const Vec3& e) { return (e - w * dot(w, e)) / l; }

}  // namespace

Vec2 half_vector_constraint_value(const Vec3& prev, const ManifoldVertex& v, const Vec3& next) {
    const Vec3 wi = normalize(prev - v.p), wo = normalize(next - v.p);
    return tangential(v, generalized_half_vector(v, wi, wo)) - v.h_target;
}

ConstraintBlocks half_vector_constraint(const TangentBasis& prev, const ManifoldVertex& v, const TangentBasis& next) {
    ConstraintBlocks out;
    Vec3 di = prev.p - v.p, dout = next.p - v.p;
    const double li = length(di), lo = length(dout);
    if (!(li > 0) || !(lo > 0)) {
        out.valid = false;
        return out;
    }
    const Vec3 wi = di / li, wo = dout / lo;
    const double eta_i = dot(wi, v.ng) >= 0 ? 1.0 : v.eta;
    const double eta_o = dot(wo, v.ng) >= 0 ? 1.0 : v.eta;
    const double sign = half_vector_orientation(v, wi, wo);
    const Vec3 h = (wi * eta_i + wo * eta_o) * sign;
    const double hl = length(h);
    if (!(hl > 0)) {
        out.valid = false;
        return out;
    }
    const Vec3 hn = h / hl;
    out.value = Vec2(dot(hn, v.s), dot(hn, v.t)) - v.h_target;

    // d(hn) for a change dh of the unnormalised half vector.
    const auto dhn = [&](const Vec3& dh) { return unit_derivative(hn, hl, dh * sign); };
    // Moving x_{i-1} by e changes wi only; moving x_{i+1} changes wo only; moving x_i by e
    // moves both directions by -e and also turns the frame (s, t) with the normal.
    const auto dh_prev = [&](const Vec3& e) { return unit_derivative(wi, li, e) * eta_i; };
    const auto dh_next = [&](const Vec3& e) { return unit_derivative(wo, lo, e) * eta_o; };
    const auto proj = [&](const Vec3& d) { return Vec2(dot(d, v.s), dot(d, v.t)); };

    out.A = Mat2::from_columns(proj(dhn(dh_prev(prev.dp_ds))), proj(dhn(dh_prev(prev.dp_dt))));
    out.C = Mat2::from_columns(proj(dhn(dh_next(next.dp_ds))), proj(dhn(dh_next(next.dp_dt))));
    const auto b_column = [&](const Vec3& e, const Vec3& ds, const Vec3& dt) {
        const Vec3 d = dhn(-(dh_prev(e) + dh_next(e)));
        return Vec2(dot(d, v.s) + dot(hn, ds), dot(d, v.t) + dot(hn, dt));
    };
    out.B = Mat2::from_columns(b_column(v.dp_ds, v.ds_ds, v.dt_ds), b_column(v.dp_dt, v.ds_dt, v.dt_dt));
    return out;
}

}  // namespace snell
