#pragma once
// Shapes intersected analytically in double precision, as Embree user geometries (the sphere,
// the cylinder). They supply the nearest root of a ray and a geometric normal at it; the Embree
// callbacks (bounds, intersect, occluded) are shared.
#include "geometry/shape.h"

namespace snell {

class AnalyticShape : public Shape {
public:
    unsigned attach(RTCDevice device, RTCScene scene) final;
    /// The nearest ray parameter in (tnear, tfar) where the (double) ray meets the shape, or a
    /// negative value.
    virtual double nearest_root(const Ray& ray, double tnear, double tfar) const = 0;
    /// An (unnormalised) geometric normal at the hit ray.at(t), as Embree reports it.
    virtual Vec3 hit_normal(const Ray& ray, double t) const = 0;
};

}  // namespace snell
