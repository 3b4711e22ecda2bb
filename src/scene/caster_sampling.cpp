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

bool CasterSampling::cone(const SurfaceInteraction& si, size_t i, Cone* out) const {
    const BoundingSphere& b = m_scene->refractive_casters()[i];
    const Vec3 v = b.center - si.p;
    const double d2 = length_squared(v), r2 = b.radius * b.radius;
    if (!(d2 > r2)) return false;  // inside the caster's sphere: its cone is every direction
    const double sin2 = r2 / d2;
    out->axis = v / std::sqrt(d2);
    // The side the path arrived on: a reflecting BSDF leaves by it alone, so a cone wholly
    // below that tangent plane would only draw zero-valued directions.
    const Vec3 n = dot(si.wo, si.ng) >= 0 ? si.ng : -si.ng;
    if (dot(out->axis, n) <= -std::sqrt(sin2)) return false;
    out->one_minus_cos = sin2 / (1 + std::sqrt(1 - sin2));  // without cancellation for far casters
    return overlaps_a_light(si.p, *out);
}

bool CasterSampling::overlaps_a_light(const Vec3& p, const Cone& c) const {
    const auto& lights = m_scene->bounded_lights();
    if (lights.empty()) return true;  // a bright environment, or too many lights to test
    const double cos_c = 1 - c.one_minus_cos, sin_c = std::sqrt(std::max(0.0, c.one_minus_cos * (1 + cos_c)));
    for (const LightBounds& l : lights) {
        Vec3 axis = l.direction;  // a directional light: a cone of angle 0
        double cos_l = 1, sin_l = 0;
        if (!l.directional) {
            const Vec3 v = l.sphere.center - p;
            const double d2 = length_squared(v), r = l.sphere.radius;
            if (!(d2 > r * r)) return true;  // inside the light's sphere
            axis = v / std::sqrt(d2);
            sin_l = r / std::sqrt(d2);
            cos_l = std::sqrt(1 - sin_l * sin_l);
        }
        // The cones overlap where the angle between their axes is at most the sum of their
        // half angles (each under 90 degrees, so the sum's cosine decides).
        if (dot(axis, c.axis) >= cos_c * cos_l - sin_c * sin_l) return true;
    }
    return false;
}

size_t CasterSampling::applicable(const SurfaceInteraction& si, Cone* cones) const {
    size_t n = 0;
    for (size_t i = 0; i < m_scene->refractive_casters().size(); ++i)
        if (cone(si, i, &cones[n])) ++n;
    return n;
}

bool CasterSampling::aims_at(const BSDF& bsdf) const {
    return m_probability > 0 && !bsdf.has_delta() && !bsdf.is_transmissive() && bsdf.is_smooth_sampled();
}

bool CasterSampling::applies(const SurfaceInteraction& si, const BSDF& bsdf) const {
    Cone cones[kMaxCasters];
    return aims_at(bsdf) && applicable(si, cones) > 0;
}

double CasterSampling::cone_pdf(const Cone* cones, size_t n, const Vec3& d) {
    double sum = 0;
    for (size_t j = 0; j < n; ++j)
        // 1 - cos(d, axis) = |d - axis|^2 / 2 for unit vectors, exact for narrow cones.
        if (0.5 * length_squared(d - cones[j].axis) <= cones[j].one_minus_cos)
            sum += 1.0 / (2 * kPi * cones[j].one_minus_cos);
    return n > 0 ? sum / double(n) : 0.0;
}

double CasterSampling::pdf(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx, const Vec3& wo,
                           const Vec3& wi) const {
    const double p_bsdf = bsdf.pdf(ctx, wo, wi);
    Cone cones[kMaxCasters];
    const size_t n = aims_at(bsdf) ? applicable(si, cones) : 0;
    if (n == 0) return p_bsdf;
    return (1 - m_probability) * p_bsdf + m_probability * cone_pdf(cones, n, si.to_world(wi));
}

std::optional<BSDFSample> CasterSampling::sample(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                                                 double uc, const Vec2& u) const {
    const Vec3 wo = si.to_local(si.wo);
    Cone cones[kMaxCasters];
    const size_t n = aims_at(bsdf) ? applicable(si, cones) : 0;
    if (n == 0) return bsdf.sample(ctx, wo, uc, u);
    const double c = m_probability;
    if (uc >= c) {
        // BSDF sampling, its lobe chosen by the rest of uc.
        auto bs = bsdf.sample(ctx, wo, std::min((uc - c) / (1 - c), 1 - 0x1p-53), u);
        if (!bs || !(bs->pdf > 0)) return bs;
        const double p = (1 - c) * bs->pdf + c * cone_pdf(cones, n, si.to_world(bs->wi));
        bs->weight *= bs->pdf / p;
        bs->pdf = p;
        return bs;
    }
    // A caster's cone, picked uniformly among those that apply, then a direction uniform in it.
    const Cone& k = cones[std::min(size_t(uc / c * double(n)), n - 1)];
    const double one_minus_z = u.x * k.one_minus_cos, z = 1 - one_minus_z;
    const double r = std::sqrt(std::max(0.0, one_minus_z * (2 - one_minus_z))), phi = 2 * kPi * u.y;
    const Vec3 d = Frame::from_normal(k.axis).to_world(Vec3(r * std::cos(phi), r * std::sin(phi), z));
    const Vec3 wi = si.to_local(d);
    const SampledSpectrum f = bsdf.eval(ctx, wo, wi);
    if (f.is_zero()) return std::nullopt;
    const double p = (1 - c) * bsdf.pdf(ctx, wo, wi) + c * cone_pdf(cones, n, d);
    if (!(p > 0)) return std::nullopt;
    BSDFSample bs;
    bs.wi = wi;
    bs.weight = f * (std::abs(wi.z) / p);
    bs.pdf = p;
    bs.lobe = bsdf.flags() & (kReflection | kDiffuse | kGlossy);
    return bs;
}

}  // namespace snell
