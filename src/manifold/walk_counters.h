#pragma once
// MNEE's statistics (paper Table 1), registered with core/stats.h: walk outcomes by kind,
// iterations and time of the walks, what became of the seeds, Alg. 2 walks. Counted by
// manifold/mnee.cpp and integrators/mnee/; summarised by manifold/walk_statistics.h.
#include "core/stats.h"

namespace snell::walk_counters {

/// Bins of the iteration histogram; the last collects longer walks.
inline constexpr uint32_t kIterationBins = 64;

extern StatCounter walks_started;            ///< "mnee.walks_started": Alg. 1 walks
extern StatCounter walks_converged;          ///< converged and admissible (before visibility)
extern StatCounter walk_iterations_success;  ///< iterations summed over converged walks
extern StatCounter walk_fail_no_convergence;
extern StatCounter walk_fail_singular;
extern StatCounter walk_fail_projection;
extern StatCounter walk_fail_scattering;   ///< converged to a reflection or a non-physical refraction
extern StatCounter walk_fail_occluded;     ///< admissible path blocked
extern StatTimer walk_time;                ///< "mnee.walk_time_ns": in Alg. 1 and Alg. 2 walks
extern StatCounter seeds_occluded;         ///< seed segment blocked by an opaque surface
extern StatCounter seeds_too_many;         ///< seed with more refractive vertices than allowed
extern StatCounter seeds_culled;           ///< seed culled at x_b (Fig. 3 margin)
extern StatCounter pdf_walks;              ///< Alg. 2 walks (MIS densities of BSDF-sampled paths)
extern StatCounter pdf_walks_found;        ///< ... that reproduced the input path
extern StatHistogram iteration_histogram;  ///< iterations of converged walks

}  // namespace snell::walk_counters
