#pragma once
#include <embree3/rtcore.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "core/stats.h"
#include "geometry/instance.h"
#include "geometry/interaction.h"
#include "geometry/shape.h"
#include "light/light.h"
#include "light/light_sampler.h"
#include "scene/light_bounds.h"

namespace snell {

// Ray queries, counted by Scene::intersect() and Scene::occluded() (core/stats.h).
namespace scene_stats {
extern StatCounter rays;         ///< "scene.rays": closest-hit queries
extern StatCounter shadow_rays;  ///< "scene.shadow_rays": any-hit queries
/// "scene.untraceable_rays": rays beyond what Embree represents, answered without tracing
extern StatCounter untraceable_rays;
}  // namespace scene_stats

/// Scene::build's refusal of an instance whose transform carries the scene's rays out of the
/// range Embree traces in (its index among the instances added, for the loader to locate).
struct InstanceRangeError : std::runtime_error {
    InstanceRangeError(size_t i, const std::string& what) : std::runtime_error(what), index(i) {}
    size_t index;
};

/// The scene: shapes in an Embree BVH, lights and their sampler, the camera.
/// Ray offsets come from each point's own rounding error (Shape::position_error, as pbrt-v4's
/// OffsetRayOrigin), never from the scene's size: a scene scaled by 1e-4 or 1e4 renders the
/// same, and a giant object far away does not change how rays leave the others.
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

    /// Ray leaving `si` in direction d, its origin offset by surface_offset(si) to the side of
    /// the geometric normal that d points to.
    Ray spawn_ray(const SurfaceInteraction& si, const Vec3& d) const;
    /// Shadow ray from `si` (offset as spawn_ray) to `target`, stopping short of it by the
    /// larger of `target_error` (the target's own rounding bound) and a relative
    /// kShadowEpsilon of the distance (pbrt-v4's ShadowEpsilon).
    Ray spawn_ray_to(const SurfaceInteraction& si, const Vec3& target, double target_error = 0) const;
    /// Shadow ray between two surface points, each end kept clear of its own surface.
    Ray spawn_ray_to(const SurfaceInteraction& si, const SurfaceInteraction& target) const {
        return spawn_ray_to(si, target.p, surface_offset(target));
    }
    /// How far a ray origin at `si` must move off its surface: the point's rounding-error bound
    /// (its shape's, or its own coordinates' for a point without one).
    static double surface_offset(const SurfaceInteraction& si);
    /// Rounding bound of a bare point (a vertex of unknown surface, a light position).
    static double point_offset(const Vec3& p) { return kFloatPositionError * max_abs_component(p); }
    /// tmin for a ray cast from a bare point `o` towards something about `dist` away.
    static double ray_tmin(const Vec3& o, double dist) { return point_offset(o) + kShadowEpsilon * dist; }
    /// Relative shortening of shadow rays (pbrt-v4's ShadowEpsilon).
    static constexpr double kShadowEpsilon = 1e-4;
    /// Radius of the bounding sphere of all shapes.
    double scene_radius() const { return m_radius; }
    const Bounds3& bounds() const { return m_bounds; }

    const std::vector<std::shared_ptr<Shape>>& shapes() const { return m_shapes; }
    const std::vector<std::shared_ptr<Light>>& lights() const { return m_lights; }
    /// Lights with a direction-only domain (envmap, constant, directional) reached by escaping rays.
    const std::vector<const Light*>& infinite_lights() const { return m_infinite; }
    /// Whether any light is a delta light (point, spot, directional), which BSDF sampling cannot hit.
    bool has_delta_lights() const { return m_has_delta_lights; }
    /// Spheres holding the shapes that refract light (BSDF::is_refractive_interface at 550 nm,
    /// emitters excluded): caster sampling's cones (scene/caster_sampling.h).
    const std::vector<BoundingSphere>& refractive_casters() const { return m_refractive_casters; }
    /// The shapes a manifold chain can lie on at some wavelength (not emitters; transmissive,
    /// smooth or microfacet BSDF), in shapes()' order. Whether at a given wavelength:
    /// is_manifold_interface (the IOR may be 1 there). Built once, so that the surface trials of
    /// each connection visit the glass alone, not every shape of a large scene.
    const std::vector<const Shape*>& manifold_casters() const { return m_manifold_casters; }
    /// Their bounding spheres, in the same order (CasterChoice's solid angles).
    const std::vector<BoundingSphere>& manifold_caster_bounds() const { return m_manifold_caster_bounds; }
    /// Where the lights are, for caster sampling's shadow test. Environments are left out where
    /// the other lights outshine them (by Light::power); empty where they do not, or where there
    /// are more than CasterSampling::kMaxLights.
    const std::vector<LightBounds>& bounded_lights() const { return m_bounded_lights; }
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
    bool m_has_delta_lights = false;
    std::vector<BoundingSphere> m_refractive_casters;
    std::vector<const Shape*> m_manifold_casters;
    std::vector<BoundingSphere> m_manifold_caster_bounds;
    std::vector<LightBounds> m_bounded_lights;
    LightSampler m_light_sampler;
    std::shared_ptr<Camera> m_camera;
    Bounds3 m_bounds;
    double m_radius = 1;
};

}  // namespace snell
