#pragma once
// MNEE's view of every light as a point x_c (paper Alg. 1, line 1). Area lights give points in
// area measure; point and spot lights a fixed point (delta); lights at infinity (environment,
// constant, directional) become points on a sphere around x_b so far away (relative to the
// scene) that the direction of the chain's last segment is the light direction to 1e-6 rad:
// their solid-angle densities become area densities over distance^2, and a directional light's
// irradiance becomes the intensity of a point at that distance.
#include <optional>

#include "core/vector.h"
#include "light/light.h"

namespace snell {

class Scene;

struct LightPoint {
    Vec3 p, n;           ///< position and normal (facing the scene for far points)
    Vec2 uv;             ///< surface coordinates on an area light (its texture reads them)
    double pdf = 0;      ///< area density of p, or 1 for delta positions
    bool delta = false;  ///< position (point, spot) or direction (directional) is a delta
    double p_error = 0;  ///< rounding bound of p on an area light (LightSample::p_error)
};

/// Radius of the far sphere for lights at infinity.
double far_light_distance(const Scene& scene);

/// The light point of an NEE light sample drawn at `ref`.
LightPoint light_point(const Scene& scene, const Light& light, const LightSample& ls, const Vec3& ref);

/// The light point a path reaching light along unit direction d from `from` ends on (for
/// lights at infinity: on the far sphere around `center`, where MNEE would have put it).
LightPoint light_point_hit(const Scene& scene, const Light& light, const Vec3& p, const Vec3& n, const Vec2& uv,
                           const Vec3& d, const Vec3& center);

/// Density (area measure; 1 for delta lights) with which NEE from `ref` yields light point p.
double light_point_pdf(const Scene& scene, const Light& light, const Vec3& ref, const Vec3& p, const Vec3& n);

/// Emission from light point p (normal n) along unit w (away from the light): radiance, or
/// intensity for delta lights. `center` is the far sphere's centre (x_b).
SampledSpectrum light_point_emission(const Light& light, const LightPoint& lp, const Vec3& w, const Vec3& center,
                                     const SampledWavelengths& wl);

}  // namespace snell
