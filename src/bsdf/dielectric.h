#pragma once
// Mitsuba's `dielectric`: smooth interface between two dielectrics (exact Fresnel), with
// snell's extensions `abbe` (dispersion, folded into int_ior by the factory) and `sigma_a`
// (Beer-Lambert absorption of the enclosed medium, applied by the integrator).
#include <optional>

#include "bsdf/bsdf.h"
#include "bsdf/param.h"

namespace snell {

class DielectricBSDF final : public BSDF {
public:
    /// `int_ior`/`ext_ior`: IOR inside (below, -z) and outside (+z) as functions of
    /// wavelength; `specular_*`: Mitsuba's non-physical scale factors; `sigma_a`: absorption
    /// coefficient of the interior in 1/scene unit (none when empty).
    DielectricBSDF(Spectrum int_ior, Spectrum ext_ior, SpectrumParam specular_reflectance = Spectrum::constant(1.0),
                   SpectrumParam specular_transmittance = Spectrum::constant(1.0),
                   std::optional<Spectrum> sigma_a = std::nullopt);

    /// Deltas only: eval and pdf are 0.
    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    /// Chooses reflection with probability F (so the weight carries no F), else refraction;
    /// in Radiance mode refraction scales by 1/eta_it^2 (non-symmetric transmission).
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kTransmission | kSpecular; }
    /// kappa of Eq. 9: F or (1 - F) (radiance-scaled) depending on the sides of wo and wi.
    SampledSpectrum eval_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    /// F or 1 - F: the probability with which sample() chooses that lobe.
    double pdf_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;

    double eta(double lambda) const override { return m_int_ior(lambda) / m_ext_ior(lambda); }
    bool dispersive() const override { return !m_int_ior.is_constant() || !m_ext_ior.is_constant(); }
    bool reads_uv() const override {
        return !m_specular_reflectance.is_constant() || !m_specular_transmittance.is_constant();
    }
    const Spectrum* interior_absorption() const override { return m_sigma_a ? &*m_sigma_a : nullptr; }

private:
    Spectrum m_int_ior, m_ext_ior;
    SpectrumParam m_specular_reflectance, m_specular_transmittance;
    std::optional<Spectrum> m_sigma_a;
};

}  // namespace snell
