#pragma once
// Mitsuba's `null`: a surface light passes through unchanged. Modelled as a delta transmission
// with eta 1 and weight 1, so every integrator handles it as it handles thin glass: BSDF
// sampling continues the ray straight on (MIS weight 1), and a shadow ray it blocks loses only
// what BSDF sampling then finds.
#include "bsdf/bsdf.h"

namespace snell {

class NullBSDF final : public BSDF {
public:
    SampledSpectrum eval(const BSDFContext&, const Vec3&, const Vec3&) const override { return {}; }
    double pdf(const BSDFContext&, const Vec3&, const Vec3&) const override { return 0; }
    std::optional<BSDFSample> sample(const BSDFContext&, const Vec3& wo, double, const Vec2&) const override {
        BSDFSample s;
        s.wi = -wo;
        s.weight = SampledSpectrum(1.0);
        s.pdf = 1;
        s.lobe = kTransmission | kSpecular;
        return s;
    }
    uint32_t flags() const override { return kTransmission | kSpecular; }
    /// The pass-through lobe connects wo to -wo alone, with probability 1 and value 1.
    SampledSpectrum eval_delta(const BSDFContext&, const Vec3& wo, const Vec3& wi) const override {
        return is_through(wo, wi) ? SampledSpectrum(1.0) : SampledSpectrum();
    }
    double pdf_delta(const BSDFContext&, const Vec3& wo, const Vec3& wi) const override {
        return is_through(wo, wi) ? 1.0 : 0.0;
    }

private:
    static bool is_through(const Vec3& wo, const Vec3& wi) { return length(wo + wi) < 1e-9; }
};

}  // namespace snell
