#pragma once
// Extended Embree intersection context (internal to the geometry module). Embree hands the
// context pointer to user-geometry callbacks unchanged, so appending fields after the
// RTCIntersectContext lets the analytic sphere see the *double* ray instead of the float
// copy inside RTCRayHit (the Embree tutorials' "context extension" idiom).
#include <embree3/rtcore.h>

#include <vector>

#include "core/transform.h"
#include "core/vector.h"

namespace snell {

struct RayContext {
    RTCIntersectContext ctx;   ///< must stay the first member
    const Ray* ray = nullptr;  ///< the query in double precision
    /// Exact ray distance of the last user-geometry hit accepted, and its geometry id; the
    /// float tfar Embree keeps is only used to order hits.
    double t_exact = 0;
    unsigned geom_exact = RTC_INVALID_GEOMETRY_ID;
    unsigned inst_exact = RTC_INVALID_GEOMETRY_ID;  ///< the instance it was found in, if any
    /// Per instance geometry id, the transform into its group's space (instanced analytic shapes
    /// intersect the double ray carried there); nullptr entries for other geometry.
    const std::vector<const Transform*>* inst_to_local = nullptr;

    explicit RayContext(const Ray& r, const std::vector<const Transform*>* to_local = nullptr)
        : ray(&r), inst_to_local(to_local) {
        rtcInitIntersectContext(&ctx);
    }
    /// The double ray in the space of the instance `inst_id` (the world ray for none).
    Ray ray_in(unsigned inst_id) const {
        if (inst_id == RTC_INVALID_GEOMETRY_ID || !inst_to_local || inst_id >= inst_to_local->size() ||
            !(*inst_to_local)[inst_id])
            return *ray;
        const Transform& t = *(*inst_to_local)[inst_id];
        Ray r = *ray;
        r.o = t.point(ray->o);
        r.d = t.vector(ray->d);
        return r;
    }
    static const RayContext* from(const RTCIntersectContext* c) { return reinterpret_cast<const RayContext*>(c); }
    static RayContext* from(RTCIntersectContext* c) { return reinterpret_cast<RayContext*>(c); }
};

}  // namespace snell
