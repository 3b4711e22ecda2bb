#pragma once
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "camera/camera.h"
#include "core/stats.h"
#include "geometry/instance.h"
#include "geometry/interaction.h"
#include "geometry/shape.h"
#include "light/light.h"
#include "light/light_sampler.h"

namespace snell {

// Ray queries, counted by Scene::intersect() and Scene::occluded() (core/stats.h).
namespace scene_stats {
extern StatCounter rays;         ///< "scene.rays": closest-hit queries
extern StatCounter shadow_rays;  ///< "scene.shadow_rays": any-hit queries
}  // namespace scene_stats

/// The scene: shapes in an Embree BVH, lights and their sampler, the camera.
/// Tolerances (ray offsets, projection radii) are relative to the scene's size
/// (project promise 5): a scene scaled by 1000 behaves identically.
class Scene {
public:
    Scene();
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    void add_shape(std::shared_ptr<Shape> shape);
    /// A placed shape group (Mitsuba's `instance`); its shapes join shapes() at build().
    void add_instance(std::shared_ptr<Instance> instance);
    void add_light(std::shared_ptr<Light> light);
    void set_camera(std::shared_ptr<Camera> cam) { m_camera = std::move(cam); }
    /// Builds the BVH, preprocesses lights, builds the light sampler. Call once after adding.
    void build();

    /// Closest hit along the ray within (tmin, tmax); fills full differential geometry.
    bool intersect(const Ray& ray, SurfaceInteraction* si) const;
    /// Any hit within (tmin, tmax).
    bool occluded(const Ray& ray) const;
    /// Closest point on `shape` to p within `radius` (manifold walk projection, Sec. 3.4).
    bool closest_point(const Shape& shape, const Vec3& p, double radius, SurfaceInteraction* si) const {
        return shape.closest_point(p, radius, si);
    }

    /// Ray leaving `si` in direction d, offset to the side of the geometric normal d points to.
    Ray spawn_ray(const SurfaceInteraction& si, const Vec3& d) const;
    /// Shadow ray from `si` to point `target`, shortened at both ends by the scene epsilon.
    Ray spawn_ray_to(const SurfaceInteraction& si, const Vec3& target) const;
    /// Offset distance for ray origins: a small multiple of the scene's extent.
    double ray_epsilon() const { return m_eps; }
    /// Radius of the bounding sphere of all shapes.
    double scene_radius() const { return m_radius; }
    const Bounds3& bounds() const { return m_bounds; }

    const std::vector<std::shared_ptr<Shape>>& shapes() const { return m_shapes; }
    const std::vector<std::shared_ptr<Light>>& lights() const { return m_lights; }
    /// Lights with a direction-only domain (envmap, constant, directional) reached by escaping rays.
    const std::vector<const Light*>& infinite_lights() const { return m_infinite; }
    const LightSampler& light_sampler() const { return m_light_sampler; }
    const Camera* camera() const { return m_camera.get(); }
    RTCDevice device() const { return m_device; }
    /// The committed Embree scene (for benchmarks that measure Embree's raw rate).
    RTCScene rtc_scene() const { return m_scene; }

private:
    RTCDevice m_device = nullptr;
    RTCScene m_scene = nullptr;
    std::vector<std::shared_ptr<Shape>> m_shapes;
    std::vector<const Shape*> m_by_geom_id;
    std::vector<std::shared_ptr<Instance>> m_instances;
    std::vector<const Instance*> m_instance_by_geom_id;
    std::vector<const Transform*> m_inst_to_local;  // per instance geometry id (analytic shapes)
    std::vector<std::shared_ptr<Light>> m_lights;
    std::vector<const Light*> m_infinite;
    LightSampler m_light_sampler;
    std::shared_ptr<Camera> m_camera;
    Bounds3 m_bounds;
    double m_radius = 1, m_eps = 1e-5;
};

}  // namespace snell
