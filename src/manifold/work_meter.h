#pragma once
// Work counted, not timed, for choices that must not depend on the machine or on the threads
// (ConnectionAllocation): ray queries plus the walks' vertex projections, each worth
// kWalkStepWork ray queries.
#include "manifold/walk_counters.h"
#include "scene/scene.h"

namespace snell {

/// One vertex projection of a manifold walk (a closest-point query, the constraint blocks and
/// their share of the block-tridiagonal solve) in ray queries: their thread times per count are
/// alike on the caustic gallery (measured in docs/mnee.md, "Where the walks pay").
inline constexpr double kWalkStepWork = 1.0;

/// The calling thread's work so far: the difference of two readings is what the code between
/// them did.
inline double work_so_far() {
    return double(scene_stats::rays.this_thread() + scene_stats::shadow_rays.this_thread()) +
           kWalkStepWork * double(walk_counters::walk_vertex_steps.this_thread());
}

}  // namespace snell
