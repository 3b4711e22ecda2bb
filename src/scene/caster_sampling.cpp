#include "scene/caster_sampling.h"

#include <algorithm>
#include <cmath>

#include "core/frame.h"
#include "scene/scene.h"

namespace snell {

CasterSampling::CasterSampling(const Scene& scene, double probability) : m_scene(&scene), m_probability(probability) {
    const size_t n = scene.refractive_casters().size();
    if (n == 0 || n > kMaxCasters) m_probability = 0;
}

bool CasterSampling::cone(const SurfaceInteraction& si, size_t i, Vec3* axis, double* one_minus_cos) const {
    const BoundingSphere& b = m_scene->refractive_casters()[i];
    const Vec3 v = b.center - si.p;
    const double d2 = length_squared(v), r2 = b.radius * b.radius;
    if (!(d2 > r2)) return false;  // inside the caster's sphere: its cone is every direction
    const double sin2 = r2 / d2;
    *axis = v / std::sqrt(d2);
    // The side the path arrived on: a reflecting BSDF leaves by it alone, so a cone wholly
    // below that tangent plane would only draw zero-valued directions.
    const Vec3 n = dot(si.wo, si.ng) >= 0 ? si.ng : -si.ng;
    if (dot(*axis, n) <= -std::sqrt(sin2)) return false;
    *one_minus_cos = sin2 / (1 + std::sqrt(1 - sin2));  // without cancellation for far casters
    return true;
}

size_t CasterSampling::applicable(const SurfaceInteraction& si, size_t* ids) const {
    size_t n = 0;
    Vec3 axis;
    double omc = 0;
    for (size_t i = 0; i < m_scene->refractive_casters().size(); ++i)
        if (cone(si, i, &axis, &omc)) ids[n++] = i;
    return n;
}

bool CasterSampling::applies(const SurfaceInteraction& si, const BSDF& bsdf) const {
    if (!(m_probability > 0) || bsdf.has_delta() || bsdf.is_transmissive() || !bsdf.is_smooth_sampled()) return false;
    size_t ids[kMaxCasters];
    return applicable(si, ids) > 0;
}

double CasterSampling::cone_pdf(const SurfaceInteraction& si, const Vec3& d) const {
    size_t ids[kMaxCasters];
    const size_t n = applicable(si, ids);
    double sum = 0;
    for (size_t j = 0; j < n; ++j) {
        Vec3 axis;
        double omc = 0;
        cone(si, ids[j], &axis, &omc);
        // 1 - cos(d, axis) = |d - axis|^2 / 2 for unit vectors, exact for narrow cones.
        if (0.5 * length_squared(d - axis) <= omc) sum += 1.0 / (2 * kPi * omc);
    }
    return n > 0 ? sum / double(n) : 0.0;
}

double CasterSampling::pdf(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx, const Vec3& wo,
                           const Vec3& wi) const {
    const double p_bsdf = bsdf.pdf(ctx, wo, wi);
    if (!applies(si, bsdf)) return p_bsdf;
    return (1 - m_probability) * p_bsdf + m_probability * cone_pdf(si, si.to_world(wi));
}

std::optional<BSDFSample> CasterSampling::sample(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                                                 double uc, const Vec2& u) const {
    const Vec3 wo = si.to_local(si.wo);
    if (!applies(si, bsdf)) return bsdf.sample(ctx, wo, uc, u);
    const double c = m_probability;
    if (uc >= c) {
        // BSDF sampling, its lobe chosen by the rest of uc.
        auto bs = bsdf.sample(ctx, wo, std::min((uc - c) / (1 - c), 1 - 0x1p-53), u);
        if (!bs || !(bs->pdf > 0)) return bs;
        const double p = (1 - c) * bs->pdf + c * cone_pdf(si, si.to_world(bs->wi));
        bs->weight *= bs->pdf / p;
        bs->pdf = p;
        return bs;
    }
    // A caster's cone, picked uniformly among those that apply, then a direction uniform in it.
    size_t ids[kMaxCasters];
    const size_t n = applicable(si, ids);
    const size_t j = std::min(size_t(uc / c * double(n)), n - 1);
    Vec3 axis;
    double omc = 0;
    cone(si, ids[j], &axis, &omc);
    const double one_minus_z = u.x * omc, z = 1 - one_minus_z;
    const double r = std::sqrt(std::max(0.0, one_minus_z * (2 - one_minus_z))), phi = 2 * kPi * u.y;
    const Vec3 wi = si.to_local(Frame::from_normal(axis).to_world(Vec3(r * std::cos(phi), r * std::sin(phi), z)));
    const SampledSpectrum f = bsdf.eval(ctx, wo, wi);
    if (f.is_zero()) return std::nullopt;
    const double p = pdf(si, bsdf, ctx, wo, wi);
    if (!(p > 0)) return std::nullopt;
    BSDFSample bs;
    bs.wi = wi;
    bs.weight = f * (std::abs(wi.z) / p);
    bs.pdf = p;
    bs.lobe = bsdf.flags() & (kReflection | kDiffuse | kGlossy);
    return bs;
}

}  // namespace snell
