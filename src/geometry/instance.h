#pragma once
// Mitsuba's `shapegroup` and `instance` through Embree instancing: a ShapeGroup's shapes sit in
// their own Embree scene, built once; each Instance places that scene with a transform (one
// Embree instance geometry, the group's BVH shared). Every (instance, shape) pair is an
// InstancedShape, the Shape the rest of the renderer sees at a hit: its differential geometry,
// closest-point projection (MNEE's walk) and area samples are the group shape's, carried to world
// space by the instance transform.
#include <memory>
#include <vector>

#include "core/transform.h"
#include "geometry/shape.h"

namespace snell {

class ShapeGroup {
public:
    explicit ShapeGroup(std::vector<std::shared_ptr<Shape>> shapes) : m_shapes(std::move(shapes)) {}
    ~ShapeGroup();
    ShapeGroup(const ShapeGroup&) = delete;
    ShapeGroup& operator=(const ShapeGroup&) = delete;

    /// The group's committed Embree scene on `device` (built on first call).
    RTCScene scene(RTCDevice device);
    const std::vector<std::shared_ptr<Shape>>& shapes() const { return m_shapes; }
    /// The group shape of an Embree geometry id inside the group's scene.
    const Shape* shape_of(unsigned geom_id) const {
        return geom_id < m_by_geom_id.size() ? m_by_geom_id[geom_id] : nullptr;
    }
    Bounds3 bounds() const;

private:
    std::vector<std::shared_ptr<Shape>> m_shapes;
    std::vector<const Shape*> m_by_geom_id;
    RTCScene m_scene = nullptr;
};

/// One shape of a group, placed by an instance's transform.
class InstancedShape final : public Shape {
public:
    InstancedShape(const Shape& base, const Transform& to_world);

    /// Not attached on its own: the Instance's Embree geometry carries it.
    unsigned attach(RTCDevice, RTCScene) override { return RTC_INVALID_GEOMETRY_ID; }
    Bounds3 bounds() const override;
    /// Exact for rigid motions and uniform scales; otherwise the area of the transformed
    /// tangent planes at the group shape's uniform samples would be needed (see area.cpp).
    double area() const override { return m_base.area() * m_area_scale; }
    /// The placed shape's bound, computed once: the default would transform the base shape's
    /// box on every ray spawned from it.
    double position_error(const SurfaceInteraction& /*si*/) const override { return m_position_error; }
    void compute_interaction(const Ray& ray, double t, uint32_t prim, const Vec2& uv,
                             SurfaceInteraction* si) const override;
    /// The group shape's closest point to the point carried into its space, carried back: exact
    /// for rigid motions and uniform scales, a smooth projection onto the surface otherwise.
    bool closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const override;
    ShapeSample sample_area(const Vec2& u) const override;
    /// The group shape's shape operator (exact at a sphere's poles too), carried by the transform.
    Vec3 normal_derivative(const SurfaceInteraction& si, const Vec3& tangent) const override;
    /// The group shape's attribute at the point carried into the group's space.
    int attribute(const std::string& name, const SurfaceInteraction& si, double* out) const override {
        SurfaceInteraction local = si;
        local.p = m_to_local.point(si.p);
        return m_base.attribute(name, local, out);
    }
    std::vector<std::string> attribute_names() const override { return m_base.attribute_names(); }

    const Shape& base() const { return m_base; }
    /// Carries a hit or projection on the group shape to world space (si->shape becomes this).
    void to_world(SurfaceInteraction* si) const;

private:
    const Shape& m_base;
    Transform m_to_world, m_to_local;
    double m_area_scale, m_length_scale;  ///< |det|^(2/3), largest stretch of to_local
    double m_position_error = 0;          ///< shape_position_error(), fixed at construction
};

/// `<shape type="instance">`: a group placed in the scene.
class Instance {
public:
    Instance(std::shared_ptr<ShapeGroup> group, const Transform& to_world);

    /// Attaches the Embree instance geometry; returns its id in `scene`.
    unsigned attach(RTCDevice device, RTCScene scene);
    const Transform& to_world() const { return m_to_world; }
    const Transform& to_local() const { return m_to_local; }
    /// The placed shape hit through geometry `geom_id` of the group's scene.
    const InstancedShape* shape_of(unsigned geom_id) const;
    const std::vector<std::shared_ptr<InstancedShape>>& shapes() const { return m_shapes; }

private:
    std::shared_ptr<ShapeGroup> m_group;
    Transform m_to_world, m_to_local;
    std::vector<std::shared_ptr<InstancedShape>> m_shapes;  // in the group's order
    std::vector<const InstancedShape*> m_by_group_geom_id;
};

}  // namespace snell
