#include "geometry/instance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace snell {

namespace {

Bounds3 transform_bounds(const Transform& t, const Bounds3& b) {
    Bounds3 out;
    if (!b.valid()) return out;
    for (int k = 0; k < 8; ++k)
        out.expand(t.point(Vec3(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z)));
    return out;
}

/// Largest factor by which `t` stretches a vector (its 3x3 block's largest singular value,
/// bounded by the Frobenius norm).
double max_stretch(const Transform& t) {
    double s = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s += t.matrix()[size_t(i)][size_t(j)] * t.matrix()[size_t(i)][size_t(j)];
    return std::sqrt(s);
}

}  // namespace

ShapeGroup::~ShapeGroup() {
    if (m_scene) rtcReleaseScene(m_scene);
}

RTCScene ShapeGroup::scene(RTCDevice device) {
    if (m_scene) return m_scene;
    m_scene = rtcNewScene(device);
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
    for (const auto& s : m_shapes) {
        const unsigned id = s->attach(device, m_scene);
        if (id >= m_by_geom_id.size()) m_by_geom_id.resize(id + 1, nullptr);
        m_by_geom_id[id] = s.get();
    }
    rtcCommitScene(m_scene);
    return m_scene;
}

Bounds3 ShapeGroup::bounds() const {
    Bounds3 b;
    for (const auto& s : m_shapes) b.expand(s->bounds());
    return b;
}

InstancedShape::InstancedShape(const Shape& base, const Transform& to_world)
    : m_base(base),
      m_to_world(to_world),
      m_to_local(to_world.inverse()),
      m_area_scale(std::pow(std::abs(to_world.det3()), 2.0 / 3.0)),
      m_length_scale(max_stretch(to_world.inverse())) {
    m_bsdf = base.bsdf_ptr();
    m_position_error = shape_position_error();
}

Bounds3 InstancedShape::bounds() const { return transform_bounds(m_to_world, m_base.bounds()); }

void InstancedShape::to_world(SurfaceInteraction* si) const {
    const Transform& M = m_to_world;
    si->p = M.point(si->p);
    si->dpdu = M.vector(si->dpdu);
    si->dpdv = M.vector(si->dpdv);
    // Normals go with the inverse transpose N (which keeps them outward, mirrors included); the
    // unit normal's derivative is the tangential part of N dn over |N n|.
    const Vec3 Nn = M.normal(si->n), Nng = M.normal(si->ng);
    const double len = length(Nn);
    const Vec3 n = Nn / len;
    auto carry = [&](const Vec3& dn) {
        const Vec3 v = M.normal(dn) / len;
        return v - n * dot(n, v);
    };
    si->dndu = carry(si->dndu);
    si->dndv = carry(si->dndv);
    si->n = n;
    si->ng = normalize(Nng);
    si->shading = Frame::from_normal_tangent(si->n, si->dpdu);
    si->shape = this;
}

void InstancedShape::compute_interaction(const Ray& ray, double t, uint32_t prim, const Vec2& uv,
                                         SurfaceInteraction* si) const {
    // The ray in the group's space, direction not renormalised: the same t reaches the same point.
    Ray local = ray;
    local.o = m_to_local.point(ray.o);
    local.d = m_to_local.vector(ray.d);
    m_base.compute_interaction(local, t, prim, uv, si);
    to_world(si);
    si->t = t;
    si->wo = -normalize(ray.d);
}

bool InstancedShape::closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const {
    if (!m_base.closest_point(m_to_local.point(p), radius * m_length_scale, si)) return false;
    to_world(si);
    return true;
}

Vec3 InstancedShape::normal_derivative(const SurfaceInteraction& si, const Vec3& tangent) const {
    // The same point on the group shape, its derivative along the tangent carried back
    // (M^-1 t is tangent there), then n_w = N n / |N n| differentiated: (I - n_w n_w^T) N dn / |N n|.
    SurfaceInteraction local;
    const Vec3 pl = m_to_local.point(si.p);
    if (!m_base.closest_point(pl, 1e-6 * (1.0 + length(pl)), &local)) return Shape::normal_derivative(si, tangent);
    const Vec3 dn = m_base.normal_derivative(local, m_to_local.vector(tangent));
    const Vec3 Nn = m_to_world.normal(local.n);
    const double len = length(Nn);
    const Vec3 n = Nn / len, v = m_to_world.normal(dn) / len;
    return v - n * dot(n, v);
}

ShapeSample InstancedShape::sample_area(const Vec2& u) const {
    ShapeSample s = m_base.sample_area(u);
    // The density changes by the ratio of the tangent plane's areas, read at the sample.
    SurfaceInteraction si;
    double ratio = 1.0 / m_area_scale;
    if (m_base.closest_point(s.p, 1e-6 * (1 + length(s.p)), &si)) {
        const double a = length(cross(si.dpdu, si.dpdv));
        const double b = length(cross(m_to_world.vector(si.dpdu), m_to_world.vector(si.dpdv)));
        if (a > 0 && b > 0) ratio = a / b;
    }
    s.p = m_to_world.point(s.p);
    s.n = normalize(m_to_world.normal(s.n));
    s.pdf *= ratio;
    s.p_error = -1;  // the base shape's bound was in its own space
    return s;
}

Instance::Instance(std::shared_ptr<ShapeGroup> group, const Transform& to_world)
    : m_group(std::move(group)), m_to_world(to_world), m_to_local(to_world.inverse()) {
    for (const auto& s : m_group->shapes()) m_shapes.push_back(std::make_shared<InstancedShape>(*s, to_world));
}

unsigned Instance::attach(RTCDevice device, RTCScene scene) {
    RTCScene group_scene = m_group->scene(device);
    m_by_group_geom_id.clear();
    for (size_t i = 0; i < m_group->shapes().size(); ++i) {
        const unsigned id = m_group->shapes()[i]->geom_id();
        if (id >= m_by_group_geom_id.size()) m_by_group_geom_id.resize(id + 1, nullptr);
        m_by_group_geom_id[id] = m_shapes[i].get();
    }
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, group_scene);
    rtcSetGeometryTimeStepCount(g, 1);
    float xfm[12];  // 3 x 4, column major
    const auto& m = m_to_world.matrix();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) xfm[c * 3 + r] = float(m[size_t(r)][size_t(c)]);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return id;
}

const InstancedShape* Instance::shape_of(unsigned geom_id) const {
    return geom_id < m_by_group_geom_id.size() ? m_by_group_geom_id[geom_id] : nullptr;
}

}  // namespace snell
