#include "bsdf/diffuse.h"

#include "core/warp.h"

namespace snell {

SampledSpectrum DiffuseBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0) return {};
    return m_reflectance.eval(ctx) * kInvPi;
}

double DiffuseBSDF::pdf(const BSDFContext&, const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    return warp::square_to_cosine_hemisphere_pdf(wi);
}

std::optional<BSDFSample> DiffuseBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double, const Vec2& u) const {
    if (wo.z <= 0) return std::nullopt;
    BSDFSample s;
    s.wi = warp::square_to_cosine_hemisphere(u);
    s.pdf = warp::square_to_cosine_hemisphere_pdf(s.wi);
    if (!(s.pdf > 0)) return std::nullopt;
    s.weight = m_reflectance.eval(ctx);  // (R/pi) cos / (cos/pi)
    s.lobe = kReflection | kDiffuse;
    return s;
}

}  // namespace snell
