#pragma once
// MNEE's statistics (paper Table 1), registered with core/stats.h: walk outcomes by kind,
// iterations and time of the walks, what became of the seeds, Alg. 2 walks. Counted by
// manifold/mnee.cpp and integrators/mnee/; summarised by manifold/walk_statistics.h.
#include "core/stats.h"

namespace snell::walk_counters {

/// Bins of the iteration histogram; the last collects longer walks.
inline constexpr uint32_t kIterationBins = 64;

/// How a manifold walk ended, counting what happens after convergence too: every walk started
/// lands in exactly one bin (a test checks the sums).
enum class WalkEnd : uint32_t {
    Found,             ///< Alg. 1: the path contributes; Alg. 2: the walk reproduced the input path
    MaxIterations,     ///< out of iterations (Sec. 3.4: 15 by default)
    Stalled,           ///< rejected steps shrank the step below min_step
    Singular,          ///< singular constraint matrix, in the walk or in the final Jacobians
    ProjectionFailed,  ///< a vertex could not be brought back onto its shape
    WrongScattering,   ///< Alg. 1: converged to a reflection or a non-physical refraction
    Occluded,          ///< Alg. 1: the admissible path is blocked
    Zero,              ///< Alg. 1: admissible and visible, but the measurement vanishes
    OtherSolution,     ///< Alg. 2: converged to a different path than the input (lines 5-7)
    Count
};
/// Snake-case name of a WalkEnd (stats JSON keys).
const char* walk_end_name(WalkEnd e);

extern StatCounter walks_started;            ///< "mnee.walks_started": Alg. 1 walks
extern StatCounter walks_converged;          ///< converged and admissible (before visibility)
extern StatCounter walk_iterations_success;  ///< iterations summed over converged walks
extern StatCounter walk_vertex_steps;        ///< "mnee.walk_vertex_steps": vertices projected, all walks
extern StatCounter walk_fail_no_convergence;
extern StatCounter walk_fail_singular;
extern StatCounter walk_fail_projection;
extern StatCounter walk_fail_scattering;  ///< converged to a reflection or a non-physical refraction
extern StatCounter walk_fail_occluded;    ///< admissible path blocked
extern StatTimer walk_time;               ///< "mnee.walk_time_ns": in Alg. 1 and Alg. 2 walks
extern StatCounter seeds_occluded;        ///< seed segment blocked by an opaque surface
extern StatCounter seeds_too_many;        ///< seed with more refractive vertices than allowed
extern StatCounter seeds_culled;          ///< seed culled at x_b (Fig. 3 margin)
extern StatHistogram surface_seed_end;    ///< "mnee.surface_seed_end": surface seeds by SurfaceSeedEnd
/// "mnee.solutions_per_connection": distinct solutions per light connection and wavelength
/// solve (bins 0..7, the last collects more), with solutions=all or unbiased.
extern StatHistogram solutions_per_connection;
extern StatCounter bernoulli_loops;   ///< solutions=unbiased: geometric 1/p estimates made
extern StatCounter bernoulli_trials;  ///< ... their counts N summed (mean: E[1/p] over found solutions)
extern StatCounter bernoulli_capped;  ///< ... that reached max_trials
extern StatCounter geometry_clamped;  ///< connections scaled down by max_geometry
extern StatCounter pdf_walks;         ///< Alg. 2 walks (MIS densities of BSDF-sampled paths)
extern StatCounter pdf_walks_found;   ///< ... that reproduced the input path
/// "mnee.mis_cut_densities": MNEE densities of other techniques' paths not computed because
/// mis_cutoff leaves MNEE no share of the path (each saves Alg. 2's walk, where one would run).
extern StatCounter mis_cut_densities;
/// "mnee.mis_cut_counts": surface solutions whose 1 / p estimate mis_cutoff made unnecessary.
extern StatCounter mis_cut_counts;
/// "mnee.mis_cut_solutions": MNEE's solutions dropped by mis_cutoff (weight 0).
extern StatCounter mis_cut_solutions;
extern StatHistogram iteration_histogram;  ///< iterations of converged walks
extern StatHistogram walk_end_alg1;        ///< "mnee.walk_end_alg1": Alg. 1 walks by WalkEnd
extern StatHistogram walk_end_alg2;        ///< "mnee.walk_end_alg2": Alg. 2 walks by WalkEnd
/// "mnee.allocation_regions": image regions by the connect probability they chose
/// (ConnectionAllocation's candidates, bin j: kConnectCandidates[j]).
extern StatHistogram allocation_regions;
/// "mnee.allocation_regions_without_trials": regions with q > 0 that run no surface trials.
extern StatCounter allocation_regions_without_trials;
/// "mnee.allocation_regions_failed_walk_trials": regions with q > 0 whose trials run beside
/// failed straight walks too (ConnectionAllocation's third kind).
extern StatCounter allocation_regions_failed_walk_trials;

/// Counts one ended walk of Alg. 1 (`alg2` false) or Alg. 2.
inline void count_walk_end(bool alg2, WalkEnd e) { (alg2 ? walk_end_alg2 : walk_end_alg1).add(uint32_t(e)); }

}  // namespace snell::walk_counters
