#include "bsdf/roughconductor.h"

#include "bsdf/fresnel.h"

namespace snell {

RoughConductorBSDF::RoughConductorBSDF(MicrofacetParam distribution, std::optional<ConductorIOR> ior,
                                       SpectrumParam specular_reflectance)
    : m_distr(distribution), m_ior(std::move(ior)), m_specular_reflectance(std::move(specular_reflectance)) {}

SampledSpectrum RoughConductorBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0) return {};
    const Vec3 m = normalize(wo + wi);
    const MicrofacetDistribution distr = m_distr.eval(ctx);
    const double D = distr.D(m);
    if (D == 0) return {};
    const double G = distr.G(wo, wi, m);
    const double c = dot(wo, m);
    SampledSpectrum F(1.0);
    if (m_ior)
        for (int i = 0; i < kSpectrumSamples; ++i)
            F[i] = fresnel_conductor(c, m_ior->eta(ctx.wl[i]), m_ior->k(ctx.wl[i]));
    return m_specular_reflectance.eval(ctx) * F * (D * G / (4 * wo.z * wi.z));
}

double RoughConductorBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const Vec3 m = normalize(wo + wi);
    const double dm = dot(wi, m);
    if (!(dm > 0)) return 0;
    return m_distr.eval(ctx).pdf(wo, m) / (4 * dm);
}

std::optional<BSDFSample> RoughConductorBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double,
                                                     const Vec2& u) const {
    if (wo.z <= 0) return std::nullopt;
    const auto [m, pm] = m_distr.eval(ctx).sample(wo, u);
    if (!(pm > 0) || dot(wo, m) <= 0) return std::nullopt;
    BSDFSample s;
    s.wi = reflect(wo, m);
    if (s.wi.z <= 0) return std::nullopt;
    s.pdf = pdf(ctx, wo, s.wi);
    if (!(s.pdf > 0)) return std::nullopt;
    s.weight = eval(ctx, wo, s.wi) * s.wi.z / s.pdf;
    s.lobe = kReflection | kGlossy;
    return s;
}

}  // namespace snell
