#include "bsdf/blend.h"

namespace snell {

BlendBSDF::BlendBSDF(FloatParam weight, std::shared_ptr<const BSDF> first, std::shared_ptr<const BSDF> second)
    : m_weight(std::move(weight)),
      m_first(std::move(first)),
      m_second(std::move(second)),
      m_flags(m_first->flags() | m_second->flags()) {}

SampledSpectrum BlendBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const double weight = m_weight.eval(ctx);
    return m_first->eval(ctx, wo, wi) * (1 - weight) + m_second->eval(ctx, wo, wi) * weight;
}

double BlendBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const double weight = m_weight.eval(ctx);
    return (1 - weight) * m_first->pdf(ctx, wo, wi) + weight * m_second->pdf(ctx, wo, wi);
}

std::optional<BSDFSample> BlendBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const {
    const double weight = m_weight.eval(ctx);
    // uc picks the component and is stretched back to [0, 1) for the component's own choice.
    const bool second = uc < weight;
    const double w = second ? weight : 1 - weight;
    if (!(w > 0)) return std::nullopt;
    const double uc2 = second ? uc / weight : (uc - weight) / (1 - weight);
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
    const double weight = m_weight.eval(ctx);
    return m_first->eval_delta(ctx, wo, wi) * (1 - weight) + m_second->eval_delta(ctx, wo, wi) * weight;
}

double BlendBSDF::pdf_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const double weight = m_weight.eval(ctx);
    return (1 - weight) * m_first->pdf_delta(ctx, wo, wi) + weight * m_second->pdf_delta(ctx, wo, wi);
}

}  // namespace snell
