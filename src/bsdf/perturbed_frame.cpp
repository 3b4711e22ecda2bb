#include "bsdf/perturbed_frame.h"

#include <cmath>

namespace snell {

Frame PerturbedFrameBSDF::frame_from_normal(const Vec3& n_in) {
    const double len = length(n_in);
    if (!(len > 0) || !std::isfinite(len) || !(n_in.z > 0)) return Frame();
    const Vec3 n = n_in / len;
    return Frame::from_normal_tangent(n, Vec3(1, 0, 0));
}

SampledSpectrum PerturbedFrameBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wi.z == 0) return {};
    const Frame f = local_frame(ctx);
    const Vec3 wo_p = f.to_local(wo), wi_p = f.to_local(wi);
    if (wi.z * wi_p.z <= 0) return {};
    return m_nested->eval(ctx, wo_p, wi_p) * (std::abs(wi_p.z) / std::abs(wi.z));
}

double PerturbedFrameBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const Frame f = local_frame(ctx);
    const Vec3 wo_p = f.to_local(wo), wi_p = f.to_local(wi);
    if (wi.z * wi_p.z <= 0) return 0;
    return m_nested->pdf(ctx, wo_p, wi_p);
}

std::optional<BSDFSample> PerturbedFrameBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc,
                                                     const Vec2& u) const {
    const Frame f = local_frame(ctx);
    auto s = m_nested->sample(ctx, f.to_local(wo), uc, u);
    if (!s) return std::nullopt;
    const Vec3 wi = f.to_world(s->wi);
    if (wi.z * s->wi.z <= 0) return std::nullopt;
    // The nested weight is f' |cos'_i| / pdf, which is eval() |cos_i| / pdf: it stays.
    s->wi = wi;
    return s;
}

}  // namespace snell
