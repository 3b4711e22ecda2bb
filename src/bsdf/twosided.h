#pragma once
// Mitsuba's `twosided`: makes a one-sided (reflection-only) BSDF two-sided, optionally with a
// different BSDF on the back (-z) side.
#include <memory>

#include "bsdf/bsdf.h"

namespace snell {

class TwoSidedBSDF final : public BSDF {
public:
    /// `back` defaults to `front`. Both must be non-transmissive (the factory checks).
    explicit TwoSidedBSDF(std::shared_ptr<const BSDF> front, std::shared_ptr<const BSDF> back = nullptr);

    /// Below the surface (wo.z < 0) the back BSDF is evaluated with both directions mirrored.
    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    /// Computed once at construction: front and back are often the same object, and asking both
    /// at every call made nested twosided BSDFs cost 2^depth (issue 12).
    uint32_t flags() const override { return m_flags; }

private:
    std::shared_ptr<const BSDF> m_front, m_back;
    uint32_t m_flags = 0;
};

}  // namespace snell
