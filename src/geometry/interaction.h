#pragma once
#include <cstdint>

#include "core/frame.h"
#include "core/vector.h"

namespace snell {

class Shape;
class BSDF;
class Light;

/// A point on a surface with its full differential geometry. MNEE needs exactly this at
/// every vertex (paper Sec. 3.4: the constraint derivatives A_i, B_i, C_i use dp/du, dp/dv,
/// dn/du, dn/dv), so every hit and every closest-point projection fills all of it.
struct SurfaceInteraction {
    Vec3 p;           ///< position
    double t = 0;     ///< ray distance (0 for projections and samples)
    Vec3 ng;          ///< unit geometric normal, on the shape's outward side
    Vec3 n;           ///< unit shading normal (interpolated for smooth meshes), same side as ng
    Vec3 dpdu, dpdv;  ///< position derivatives w.r.t. the surface parameters (u, v)
    Vec3 dndu, dndv;  ///< derivatives of the *unit* shading normal n w.r.t. (u, v)
    Vec2 uv;          ///< surface parameters (sphere: (phi/2pi, theta/pi); mesh: texture or barycentric)
    Frame shading;    ///< from_normal_tangent(n, dpdu): consistent over the surface
    Vec3 wo;          ///< unit direction back towards the previous vertex (world), if any
    const Shape* shape = nullptr;
    uint32_t prim = 0;  ///< triangle index for meshes

    Vec3 to_local(const Vec3& w) const { return shading.to_local(w); }
    Vec3 to_world(const Vec3& w) const { return shading.to_world(w); }
    const BSDF* bsdf() const;
    const Light* emitter() const;
};

}  // namespace snell
