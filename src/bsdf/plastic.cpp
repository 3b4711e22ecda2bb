#include "bsdf/plastic.h"

#include "bsdf/fresnel.h"
#include "core/warp.h"

namespace snell {

PlasticBSDF::PlasticBSDF(SpectrumParam diffuse_reflectance, SpectrumParam specular_reflectance, double int_ior,
                         double ext_ior, bool nonlinear)
    : m_diffuse_reflectance(std::move(diffuse_reflectance)),
      m_specular_reflectance(std::move(specular_reflectance)),
      m_eta(int_ior / ext_ior),
      m_inv_eta2(1.0 / sqr(int_ior / ext_ior)),
      m_fdr_int(fresnel_diffuse_reflectance(ext_ior / int_ior)),
      m_nonlinear(nonlinear) {
    // Lobe selection by the average albedos, as Mitsuba does.
    const double d = m_diffuse_reflectance.average(), s = m_specular_reflectance.average();
    m_specular_sampling_weight = d + s > 0 ? s / (d + s) : 0.5;
}

double PlasticBSDF::specular_probability(double F) const {
    const double ps = F * m_specular_sampling_weight;
    const double pd = (1 - F) * (1 - m_specular_sampling_weight);
    return ps + pd > 0 ? ps / (ps + pd) : 0.0;
}

SampledSpectrum PlasticBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0) return {};
    const double Fo = fresnel_dielectric(wo.z, m_eta).R, Fi = fresnel_dielectric(wi.z, m_eta).R;
    SampledSpectrum diff = m_diffuse_reflectance.eval(ctx);
    // Internal bounces between base and coating: geometric series in rho * R_dr.
    for (int i = 0; i < kSpectrumSamples; ++i) diff[i] /= m_nonlinear ? 1 - diff[i] * m_fdr_int : 1 - m_fdr_int;
    // Radiance crossing the coating twice, compressed by 1/eta^2 inside.
    return diff * m_inv_eta2 * (1 - Fo) * (1 - Fi) * kInvPi;
}

double PlasticBSDF::pdf(const BSDFContext&, const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const double ps = specular_probability(fresnel_dielectric(wo.z, m_eta).R);
    return (1 - ps) * warp::square_to_cosine_hemisphere_pdf(wi);
}

std::optional<BSDFSample> PlasticBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const {
    if (wo.z <= 0) return std::nullopt;
    const double F = fresnel_dielectric(wo.z, m_eta).R;
    const double ps = specular_probability(F);
    BSDFSample s;
    if (uc < ps) {
        s.wi = reflect(wo);
        s.pdf = ps;
        s.weight = m_specular_reflectance.eval(ctx) * (F / ps);
        s.lobe = kReflection | kSpecular;
        return s;
    }
    s.wi = warp::square_to_cosine_hemisphere(u);
    s.pdf = (1 - ps) * warp::square_to_cosine_hemisphere_pdf(s.wi);
    if (!(s.pdf > 0)) return std::nullopt;
    s.weight = eval(ctx, wo, s.wi) * s.wi.z / s.pdf;
    s.lobe = kReflection | kDiffuse;
    return s;
}

}  // namespace snell
