#pragma once
// Shared by the per-shading-point MNEE tests: a receiver on the floor under a droplet, and a
// running mean with its standard error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/sampler.h"
#include "light/light.h"
#include "scene/scene.h"

namespace snell::test {

/// The floor point below (x, z), reached by tracing straight down from height `from_y` through
/// the droplet; it looks up (wo = +y).
inline SurfaceInteraction droplet_receiver(const Scene& scene, double x, double z, double from_y = 3) {
    Ray r{Vec3(x, from_y, z), Vec3(0, -1, 0), 0, 100};
    SurfaceInteraction si;
    for (int i = 0; i < 4; ++i) {
        EXPECT_TRUE(scene.intersect(r, &si));
        if (!si.bsdf()->is_transmissive()) break;
        r = scene.spawn_ray(si, Vec3(0, -1, 0));
    }
    si.wo = Vec3(0, 1, 0);
    return si;
}

/// One BSDF-sampled path from x_b through refractions only (at most six interfaces) to an
/// emitter: beta * Le at the hero wavelength if `accept(chain, hit)` holds for its refractive
/// vertices and the emitter hit, else 0. An independent estimate of the light MNEE connects.
template <typename Accept>
double refracted_light_sample(const Scene& scene, const SurfaceInteraction& xb, const BSDFContext& ctx, Sampler& smp,
                              Accept accept) {
    const auto bs = xb.bsdf()->sample(ctx, xb.to_local(xb.wo), smp.next_1d(), smp.next_2d());
    if (!bs) return 0;
    double beta = bs->weight[0];
    Ray ray = scene.spawn_ray(xb, xb.to_world(bs->wi));
    std::vector<SurfaceInteraction> chain;
    SurfaceInteraction h;
    for (int d = 0; d < 6 && scene.intersect(ray, &h); ++d) {
        if (h.emitter()) return accept(chain, h) ? beta * h.emitter()->le(h.p, h.n, h.uv, -ray.d, ctx.wl)[0] : 0.0;
        const auto b2 = h.bsdf()->sample(ctx, h.to_local(h.wo), smp.next_1d(), smp.next_2d());
        if (!b2 || !(b2->lobe & kTransmission)) return 0;
        chain.push_back(h);
        beta *= b2->weight[0];
        ray = scene.spawn_ray(h, h.to_world(b2->wi));
    }
    return 0;
}

struct Mean {
    double sum = 0, sq = 0;
    long n = 0;
    void add(double v) { sum += v, sq += v * v, ++n; }
    double mean() const { return sum / double(n); }
    double stderr_() const { return std::sqrt(std::max(0.0, sq / double(n) - sqr(mean())) / double(n)); }
};

}  // namespace snell::test
