#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "bsdf/bsdf.h"
#include "geometry/embree_context.h"
#include "light/directional.h"
#include "light/light.h"
#include "scene/caster_sampling.h"

namespace snell {

namespace scene_stats {
StatCounter rays{"scene.rays", "closest-hit ray queries"};
StatCounter shadow_rays{"scene.shadow_rays", "any-hit (visibility) ray queries"};
StatCounter untraceable_rays{"scene.untraceable_rays",
                             "rays Embree cannot represent (origin beyond 1.8e18 or not finite), not traced"};
}  // namespace scene_stats

namespace {

// Embree intersects in float and asserts that a ray's origin lies within +-1.844e18 and its
// direction is finite (RayK::valid(), FLT_LARGE), aborting the process otherwise. Lights at
// infinity become points 1e6 scene radii away (manifold/light_point.h), so the scene itself
// must stay within 1e12 of the origin, well inside that limit.
constexpr double kEmbreeMaxOrigin = 1.8e18;
constexpr double kMaxSceneCoordinate = 1e12;

bool embree_can_trace(const Ray& r) {
    return max_abs_component(r.o) < kEmbreeMaxOrigin && std::isfinite(r.d.x) && std::isfinite(r.d.y) &&
           std::isfinite(r.d.z) && !std::isnan(r.tmin) && !std::isnan(r.tmax);
}

std::string coordinate_error(const char* what, double extent) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "%s reaches %.3g from the origin; snell handles coordinates up to %.0e (Embree traces rays in "
                  "single precision; scale the scene down or move it nearer the origin)",
                  what, extent, kMaxSceneCoordinate);
    return buf;
}

void embree_error(void*, RTCError code, const char* msg) {
    std::fprintf(stderr, "embree error %d: %s\n", int(code), msg ? msg : "");
}

void to_embree(const Ray& r, RTCRay& e) {
    e.org_x = float(r.o.x);
    e.org_y = float(r.o.y);
    e.org_z = float(r.o.z);
    e.dir_x = float(r.d.x);
    e.dir_y = float(r.d.y);
    e.dir_z = float(r.d.z);
    e.tnear = float(std::max(0.0, r.tmin));
    e.tfar = float(r.tmax);
    e.time = 0;
    e.mask = 0xFFFFFFFFu;
    e.id = 0;
    e.flags = 0;
}

}  // namespace

Scene::Scene() {
    m_device = rtcNewDevice(nullptr);
    if (!m_device) throw std::runtime_error("cannot create Embree device");
    rtcSetDeviceErrorFunction(m_device, embree_error, nullptr);
    m_scene = rtcNewScene(m_device);
    // Robust mode: Embree avoids optimisations that lose accuracy at triangle edges, so rays
    // through shared edges and vertices (closed meshes, glass) are not missed.
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
}

Scene::~Scene() {
    if (m_scene) rtcReleaseScene(m_scene);
    if (m_device) rtcReleaseDevice(m_device);
}

void Scene::add_shape(std::shared_ptr<Shape> shape) { m_shapes.push_back(std::move(shape)); }
void Scene::add_instance(std::shared_ptr<Instance> instance) { m_instances.push_back(std::move(instance)); }
void Scene::add_light(std::shared_ptr<Light> light) { m_lights.push_back(std::move(light)); }

