#pragma once
#include <embree3/rtcore.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/object.h"
#include "core/vector.h"
#include "geometry/interaction.h"

namespace snell {

class BSDF;
class Light;

/// Bound on the rounding error of a surface point, per unit of the coordinate magnitudes it
/// was computed from. Embree stores vertices and intersects in float (unit roundoff 2^-24)
/// and its watertight test loses a few ulps more; 32 ulps clears that with margin. Used like
/// pbrt-v4's error bounds (OffsetRayOrigin): a ray leaves a surface point offset by its own
/// error, which depends on that point's geometry and never on the size of the whole scene.
constexpr double kFloatPositionError = 32.0 * 0x1.0p-24;

/// A point sampled on a shape, with its density.
struct ShapeSample {
    Vec3 p;
    Vec3 n;          ///< unit (shading-side) normal at p
    double pdf = 0;  ///< area measure for sample_area; solid angle for sample_from
    Vec2 uv;         ///< surface parameterisation at p (textured emitters read it)
    /// Bound on the rounding error of p (Shape::position_error); negative: the shape's default.
    double p_error = -1;
};

/// A sphere that holds a shape (caster sampling's cones, scene/caster_sampling.h).
struct BoundingSphere {
    Vec3 center;
    double radius = 0;
};

/// Interface of a geometric primitive (sphere, triangle mesh). Shapes own their BSDF and,
/// if emissive, their area light.
class Shape : public Object {
public:
    /// Registers the primitive with the Embree scene, returns its geometry id.
    virtual unsigned attach(RTCDevice device, RTCScene scene) = 0;
    virtual Bounds3 bounds() const = 0;
    /// A sphere holding the shape. Default: the one through the corners of bounds(); spheres
    /// and meshes give tighter ones.
    virtual BoundingSphere bounding_sphere() const {
        const Bounds3 b = bounds();
        return {b.center(), 0.5 * length(b.extent())};
    }
    virtual double area() const = 0;
    /// Distance within which the computed position of `si` (a point of this shape) may lie
    /// off the true surface, as Embree sees it. Default: shape_position_error(); meshes use
    /// the hit triangle's vertices.
    virtual double position_error(const SurfaceInteraction& /*si*/) const { return shape_position_error(); }
    /// The same bound for any point of the shape: from its coordinates' largest magnitude.
    double shape_position_error() const {
        const Bounds3 b = bounds();
        return kFloatPositionError * std::max(max_abs_component(b.lo), max_abs_component(b.hi));
    }

    /// Fills `si` from an Embree hit on primitive `prim` at barycentrics/parameters `uv`
    /// (as Embree reports them) at ray distance t. Full differential geometry, ng and n
    /// pointing to the shape's outside (flipped when `flip_normals` is set), and
    /// wo = -normalize(ray.d).
    virtual void compute_interaction(const Ray& ray, double t, uint32_t prim, const Vec2& uv,
                                     SurfaceInteraction* si) const = 0;

    /// Closest point on *this* shape to p (the manifold walk's projection, paper Sec. 3.4),
    /// with full differential geometry. Spheres are exact; meshes use an Embree point query
    /// restricted to this shape. Returns false if none is found within `radius`.
    virtual bool closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const = 0;
    /// The same for a point displaced from `near`, a point on this shape: meshes first try the
    /// primitive `near` lies on (the manifold walk's small steps mostly stay over it), and
    /// query the whole shape only where p does not project into that primitive's interior.
    virtual bool closest_point_near(const SurfaceInteraction& near, const Vec3& p, double radius,
                                    SurfaceInteraction* si) const {
        (void)near;
        return closest_point(p, radius, si);
    }

    /// Uniform sample in area measure (pdf = 1/area).
    virtual ShapeSample sample_area(const Vec2& u) const = 0;
    /// Sample as seen from `ref`; pdf in solid angle at ref. Default: area sampling converted;
    /// spheres sample the visible cone.
    virtual std::optional<ShapeSample> sample_from(const Vec3& ref, const Vec2& u) const;
    /// Solid-angle density of sample_from producing point p (normal n) seen from ref.
    virtual double pdf_from(const Vec3& ref, const Vec3& p, const Vec3& n) const;

    /// Derivative of the unit shading normal along a unit tangent direction at `si` (the
    /// shape operator applied to `tangent`). Default: from dn/du, dn/dv by expressing the
    /// tangent in the (dp/du, dp/dv) basis; shapes with degenerate parametrisations (sphere
    /// poles) override it with an exact form.
    virtual Vec3 normal_derivative(const SurfaceInteraction& si, const Vec3& tangent) const {
        const double g11 = dot(si.dpdu, si.dpdu), g12 = dot(si.dpdu, si.dpdv), g22 = dot(si.dpdv, si.dpdv);
        const double det = g11 * g22 - g12 * g12;
        if (!(std::abs(det) > 1e-30 * (g11 * g22 + 1e-300))) return Vec3();
        const double r1 = dot(si.dpdu, tangent), r2 = dot(si.dpdv, tangent);
        const double a = (g22 * r1 - g12 * r2) / det, b = (g11 * r2 - g12 * r1) / det;
        return si.dndu * a + si.dndv * b;
    }

    /// Mitsuba's mesh attributes (`mesh_attribute` textures): the value of the attribute `name`
    /// ("vertex_color", "face_weight", ...) at si, interpolated over the triangle for vertex
    /// attributes; its channel count (1 or 3), or 0 when the shape has no such attribute.
    virtual int attribute(const std::string& /*name*/, const SurfaceInteraction& /*si*/, double* /*out*/) const {
        return 0;
    }
    /// The names of the shape's attributes (for error messages).
    virtual std::vector<std::string> attribute_names() const { return {}; }

    const BSDF* bsdf() const { return m_bsdf.get(); }
    const std::shared_ptr<BSDF>& bsdf_ptr() const { return m_bsdf; }
    const Light* emitter() const { return m_emitter; }
    void set_bsdf(std::shared_ptr<BSDF> b) { m_bsdf = std::move(b); }
    void set_emitter(const Light* l) { m_emitter = l; }
    /// Whether anything evaluated at the shape's points reads their uv: its BSDF's or its
    /// emitter's textures. Shapes whose uv costs work (Sphere: two atan2, at every projection of
    /// a walk onto it; docs/experiments.md, twenty-seventh measurement) skip it where nothing
    /// does, and leave uv at (0, 0). True unless Scene::build() finds that nothing does.
    bool reads_uv() const { return m_reads_uv; }
    void set_reads_uv(bool reads) { m_reads_uv = reads; }
    unsigned geom_id() const { return m_geom_id; }

protected:
    std::shared_ptr<BSDF> m_bsdf;
    const Light* m_emitter = nullptr;
    unsigned m_geom_id = RTC_INVALID_GEOMETRY_ID;
    bool m_reads_uv = true;
};

inline const BSDF* SurfaceInteraction::bsdf() const { return shape ? shape->bsdf() : nullptr; }
inline const Light* SurfaceInteraction::emitter() const { return shape ? shape->emitter() : nullptr; }

}  // namespace snell
