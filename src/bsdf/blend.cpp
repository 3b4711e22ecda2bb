#include "bsdf/blend.h"

namespace snell {

BlendBSDF::BlendBSDF(double weight, std::shared_ptr<const BSDF> first, std::shared_ptr<const BSDF> second)
    : m_weight(weight), m_first(std::move(first)), m_second(std::move(second)) {}

SampledSpectrum BlendBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    return m_first->eval(ctx, wo, wi) * (1 - m_weight) + m_second->eval(ctx, wo, wi) * m_weight;
}

double BlendBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    return (1 - m_weight) * m_first->pdf(ctx, wo, wi) + m_weight * m_second->pdf(ctx, wo, wi);
}

std::optional<BSDFSample> BlendBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const {
    // uc picks the component and is stretched back to [0, 1) for the component's own choice.
    const bool second = uc < m_weight;
    const double w = second ? m_weight : 1 - m_weight;
    if (!(w > 0)) return std::nullopt;
    const double uc2 = second ? uc / m_weight : (uc - m_weight) / (1 - m_weight);
    auto s = (second ? m_second : m_first)->sample(ctx, wo, std::min(uc2, 0x1.fffffffffffffp-1), u);
    if (!s) return std::nullopt;
    if (s->is_delta()) {
        // The lobe is chosen with probability w times the component's; its value is w times the
        // component's: the weight stays.
        s->pdf *= w;
        return s;
    }
    s->pdf = pdf(ctx, wo, s->wi);
    if (!(s->pdf > 0)) return std::nullopt;
    s->weight = eval(ctx, wo, s->wi) * std::abs(s->wi.z) / s->pdf;
    return s;
}

SampledSpectrum BlendBSDF::eval_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    return m_first->eval_delta(ctx, wo, wi) * (1 - m_weight) + m_second->eval_delta(ctx, wo, wi) * m_weight;
}

double BlendBSDF::pdf_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    return (1 - m_weight) * m_first->pdf_delta(ctx, wo, wi) + m_weight * m_second->pdf_delta(ctx, wo, wi);
}

}  // namespace snell
