#include "bsdf/thindielectric.h"

#include "bsdf/fresnel.h"

namespace snell {

ThinDielectricBSDF::ThinDielectricBSDF(Spectrum int_ior, Spectrum ext_ior, SpectrumParam specular_reflectance,
                                       SpectrumParam specular_transmittance)
    : m_int_ior(std::move(int_ior)),
      m_ext_ior(std::move(ext_ior)),
      m_specular_reflectance(std::move(specular_reflectance)),
      m_specular_transmittance(std::move(specular_transmittance)) {}

SampledSpectrum ThinDielectricBSDF::eval(const BSDFContext&, const Vec3&, const Vec3&) const { return {}; }
double ThinDielectricBSDF::pdf(const BSDFContext&, const Vec3&, const Vec3&) const { return 0; }

double ThinDielectricBSDF::slab_reflectance(double lambda, double cos_theta) const {
    const double R = fresnel_dielectric(std::abs(cos_theta), m_int_ior(lambda) / m_ext_ior(lambda)).R;
    if (R >= 1) return 1;
    // Geometric series of the inner bounces: R + T^2 R (1 + R^2 + R^4 + ...).
    const double T = 1 - R;
    return R + T * T * R / (1 - R * R);
}

SampledSpectrum ThinDielectricBSDF::slab_reflectance(const SampledWavelengths& wl, double cos_theta) const {
    SampledSpectrum R;
    for (int i = 0; i < kSpectrumSamples; ++i) R[i] = slab_reflectance(wl[i], cos_theta);
    return R;
}

std::optional<BSDFSample> ThinDielectricBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc,
                                                     const Vec2&) const {
    if (wo.z == 0) return std::nullopt;
    // The slab neither bends nor disperses a ray: every wavelength follows the hero's lobe,
    // weighted by its own reflectance over the hero's.
    const SampledSpectrum R = slab_reflectance(ctx.wl, wo.z);
    BSDFSample s;
    s.eta = 1;
    if (uc < R[0]) {
        s.wi = reflect(wo);
        s.pdf = R[0];
        s.weight = m_specular_reflectance.eval(ctx) * R / R[0];
        s.lobe = kReflection | kSpecular;
    } else {
        s.wi = -wo;
        s.pdf = 1 - R[0];
        s.weight = m_specular_transmittance.eval(ctx) * (SampledSpectrum(1.0) - R) / s.pdf;
        s.lobe = kTransmission | kSpecular;
    }
    if (!(s.pdf > 0)) return std::nullopt;
    return s;
}

}  // namespace snell
