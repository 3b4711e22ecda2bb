#include "integrators/bdpt/connect.h"

#include <cmath>

#include "geometry/scene.h"

namespace snell::bdpt {

namespace {

// Light-subpath vertex y scattering towards unit direction d: the adjoint BSDF times the
// shading cosine, with the shading-normal correction of Importance transport.
double adjoint_f(const Vertex& y, const Vec3& d, double lambda) {
    return y.bsdf->eval({lambda, TransportMode::Importance}, y.si.to_local(y.si.wo), y.si.to_local(d)) *
           std::abs(dot(y.si.n, d)) * shading_correction(y.si, y.si.wo, d);
}

// Beer-Lambert transmittance of a connection edge of length `dist` leaving vertex v along d:
// the edge lies in v's medium, or the one behind v's interface when it refracts there.
double edge_transmittance(const Vertex& v, const Vec3& d, double dist, double lambda) {
    MediumStack media = v.media;
    if (dot(v.si.wo, v.si.ng) * dot(d, v.si.ng) < 0 && (v.bsdf->eta(lambda) != 1.0 || v.bsdf->interior_absorption()))
        media.cross(v.bsdf->interior_absorption(), dot(v.si.wo, v.si.ng) > 0);
    return media.transmittance(dist, lambda);
}

}  // namespace

double connect(const Scene& scene, const std::vector<Vertex>& cam, const std::vector<Vertex>& lig, int s, int t,
               double lambda) {
    const Vertex& z = cam[size_t(t - 1)];
    const Vertex& y = lig[size_t(s - 1)];
    if (!z.connectible() || !y.connectible()) return 0;
    if (y.infinite) {
        // A light at infinity: the "edge" is the direction y.dir; its geometry term is the
        // cosine at z alone. The shadow ray must escape; a camera vertex inside an absorbing
        // medium cannot see the sky without crossing the medium's boundary, which occludes it.
        const double fz = z.bsdf->eval({lambda, TransportMode::Radiance}, z.si.to_local(z.si.wo), z.si.to_local(y.dir)) *
                          std::abs(dot(z.si.n, y.dir));
        const double c = z.beta * fz * y.light->emitted(Vec3(), Vec3(), -y.dir, lambda) * y.beta;
        if (!(c > 0) || scene.occluded(scene.spawn_ray(z.si, y.dir))) return 0;
        return c;
    }
    Vec3 d = y.si.p - z.si.p;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return 0;
    const double dist = std::sqrt(d2);
    d /= dist;
    const double fz = z.bsdf->eval({lambda, TransportMode::Radiance}, z.si.to_local(z.si.wo), z.si.to_local(d)) *
                      std::abs(dot(z.si.n, d));
    if (!(fz > 0)) return 0;
    double fy;
    if (s == 1) {
        fy = y.has_normal() ? y.light->le(y.si.p, y.si.n, -d, lambda) * std::abs(dot(y.si.n, d))
                            : y.light->emitted(y.si.p, Vec3(), -d, lambda);
    } else {
        fy = adjoint_f(y, -d, lambda);
    }
    double c = z.beta * fz * fy * y.beta / d2;
    if (!(c > 0)) return 0;
    c *= edge_transmittance(z, d, dist, lambda);
    if (scene.occluded(scene.spawn_ray_to(z.si, y.si.p))) return 0;
    return c;
}

double connect_camera(const Scene& scene, const Vertex& z0, const Vertex& y, double lambda, Vec2* raster) {
    if (!y.connectible() || y.type != VertexType::Surface) return 0;
    double cos_theta = 0;
    if (!z0.pinhole->raster(y.si.p, raster, &cos_theta)) return 0;
    Vec3 d = z0.si.p - y.si.p;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return 0;
    const double dist = std::sqrt(d2);
    d /= dist;
    double c = y.beta * adjoint_f(y, d, lambda) * z0.pinhole->importance(cos_theta) * cos_theta / d2;
    if (!(c > 0)) return 0;
    c *= edge_transmittance(y, d, dist, lambda);
    if (scene.occluded(scene.spawn_ray_to(y.si, z0.si.p))) return 0;
    return c;
}

}  // namespace snell::bdpt
