#pragma once
#include "core/vector.h"

namespace snell {

/// Bounding sphere of the scene, kept by infinite and directional lights to place their
/// far-away sample points and to estimate their power. Defaults to the unit sphere until
/// Light::preprocess supplies the scene bounds (as in Mitsuba).
struct SceneSphere {
    Vec3 center{0, 0, 0};
    double radius = 1;

    void set(const Bounds3& b) {
        if (!b.valid()) return;
        center = b.center();
        radius = 0.5 * length(b.extent());
        if (!(radius > 0)) radius = 1;  // a single point: keep a usable scale
    }
    /// Distance from p at which a point along any direction is surely outside the scene:
    /// twice the larger of the radius and p's distance from the centre.
    double far_distance(const Vec3& p) const { return 2 * std::max(radius, length(p - center)); }
};

}  // namespace snell
