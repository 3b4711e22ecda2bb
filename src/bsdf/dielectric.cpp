#include "bsdf/dielectric.h"

#include "bsdf/fresnel.h"

namespace snell {

DielectricBSDF::DielectricBSDF(Spectrum int_ior, Spectrum ext_ior, Spectrum specular_reflectance,
                               Spectrum specular_transmittance, std::optional<Spectrum> sigma_a)
    : m_int_ior(std::move(int_ior)),
      m_ext_ior(std::move(ext_ior)),
      m_specular_reflectance(std::move(specular_reflectance)),
      m_specular_transmittance(std::move(specular_transmittance)),
      m_sigma_a(std::move(sigma_a)) {}

double DielectricBSDF::eval(const BSDFContext&, const Vec3&, const Vec3&) const { return 0; }
double DielectricBSDF::pdf(const BSDFContext&, const Vec3&, const Vec3&) const { return 0; }

std::optional<BSDFSample> DielectricBSDF::sample(const BSDFContext& ctx, const Vec3& wo,
                                                 double uc, const Vec2&) const {
    if (wo.z == 0) return std::nullopt;
    const DielectricFresnel f = fresnel_dielectric(wo.z, eta(ctx.lambda));
    BSDFSample s;
    if (uc < f.R) {
        s.wi = reflect(wo);
        s.pdf = f.R;
        s.weight = m_specular_reflectance.eval(ctx.lambda);
        s.eta = 1;
        s.lobe = kReflection | kSpecular;
    } else {
        s.wi = refract(wo, f.cos_t, f.eta_ti);
        s.pdf = 1 - f.R;
        // Radiance is compressed into the denser medium (Veach 1997, Sec. 5.2).
        const double scale = ctx.mode == TransportMode::Radiance ? sqr(f.eta_ti) : 1.0;
        s.weight = m_specular_transmittance.eval(ctx.lambda) * scale;
        s.eta = f.eta_it;
        s.lobe = kTransmission | kSpecular;
    }
    return s;
}

double DielectricBSDF::eval_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return 0;
    const DielectricFresnel f = fresnel_dielectric(wo.z, eta(ctx.lambda));
    if (wo.z * wi.z > 0) return f.R * m_specular_reflectance.eval(ctx.lambda);
    const double scale = ctx.mode == TransportMode::Radiance ? sqr(f.eta_ti) : 1.0;
    return (1 - f.R) * m_specular_transmittance.eval(ctx.lambda) * scale;
}

double DielectricBSDF::pdf_delta(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return 0;
    const double R = fresnel_dielectric(wo.z, eta(ctx.lambda)).R;
    return wo.z * wi.z > 0 ? R : 1 - R;
}

}  // namespace snell
