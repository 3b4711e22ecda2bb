#include "bsdf/perturbed_frame.h"

#include <algorithm>
#include <cmath>

namespace snell {

Frame PerturbedFrameBSDF::frame_from_normal(const Vec3& n_in) {
    const double len = length(n_in);
    if (!(len > 0) || !std::isfinite(len) || !(n_in.z > 0)) return Frame();
    const Vec3 n = n_in / len;
    return Frame::from_normal_tangent(n, Vec3(1, 0, 0));
}

Frame PerturbedFrameBSDF::local_frame(const BSDFContext& ctx, const Vec3& wo) const {
    Vec3 n = local_normal(ctx);
    // Mitsuba 3's flip_invalid_normals: a viewer behind the perturbed normal sees it mirrored.
    if (m_opt.flip_invalid_normals && wo.z * dot(wo, n) <= 0) n = Vec3(-n.x, -n.y, n.z);
    return frame_from_normal(n);
}

double PerturbedFrameBSDF::shadowing(const Vec3& n, const Vec3& wi) const {
    if (!m_opt.shadowing) return 1.0;
    auto tan2 = [](const Vec3& v) {
        const double z2 = v.z * v.z, xy2 = v.x * v.x + v.y * v.y;
        return z2 > 0 ? xy2 / z2 : kInfinity;
    };
    const double a2 = std::min(0.125 * tan2(n), 1.0);
    if (!(a2 > 0)) return 1.0;  // the unperturbed normal: no shadowing (and no 0 * inf at grazing wi)
    const double t2 = tan2(wi);
    return std::isfinite(t2) ? 2.0 / (1.0 + std::sqrt(1.0 + a2 * t2)) : 0.0;
}

SampledSpectrum PerturbedFrameBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wi.z == 0) return {};
    const Frame f = local_frame(ctx, wo);
    const Vec3 wo_p = f.to_local(wo), wi_p = f.to_local(wi);
    if (wi.z * wi_p.z <= 0) return {};
    return m_nested->eval(ctx, wo_p, wi_p) * (std::abs(wi_p.z) / std::abs(wi.z) * shadowing(f.n, wi));
}

double PerturbedFrameBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const Frame f = local_frame(ctx, wo);
    const Vec3 wo_p = f.to_local(wo), wi_p = f.to_local(wi);
    if (wi.z * wi_p.z <= 0) return 0;
    return m_nested->pdf(ctx, wo_p, wi_p);
}

std::optional<BSDFSample> PerturbedFrameBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc,
                                                     const Vec2& u) const {
    const Frame f = local_frame(ctx, wo);
    auto s = m_nested->sample(ctx, f.to_local(wo), uc, u);
    if (!s) return std::nullopt;
    const Vec3 wi = f.to_world(s->wi);
    if (wi.z * s->wi.z <= 0) return std::nullopt;
    // The nested weight is f' |cos'_i| / pdf, which is eval() |cos_i| / pdf without the
    // shadowing term: that is applied here.
    s->weight = s->weight * shadowing(f.n, wi);
    s->wi = wi;
    return s;
}

}  // namespace snell