void Scene::build() {
    m_bounds = Bounds3();
    for (const auto& s : m_shapes) {
        // Its uv only where a texture of its BSDF or emitter reads it; a bare shape keeps it.
        const BSDF* bsdf = s->bsdf();
        const Light* emitter = s->emitter();
        s->set_reads_uv((!bsdf && !emitter) || (bsdf && bsdf->reads_uv()) || (emitter && emitter->reads_uv()));
        const unsigned id = s->attach(m_device, m_scene);
        if (id >= m_by_geom_id.size()) m_by_geom_id.resize(id + 1, nullptr);
        m_by_geom_id[id] = s.get();
        m_bounds.expand(s->bounds());
    }
    // Instances: one Embree instance geometry each; their placed shapes join shapes().
    for (const auto& inst : m_instances) {
        const unsigned id = inst->attach(m_device, m_scene);
        if (id >= m_instance_by_geom_id.size()) {
            m_instance_by_geom_id.resize(id + 1, nullptr);
            m_inst_to_local.resize(id + 1, nullptr);
        }
        m_instance_by_geom_id[id] = inst.get();
        m_inst_to_local[id] = &inst->to_local();
        for (const auto& s : inst->shapes()) {
            m_shapes.push_back(s);
            m_bounds.expand(s->bounds());
        }
    }
    // Checked before Embree builds its float BVH over these bounds.
    if (!m_shapes.empty()) {
        const double extent = std::max(max_abs_component(m_bounds.lo), max_abs_component(m_bounds.hi));
        const bool finite = std::isfinite(length_squared(m_bounds.lo) + length_squared(m_bounds.hi));
        if (!finite || !(extent <= kMaxSceneCoordinate))
            throw std::runtime_error(coordinate_error("the scene's geometry", extent));
    }
    Bounds3 reach = m_bounds;  // where rays start: the geometry and the sensor
    if (m_camera) {
        const Vec3 eye = m_camera->to_world().point(Vec3(0, 0, 0));
        const double cam = max_abs_component(eye);
        if (!(cam <= kMaxSceneCoordinate)) throw std::runtime_error(coordinate_error("the sensor's position", cam));
        reach.expand(eye);
    }
    // Embree traces an instance's rays in its group's space: the composed transform must keep
    // them in range there too (issue 30: an instance scaled by 1e-20 passed the world-space
    // check and its rays, 1e20 times longer, made Embree abort). Affine: the box's corners bound it.
    if (reach.valid())
        for (size_t i = 0; i < m_instances.size(); ++i) {
            const Transform& to_local = m_instances[i]->to_local();
            double local = 0;
            for (int c = 0; c < 8; ++c) {
                const Vec3 corner(c & 1 ? reach.hi.x : reach.lo.x, c & 2 ? reach.hi.y : reach.lo.y,
                                  c & 4 ? reach.hi.z : reach.lo.z);
                local = std::max(local, max_abs_component(to_local.point(corner)));
            }
            if (!(local <= kMaxSceneCoordinate)) {
                char buf[320];
                std::snprintf(buf, sizeof buf,
                              "the instance's to_world carries the scene (and its rays) to %.3g from the origin of "
                              "its shapegroup's space; snell traces up to %.0e there (scale the instance less "
                              "extremely, or scale its shapes instead)",
                              local, kMaxSceneCoordinate);
                throw InstanceRangeError(i, buf);
            }
        }
    rtcCommitScene(m_scene);
    if (rtcGetDeviceError(m_device) != RTC_ERROR_NONE) throw std::runtime_error("Embree failed to build the scene");

    if (!m_bounds.valid()) m_bounds.expand(Vec3(0, 0, 0));  // empty scene
    m_radius = 0.5 * length(m_bounds.extent());
    if (!(m_radius > 0)) m_radius = 1;

    m_infinite.clear();
    m_has_delta_lights = false;
    for (const auto& l : m_lights) {
        l->preprocess(m_bounds);
        if (l->is_infinite()) m_infinite.push_back(l.get());
        m_has_delta_lights = m_has_delta_lights || l->is_delta();
    }
    m_light_sampler = LightSampler(m_lights);
    m_refractive_casters.clear();
    m_manifold_casters.clear();
    m_manifold_caster_bounds.clear();
    for (const auto& s : m_shapes) {
        const BSDF* b = s->emitter() ? nullptr : s->bsdf();
        if (!b || !b->is_transmissive() || !(b->has_delta() || b->has_microfacet())) continue;
        m_manifold_casters.push_back(s.get());
        m_manifold_caster_bounds.push_back(s->bounding_sphere());
        if (b->is_refractive_interface(550.0)) m_refractive_casters.push_back(s->bounding_sphere());
    }
    m_bounded_lights.clear();
    double bounded_power = 0, environment_power = 0;
    for (const auto& l : m_lights) {
        if (const auto* d = dynamic_cast<const DirectionalLight*>(l.get()))
            m_bounded_lights.push_back(LightBounds::towards(-d->direction()));
        else if (l->shape())
            m_bounded_lights.push_back(LightBounds::around(l->shape()->bounding_sphere()));
        else if (l->kind() == LightKind::Point || l->kind() == LightKind::Spot || l->kind() == LightKind::Projector)
            m_bounded_lights.push_back(LightBounds::around({l->position(), 0.0}));
        else {  // an environment: light from every direction
            environment_power += l->power();
            continue;
        }
        bounded_power += l->power();
    }
    // A dim environment (an ambient fill) leaves the shadow test to the other lights; one that
    // outshines them lights every point through every caster.
    if (environment_power > bounded_power) m_bounded_lights.clear();
    if (m_bounded_lights.size() > CasterSampling::kMaxLights) m_bounded_lights.clear();
}

