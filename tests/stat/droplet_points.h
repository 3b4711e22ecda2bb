#pragma once
// Shared by the per-shading-point MNEE tests: a receiver on the floor under a droplet, and a
// running mean with its standard error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

struct Mean {
    double sum = 0, sq = 0;
    long n = 0;
    void add(double v) { sum += v, sq += v * v, ++n; }
    double mean() const { return sum / double(n); }
    double stderr_() const { return std::sqrt(std::max(0.0, sq / double(n) - sqr(mean())) / double(n)); }
};

}  // namespace snell::test
