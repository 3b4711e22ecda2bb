#pragma once
// Extended Embree intersection context (internal to the geometry module). Embree hands the
// context pointer to user-geometry callbacks unchanged, so appending fields after the
// RTCIntersectContext lets the analytic sphere see the *double* ray instead of the float
// copy inside RTCRayHit (the Embree tutorials' "context extension" idiom).
#include <embree3/rtcore.h>

#include "core/vector.h"

namespace snell {

struct RayContext {
    RTCIntersectContext ctx;   ///< must stay the first member
    const Ray* ray = nullptr;  ///< the query in double precision
    /// Exact ray distance of the last user-geometry hit accepted, and its geometry id; the
    /// float tfar Embree keeps is only used to order hits.
    double t_exact = 0;
    unsigned geom_exact = RTC_INVALID_GEOMETRY_ID;

    explicit RayContext(const Ray& r) : ray(&r) { rtcInitIntersectContext(&ctx); }
    static const RayContext* from(const RTCIntersectContext* c) { return reinterpret_cast<const RayContext*>(c); }
    static RayContext* from(RTCIntersectContext* c) { return reinterpret_cast<RayContext*>(c); }
};

}  // namespace snell
