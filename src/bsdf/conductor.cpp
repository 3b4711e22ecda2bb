#include "bsdf/conductor.h"

#include "bsdf/fresnel.h"

namespace snell {

ConductorBSDF::ConductorBSDF(std::optional<ConductorIOR> ior, Spectrum specular_reflectance)
    : m_ior(std::move(ior)), m_specular_reflectance(std::move(specular_reflectance)) {}

double ConductorBSDF::eval(const BSDFContext&, const Vec3&, const Vec3&) const { return 0; }
double ConductorBSDF::pdf(const BSDFContext&, const Vec3&, const Vec3&) const { return 0; }

double ConductorBSDF::reflectance(double lambda, double cos_theta) const {
    const double F =
        m_ior ? fresnel_conductor(cos_theta, m_ior->eta(lambda), m_ior->k(lambda)) : 1.0;
    return F * m_specular_reflectance(lambda);
}

std::optional<BSDFSample> ConductorBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double,
                                                const Vec2&) const {
    if (wo.z <= 0) return std::nullopt;
    BSDFSample s;
    s.wi = reflect(wo);
    s.pdf = 1;
    s.weight = reflectance(ctx.lambda, wo.z);
    s.lobe = kReflection | kSpecular;
    return s;
}

}  // namespace snell
