#include "integrators/bdpt/connect.h"

#include <cmath>

#include "integrators/scatter.h"
#include "scene/scene.h"

namespace snell::bdpt {

namespace {

// Light-subpath vertex y scattering towards unit direction d: the adjoint BSDF times the
// shading cosine, with the shading-normal correction of Importance transport.
SampledSpectrum adjoint_f(const Vertex& y, const Vec3& d, const SampledWavelengths& wl) {
    return y.bsdf->eval(BSDFContext{wl, TransportMode::Importance}.at(y.si), y.si.to_local(y.si.wo), y.si.to_local(d)) *
           (std::abs(dot(y.si.n, d)) * shading_correction(y.si, y.si.wo, d));
}

// Beer-Lambert transmittance of a connection edge of length `dist` leaving vertex v along d:
// the edge lies in v's medium, or the one behind v's interface when it refracts there.
SampledSpectrum edge_transmittance(const Vertex& v, const Vec3& d, double dist, const SampledWavelengths& wl) {
    return medium_towards(v.media, v.si, *v.bsdf, d, wl.hero()).transmittance(dist, wl);
}

// Both subpaths passed a dispersive refraction: each scaled its hero by the wavelength count,
// which the joined path must carry once.
SampledSpectrum joined(const SampledSpectrum& c, const Vertex& z, const Vertex& y, const SampledWavelengths& wl) {
    return z.hero_only && y.hero_only ? c / double(wl.count()) : c;
}

}  // namespace

SampledSpectrum connect(const Scene& scene, const std::vector<Vertex>& cam, const std::vector<Vertex>& lig, int s,
                        int t, const SampledWavelengths& wl) {
    const Vertex& z = cam[size_t(t - 1)];
    const Vertex& y = lig[size_t(s - 1)];
    if (!z.connectible() || !y.connectible()) return {};
    if (y.infinite) {
        // A light at infinity: the "edge" is the direction y.dir; its geometry term is the
        // cosine at z alone. The shadow ray must escape; a camera vertex inside an absorbing
        // medium cannot see the sky without crossing the medium's boundary, which occludes it.
        const SampledSpectrum fz = z.bsdf->eval(BSDFContext{wl, TransportMode::Radiance}.at(z.si),
                                                z.si.to_local(z.si.wo), z.si.to_local(y.dir)) *
                                   std::abs(dot(z.si.n, y.dir));
        const SampledSpectrum c = z.beta * fz * y.light->emitted(Vec3(), Vec3(), Vec2(), -y.dir, wl) * y.beta;
        if (c.is_zero() || scene.occluded(scene.spawn_ray(z.si, y.dir))) return {};
        return joined(c, z, y, wl);
    }
    Vec3 d = y.si.p - z.si.p;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return {};
    const double dist = std::sqrt(d2);
    d /= dist;
    const SampledSpectrum fz =
        z.bsdf->eval(BSDFContext{wl, TransportMode::Radiance}.at(z.si), z.si.to_local(z.si.wo), z.si.to_local(d)) *
        std::abs(dot(z.si.n, d));
    if (fz.is_zero()) return {};
    SampledSpectrum fy;
    if (s == 1) {
        fy = y.has_normal() ? y.light->le(y.si.p, y.si.n, y.si.uv, -d, wl) * std::abs(dot(y.si.n, d))
                            : y.light->emitted(y.si.p, Vec3(), Vec2(), -d, wl);
    } else {
        fy = adjoint_f(y, -d, wl);
    }
    SampledSpectrum c = z.beta * fz * fy * y.beta / d2;
    if (c.is_zero()) return {};
    c *= edge_transmittance(z, d, dist, wl);
    if (scene.occluded(scene.spawn_ray_to(z.si, y.si))) return {};
    return joined(c, z, y, wl);
}

SampledSpectrum connect_camera(const Scene& scene, const Vertex& z0, const Vertex& y, const SampledWavelengths& wl,
                               Vec2* raster) {
    if (!y.connectible() || y.type != VertexType::Surface) return {};
    double cos_theta = 0;
    if (!z0.pinhole->raster(y.si.p, raster, &cos_theta)) return {};
    Vec3 d = z0.si.p - y.si.p;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return {};
    const double dist = std::sqrt(d2);
    d /= dist;
    SampledSpectrum c = y.beta * adjoint_f(y, d, wl) * (z0.pinhole->importance(cos_theta) * cos_theta / d2);
    if (c.is_zero()) return {};
    c *= edge_transmittance(y, d, dist, wl);
    if (scene.occluded(scene.spawn_ray_to(y.si, z0.si))) return {};
    return c;
}

}  // namespace snell::bdpt
