#pragma once
// Mitsuba's `blendbsdf` ((1 - w) first + w second) and, built from it, `mask` (opacity times the
// nested BSDF plus 1 - opacity of `null`). Sampling picks a component with its weight; a
// non-delta sample is then weighted by the whole mixture's value and density, so that MIS sees
// one BSDF; a delta sample keeps its component's weight with the lobe probability scaled.
#include <memory>

#include "bsdf/bsdf.h"
#include "bsdf/param.h"

namespace snell {

class BlendBSDF final : public BSDF {
public:
    /// `weight` in [0, 1] (a texture or a constant): the share of `second`.
    BlendBSDF(FloatParam weight, std::shared_ptr<const BSDF> first, std::shared_ptr<const BSDF> second);

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return m_flags; }  ///< computed once (a blend may nest the same BSDF twice)
    SampledSpectrum eval_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;

private:
    FloatParam m_weight;
    std::shared_ptr<const BSDF> m_first, m_second;
    uint32_t m_flags = 0;
};

}  // namespace snell
