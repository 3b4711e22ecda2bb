#include "manifold/manifold_vertex.h"

#include "geometry/shape.h"

namespace snell {

namespace {
// Derivative of s = normalize(q), q = a - n (n.a), along a direction in which n changes by dn.
Vec3 frame_s_derivative(const Vec3& n, const Vec3& s, double q_len, const Vec3& a, const Vec3& dn) {
    const Vec3 dq = -(dn * dot(n, a) + n * dot(dn, a));
    return (dq - s * dot(s, dq)) / q_len;
}
}  // namespace

ManifoldVertex ManifoldVertex::from_interaction(const SurfaceInteraction& si, double eta) {
    ManifoldVertex v;
    v.si = si;
    v.derive_from_si(eta);
    return v;
}

void ManifoldVertex::derive_from_si(double eta_) {
    ManifoldVertex& v = *this;
    v.p = si.p;
    v.n = si.n;
    v.ng = si.ng;
    v.eta = eta_;
    v.shape = si.shape;
    v.bsdf = si.bsdf();

    // Orthonormal position tangent basis in the geometric tangent plane.
    Vec3 ds = si.dpdu - si.ng * dot(si.ng, si.dpdu);
    if (!(length_squared(ds) > 1e-24 * (length_squared(si.dpdu) + 1e-300))) {
        ds = si.dpdv - si.ng * dot(si.ng, si.dpdv);
    }
    if (!(length_squared(ds) > 0)) ds = Frame::from_normal(si.ng).s;
    v.dp_ds = normalize(ds);
    v.dp_dt = cross(si.ng, v.dp_ds);

    // Shape operator along the basis.
    v.dn_ds = v.dn_dt = Vec3();
    if (si.shape) {
        v.dn_ds = si.shape->normal_derivative(si, v.dp_ds);
        v.dn_dt = si.shape->normal_derivative(si, v.dp_dt);
    }

    // Constraint frame from the fixed reference direction, and its derivatives.
    Vec3 a = constraint_frame_reference();
    Vec3 q = a - v.n * dot(v.n, a);
    if (length_squared(q) < 1e-12) {  // n = ±a: pick the next axis (measure-zero set)
        a = normalize(cross(a, Vec3(0, 0, 1)));
        q = a - v.n * dot(v.n, a);
    }
    const double ql = length(q);
    v.s = q / ql;
    v.t = cross(v.n, v.s);
    v.ds_ds = frame_s_derivative(v.n, v.s, ql, a, v.dn_ds);
    v.ds_dt = frame_s_derivative(v.n, v.s, ql, a, v.dn_dt);
    v.dt_ds = cross(v.dn_ds, v.s) + cross(v.n, v.ds_ds);
    v.dt_dt = cross(v.dn_dt, v.s) + cross(v.n, v.ds_dt);
}

double half_vector_orientation(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo) {
    const bool wi_out = dot(wi, v.ng) >= 0, wo_out = dot(wo, v.ng) >= 0;
    // Transmission: for every admissible refraction eta_i wi + eta_o wo points into the
    // less dense side (Snell: the denser side's direction has the larger normal component
    // once scaled by its IOR), i.e. to -n when the inside is denser (eta > 1) and to +n
    // otherwise (an air bubble in water). Reflection inside points to -n. The sign depends
    // only on the sides of wi and wo and on eta, so c_i is continuous while the walk moves
    // vertices (orienting by the sign of h.n instead jumps far from solutions).
    if (wi_out != wo_out) return v.eta > 1 ? -1.0 : 1.0;
    return wi_out ? 1.0 : -1.0;
}

Vec3 generalized_half_vector(const ManifoldVertex& v, const Vec3& wi, const Vec3& wo) {
    // IOR on each side relative to the outside (the side of ng).
    const double eta_i = dot(wi, v.ng) >= 0 ? 1.0 : v.eta;
    const double eta_o = dot(wo, v.ng) >= 0 ? 1.0 : v.eta;
    const Vec3 h = (wi * eta_i + wo * eta_o) * half_vector_orientation(v, wi, wo);
    const double l = length(h);
    return l > 0 ? h / l : v.n;
}

}  // namespace snell
