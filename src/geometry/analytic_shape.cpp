#include "geometry/analytic_shape.h"

#include <cassert>

#include "geometry/embree_context.h"

namespace snell {
namespace {

void analytic_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* s = static_cast<const AnalyticShape*>(args->geometryUserPtr);
    const Bounds3 b = s->bounds();
    args->bounds_o->lower_x = float(b.lo.x);
    args->bounds_o->lower_y = float(b.lo.y);
    args->bounds_o->lower_z = float(b.lo.z);
    args->bounds_o->upper_x = float(b.hi.x);
    args->bounds_o->upper_y = float(b.hi.y);
    args->bounds_o->upper_z = float(b.hi.z);
}

/// The double ray of the query (in the instance's space when the shape is instanced): from our
/// extended context when present, else the float copy.
Ray query_ray(const RTCIntersectContext* ctx, const RTCRay& r) {
    if (ctx) {
        if (RayContext::from(ctx)->ray) return RayContext::from(ctx)->ray_in(ctx->instID[0]);
    }
    Ray out;
    out.o = {r.org_x, r.org_y, r.org_z};
    out.d = {r.dir_x, r.dir_y, r.dir_z};
    out.tmin = r.tnear;
    out.tmax = r.tfar;
    return out;
}

void analytic_intersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    assert(args->N == 1);
    const auto* s = static_cast<const AnalyticShape*>(args->geometryUserPtr);
    auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
    const Ray ray = query_ray(args->context, rh->ray);
    // Embree's tfar shrinks as closer hits are found; compare against it in double.
    const double t = s->nearest_root(ray, std::max<double>(ray.tmin, rh->ray.tnear), rh->ray.tfar);
    if (t < 0) return;
    const Vec3 n = s->hit_normal(ray, t);
    rh->ray.tfar = float(t);
    rh->hit.Ng_x = float(n.x);
    rh->hit.Ng_y = float(n.y);
    rh->hit.Ng_z = float(n.z);
    rh->hit.u = rh->hit.v = 0;
    rh->hit.primID = args->primID;
    rh->hit.geomID = args->geomID;
    rh->hit.instID[0] = args->context->instID[0];
    if (RayContext* c = RayContext::from(args->context); c->ray) {
        c->t_exact = t;
        c->geom_exact = args->geomID;
        c->inst_exact = args->context->instID[0];
    }
}

void analytic_occluded(const RTCOccludedFunctionNArguments* args) {
    if (!args->valid[0]) return;
    assert(args->N == 1);
    const auto* s = static_cast<const AnalyticShape*>(args->geometryUserPtr);
    auto* r = reinterpret_cast<RTCRay*>(args->ray);
    const Ray ray = query_ray(args->context, *r);
    if (s->nearest_root(ray, std::max<double>(ray.tmin, r->tnear), std::min<double>(ray.tmax, r->tfar)) >= 0)
        r->tfar = -kInfinity;  // Embree's "occluded" marker
}

}  // namespace

unsigned AnalyticShape::attach(RTCDevice device, RTCScene scene) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryUserData(g, this);
    rtcSetGeometryBoundsFunction(g, analytic_bounds, nullptr);
    rtcSetGeometryIntersectFunction(g, analytic_intersect);
    rtcSetGeometryOccludedFunction(g, analytic_occluded);
    rtcCommitGeometry(g);
    m_geom_id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return m_geom_id;
}

}  // namespace snell
