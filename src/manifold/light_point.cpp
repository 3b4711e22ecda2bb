#include "manifold/light_point.h"

#include "scene/scene.h"

namespace snell {

double far_light_distance(const Scene& scene) { return 1e6 * (scene.scene_radius() + length(scene.bounds().center())); }

LightPoint light_point(const Scene& scene, const Light& light, const LightSample& ls, const Vec3& ref) {
    LightPoint lp;
    lp.delta = ls.delta;
    if (!light.is_infinite()) {
        lp.p = ls.p;
        lp.n = ls.n;
        lp.uv = ls.uv;
        lp.pdf = ls.delta ? 1.0 : ls.pdf_area;
        lp.p_error = ls.p_error;
        return lp;
    }
    const double D = far_light_distance(scene);
    lp.p = ref + ls.wi * D;
    lp.n = -ls.wi;
    // Solid angle -> area on the far sphere (its normal faces ref, so |cos| = 1).
    lp.pdf = ls.delta ? 1.0 : ls.pdf / (D * D);
    return lp;
}

LightPoint light_point_hit(const Scene& scene, const Light& light, const Vec3& p, const Vec3& n, const Vec2& uv,
                           const Vec3& d, const Vec3& center) {
    LightPoint lp;
    lp.delta = light.is_delta();
    if (!light.is_infinite()) {
        lp.p = p;
        lp.n = n;
        lp.uv = uv;
        return lp;
    }
    lp.p = center + d * far_light_distance(scene);
    lp.n = -d;
    return lp;
}

double light_point_pdf(const Scene& scene, const Light& light, const Vec3& ref, const Vec3& p, const Vec3& n) {
    if (light.is_delta()) return 1.0;
    if (!light.is_infinite()) return light.pdf_point(ref, p, n);
    const Vec3 d = p - ref;
    const double dist2 = length_squared(d);
    const Vec3 w = d / std::sqrt(dist2);
    return light.pdf_li({ref, Vec3()}, p, n, w) * std::abs(dot(n, w)) / dist2;
    (void)scene;
}

SampledSpectrum light_point_emission(const Light& light, const LightPoint& lp, const Vec3& w, const Vec3& center,
                                     const SampledWavelengths& wl) {
    const SampledSpectrum e = light.emitted(lp.p, lp.n, lp.uv, w, wl);
    // A directional light's irradiance E is the intensity E D^2 of a point at distance D.
    return light.kind() == LightKind::Directional ? e * length_squared(lp.p - center) : e;
}

}  // namespace snell
