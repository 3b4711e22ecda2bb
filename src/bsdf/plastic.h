#pragma once
// Mitsuba's `plastic`: a diffuse base under a smooth dielectric coating. Specular reflection
// off the coating (delta) plus a diffuse lobe attenuated by the two coating transmissions and
// boosted by the internal inter-reflections (the 1 - R_dr denominators).
#include "bsdf/bsdf.h"
#include "bsdf/param.h"

namespace snell {

class PlasticBSDF final : public BSDF {
public:
    /// `int_ior`/`ext_ior`: coating and exterior IOR (Mitsuba: polypropylene 1.49 / air);
    /// `nonlinear`: account for colour shifts of the inter-reflections (Mitsuba's flag).
    PlasticBSDF(SpectrumParam diffuse_reflectance, SpectrumParam specular_reflectance, double int_ior, double ext_ior,
                bool nonlinear = false);

    /// The diffuse part only (the coating's mirror reflection is a delta).
    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    /// Density of the diffuse lobe times its selection probability.
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kSpecular | kDiffuse; }

private:
    /// Probability of picking the specular lobe given the coating's reflectance F at wo.
    double specular_probability(double F) const;

    SpectrumParam m_diffuse_reflectance, m_specular_reflectance;
    double m_eta, m_inv_eta2;
    double m_fdr_int;  ///< diffuse reflectance of the coating seen from inside
    double m_specular_sampling_weight;
    bool m_nonlinear;
};

}  // namespace snell
