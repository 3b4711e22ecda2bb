#include "bsdf/twosided.h"

namespace snell {

namespace {
Vec3 flip(const Vec3& w) { return {w.x, w.y, -w.z}; }
}  // namespace

TwoSidedBSDF::TwoSidedBSDF(std::shared_ptr<const BSDF> front, std::shared_ptr<const BSDF> back)
    : m_front(std::move(front)),
      m_back(back ? std::move(back) : m_front),
      m_flags(m_front->flags() | m_back->flags()) {}

SampledSpectrum TwoSidedBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z > 0) return m_front->eval(ctx, wo, wi);
    if (wo.z < 0) return m_back->eval(ctx, flip(wo), flip(wi));
    return {};
}

double TwoSidedBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z > 0) return m_front->pdf(ctx, wo, wi);
    if (wo.z < 0) return m_back->pdf(ctx, flip(wo), flip(wi));
    return 0;
}

std::optional<BSDFSample> TwoSidedBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const {
    if (wo.z > 0) return m_front->sample(ctx, wo, uc, u);
    if (wo.z == 0) return std::nullopt;
    auto s = m_back->sample(ctx, flip(wo), uc, u);
    if (s) s->wi = flip(s->wi);
    return s;
}

}  // namespace snell