bool Scene::intersect(const Ray& ray, SurfaceInteraction* si) const {
    if (!embree_can_trace(ray)) {  // never for a validated scene; counted, never a crash
        ++scene_stats::untraceable_rays;
        return false;
    }
    RayContext ctx(ray, &m_inst_to_local);
    RTCRayHit rh;
    to_embree(ray, rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_scene, &ctx.ctx, &rh);
    ++scene_stats::rays;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    // Analytic shapes report their exact double t through the context.
    const unsigned inst = rh.hit.instID[0];
    const double t = ctx.geom_exact == rh.hit.geomID && ctx.inst_exact == inst ? ctx.t_exact : double(rh.ray.tfar);
    const Shape* shape = inst == RTC_INVALID_GEOMETRY_ID ? m_by_geom_id[rh.hit.geomID]
                                                         : m_instance_by_geom_id[inst]->shape_of(rh.hit.geomID);
    // Fills wo as well (-normalize(ray.d)); normalising it a second time here cost a square
    // root and three divisions per hit.
    shape->compute_interaction(ray, t, rh.hit.primID, Vec2(rh.hit.u, rh.hit.v), si);
    return true;
}

bool Scene::occluded(const Ray& ray) const {
    if (!embree_can_trace(ray)) {
        ++scene_stats::untraceable_rays;
        return true;
    }
    RayContext ctx(ray, &m_inst_to_local);
    RTCRay r;
    to_embree(ray, r);
    rtcOccluded1(m_scene, &ctx.ctx, &r);
    ++scene_stats::shadow_rays;
    return r.tfar < 0;  // Embree sets tfar = -inf on any hit
}

double Scene::surface_offset(const SurfaceInteraction& si) {
    const double own = point_offset(si.p);
    return si.shape ? std::max(own, si.shape->position_error(si)) : own;
}

Ray Scene::spawn_ray(const SurfaceInteraction& si, const Vec3& d) const {
    const double off = surface_offset(si);
    Ray r;
    r.o = si.p + si.ng * (dot(d, si.ng) >= 0 ? off : -off);
    r.d = d;
    r.tmin = 0;
    r.tmax = kInfinity;
    return r;
}

Ray Scene::spawn_ray_to(const SurfaceInteraction& si, const Vec3& target, double target_error) const {
    const double off = surface_offset(si);
    Ray r;
    r.o = si.p + si.ng * (dot(target - si.p, si.ng) >= 0 ? off : -off);
    Vec3 d = target - r.o;
    const double dist = length(d);
    r.d = dist > 0 ? d / dist : si.ng;
    r.tmin = 0;
    const double short_by = std::max({kShadowEpsilon * dist, target_error, point_offset(target)});
    r.tmax = std::max(0.0, dist - short_by);
    return r;
}

}  // namespace snell
