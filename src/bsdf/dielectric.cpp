#include "bsdf/dielectric.h"

#include "bsdf/fresnel.h"

namespace snell {

DielectricBSDF::DielectricBSDF(Spectrum int_ior, Spectrum ext_ior, SpectrumParam specular_reflectance,
                               SpectrumParam specular_transmittance, std::optional<Spectrum> sigma_a)
    : m_int_ior(std::move(int_ior)),
      m_ext_ior(std::move(ext_ior)),
      m_specular_reflectance(std::move(specular_reflectance)),
      m_specular_transmittance(std::move(specular_transmittance)),
      m_sigma_a(std::move(sigma_a)) {}

SampledSpectrum DielectricBSDF::eval(const BSDFContext&, const Vec3&, const Vec3&) const { return {}; }
double DielectricBSDF::pdf(const BSDFContext&, const Vec3&, const Vec3&) const { return 0; }

std::optional<BSDFSample> DielectricBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2&) const {
    if (wo.z == 0) return std::nullopt;
    // The lobe is chosen by the hero's Fresnel term; the other wavelengths weight by theirs.
    const DielectricFresnel f = fresnel_dielectric(wo.z, eta(ctx.hero()));
    BSDFSample s;
    if (uc < f.R) {
        s.wi = reflect(wo);
        s.pdf = f.R;
        s.eta = 1;
        s.lobe = kReflection | kSpecular;
    } else {
        s.wi = refract(wo, f.cos_t, f.eta_ti);
        s.pdf = 1 - f.R;
        s.eta = f.eta_it;
        s.lobe = kTransmission | kSpecular;
        // Each wavelength refracts its own way: the direction is the hero's alone.
        s.hero_only = dispersive();
    }
    if (!(s.pdf > 0)) return std::nullopt;
    s.weight = eval_delta(ctx, wo, s.wi) / s.pdf;
    return s;
}

SampledSpectrum DielectricBSDF::eval_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return {};
    const bool reflection = wo.z * wi.z > 0;
    // kappa per wavelength; with dispersion, refraction keeps the hero alone (the pair
    // (wo, wi) obeys the specular law for the hero's eta only).
    const auto kappa = [&](double lambda) {
        const DielectricFresnel f = fresnel_dielectric(wo.z, eta(lambda));
        if (reflection) return f.R;
        // Radiance is compressed into the denser medium (Veach 1997, Sec. 5.2).
        const double scale = ctx.mode == TransportMode::Radiance ? sqr(f.eta_ti) : 1.0;
        return (1 - f.R) * scale;
    };
    SampledSpectrum k;
    if (!dispersive()) {
        k = SampledSpectrum(kappa(ctx.hero()));
    } else if (reflection) {
        for (int i = 0; i < kSpectrumSamples; ++i) k[i] = kappa(ctx.wl[i]);
    } else {
        k[0] = kappa(ctx.hero());
    }
    return k * (reflection ? m_specular_reflectance : m_specular_transmittance).eval(ctx);
}

double DielectricBSDF::pdf_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return 0;
    const double R = fresnel_dielectric(wo.z, eta(ctx.hero())).R;
    return wo.z * wi.z > 0 ? R : 1 - R;
}

}  // namespace snell
