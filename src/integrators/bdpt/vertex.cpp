#include "integrators/bdpt/vertex.h"

#include "core/warp.h"
#include "geometry/shape.h"
#include "light/light_sampler.h"
#include "scene/scene.h"

namespace snell::bdpt {

double pdf_area(const Vertex& v, const Vertex* prev, const Vertex& next, TransportMode mode,
                const SampledWavelengths& wl, const SceneDisk& disk) {
    const Vec3 wi = direction(v, next);
    if (v.type == VertexType::Camera) {
        Vec2 r;
        double cos_theta = 0;
        return v.pinhole->raster(next.si.p, &r, &cos_theta) ? to_area(v.pinhole->pdf_dir(cos_theta), v, next) : 0.0;
    }
    if (v.type == VertexType::Light) {
        if (v.infinite) return to_area(disk.pdf(), v, next);
        if (delta_position(*v.light)) return to_area(kInv4Pi, v, next);
        const double c = dot(v.si.n, wi);
        return c > 0 ? to_area(c * kInvPi, v, next) : 0.0;
    }
    if (v.type != VertexType::Surface || !v.bsdf || !prev) return 0;
    const Vec3 wo = direction(v, *prev);
    const BSDFContext ctx = BSDFContext{wl, mode}.at(v.si);
    return to_area(v.bsdf->pdf(ctx, v.si.to_local(wo), v.si.to_local(wi)), v, next);
}

double light_origin_pdf(const Scene& scene, const Vertex& v) {
    const Light& light = *v.light;
    const double pmf = scene.light_sampler().pmf(&light);
    if (v.infinite) return pmf * light.pdf_li({}, Vec3(), Vec3(), v.dir);
    if (delta_position(light)) return pmf;
    return light.shape() ? pmf / light.shape()->area() : 0.0;
}

double shading_correction(const SurfaceInteraction& si, const Vec3& wo, const Vec3& wi) {
    const double num = std::abs(dot(wo, si.n)) * std::abs(dot(wi, si.ng));
    const double den = std::abs(dot(wo, si.ng)) * std::abs(dot(wi, si.n));
    return den > 0 ? num / den : 0.0;
}

}  // namespace snell::bdpt
