#pragma once
// Where a light is, for caster sampling's shadow test (scene/caster_sampling.h): built once per
// light in Scene::build.
#include "core/vector.h"
#include "geometry/shape.h"

namespace snell {

/// A light seen from any point: a sphere holding it (radius 0 for a light at a point), or the
/// direction towards a directional light.
struct LightBounds {
    BoundingSphere sphere;
    Vec3 direction;  ///< towards the light, where `directional`
    bool directional = false;

    static LightBounds around(const BoundingSphere& s) { return {s, Vec3(), false}; }
    static LightBounds towards(const Vec3& d) { return {BoundingSphere(), d, true}; }
};

}  // namespace snell
