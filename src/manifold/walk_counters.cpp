#include "manifold/walk_counters.h"

namespace snell::walk_counters {

StatCounter walks_started{"mnee.walks_started", "manifold walks started (Alg. 1)"};
StatCounter walks_converged{"mnee.walks_converged", "walks converged to an admissible path, before visibility"};
StatCounter walk_iterations_success{"mnee.walk_iterations_success", "iterations summed over converged walks"};
StatCounter walk_vertex_steps{"mnee.walk_vertex_steps",
                              "vertex projections of all walks (iterations x chain length; a walk's cost)"};
StatCounter walk_fail_no_convergence{"mnee.walk_fail_no_convergence", "walks out of iterations"};
StatCounter walk_fail_singular{"mnee.walk_fail_singular", "walks or Jacobians with a singular matrix"};
StatCounter walk_fail_projection{"mnee.walk_fail_projection", "walks whose projection onto the shapes failed"};
StatCounter walk_fail_scattering{"mnee.walk_fail_scattering",
                                 "walks converged to a reflection or a non-physical refraction"};
StatCounter walk_fail_occluded{"mnee.walk_fail_occluded", "admissible paths blocked"};
StatTimer walk_time{"mnee.walk_time_ns", "time in manifold walks (Alg. 1 and Alg. 2)"};
StatCounter seeds_occluded{"mnee.seeds_occluded", "seed segments blocked by an opaque surface"};
StatCounter seeds_too_many{"mnee.seeds_too_many", "seeds with more refractive vertices than allowed"};
StatCounter seeds_culled{"mnee.seeds_culled", "seeds culled at x_b (Fig. 3 margin)"};
StatHistogram surface_seed_end{
    "mnee.surface_seed_end", "surface seeds by how they ended (ok, missed caster, total internal reflection, too many)",
    4};
StatHistogram solutions_per_connection{"mnee.solutions_per_connection",
                                       "distinct solutions per light connection (solutions=all or unbiased)", 8};
StatCounter bernoulli_loops{"mnee.bernoulli_loops", "geometric 1/p estimates (solutions=unbiased)"};
StatCounter bernoulli_trials{"mnee.bernoulli_trials", "trial counts N of the 1/p estimates, summed"};
StatCounter bernoulli_capped{"mnee.bernoulli_capped", "1/p estimates that reached max_trials"};
StatCounter geometry_clamped{"mnee.geometry_clamped", "connections scaled down by max_geometry"};
StatCounter pdf_walks{"mnee.pdf_walks", "Alg. 2 walks (MIS densities of BSDF-sampled paths)"};
StatCounter pdf_walks_found{"mnee.pdf_walks_found", "Alg. 2 walks that reproduced their input path"};
StatCounter mis_cut_densities{"mnee.mis_cut_densities",
                              "MNEE densities of other techniques' paths mis_cutoff made unnecessary"};
StatCounter mis_cut_counts{"mnee.mis_cut_counts", "surface solutions whose 1 / p estimate mis_cutoff made unnecessary"};
StatCounter mis_cut_solutions{"mnee.mis_cut_solutions", "MNEE solutions mis_cutoff gave no MIS weight"};
StatHistogram iteration_histogram{"mnee.iteration_histogram", "iterations of converged walks", kIterationBins};
StatHistogram walk_end_alg1{"mnee.walk_end_alg1", "Alg. 1 walks by how they ended (WalkEnd)", uint32_t(WalkEnd::Count)};
StatHistogram walk_end_alg2{"mnee.walk_end_alg2", "Alg. 2 walks by how they ended (WalkEnd)", uint32_t(WalkEnd::Count)};
StatHistogram allocation_regions{"mnee.allocation_regions",
                                 "image regions by the connect probability they chose (0, 1/64 .. 1/2, 1)", 8};
StatCounter allocation_regions_without_trials{"mnee.allocation_regions_without_trials",
                                              "image regions connecting without surface trials"};
StatCounter allocation_regions_failed_walk_trials{
    "mnee.allocation_regions_failed_walk_trials",
    "image regions whose surface trials run beside failed straight walks too"};

const char* walk_end_name(WalkEnd e) {
    switch (e) {
        case WalkEnd::Found:
            return "found";
        case WalkEnd::MaxIterations:
            return "max_iterations";
        case WalkEnd::Stalled:
            return "stalled";
        case WalkEnd::Singular:
            return "singular";
        case WalkEnd::ProjectionFailed:
            return "projection_failed";
        case WalkEnd::WrongScattering:
            return "wrong_scattering";
        case WalkEnd::Occluded:
            return "occluded";
        case WalkEnd::Zero:
            return "zero";
        case WalkEnd::OtherSolution:
            return "other_solution";
        case WalkEnd::Count:
            break;
    }
    return "unknown";
}

}  // namespace snell::walk_counters
