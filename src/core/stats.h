#pragma once
// Per-thread event counters (pbrt-v4's STAT_COUNTER idea): incremented without atomics on
// hot paths, summed when a render ends.
#include <cstdint>

namespace snell {

struct Counters {
    uint64_t rays = 0;                ///< closest-hit queries
    uint64_t shadow_rays = 0;         ///< any-hit queries
    uint64_t paths = 0;               ///< camera paths traced
    uint64_t discarded_nan = 0;       ///< samples dropped because they were NaN
    uint64_t discarded_inf = 0;       ///< samples dropped because they were infinite
    uint64_t discarded_negative = 0;  ///< samples dropped because they were negative

    // Manifold walks (MNEE, paper Table 1): outcomes by kind, iterations, time.
    static constexpr int kIterationBins = 64;  ///< histogram of iterations of successful walks
    uint64_t walks_started = 0;
    uint64_t walks_converged = 0;          ///< converged and admissible (before visibility)
    uint64_t walk_iterations_success = 0;  ///< summed over converged walks
    uint64_t walk_fail_no_convergence = 0;
    uint64_t walk_fail_singular = 0;
    uint64_t walk_fail_projection = 0;
    uint64_t walk_fail_scattering = 0;  ///< converged to a reflection or a non-physical refraction
    uint64_t walk_fail_occluded = 0;    ///< admissible path blocked
    uint64_t walk_time_ns = 0;
    uint64_t seeds_occluded = 0;   ///< seed segment blocked by an opaque surface
    uint64_t seeds_too_many = 0;   ///< seed with more refractive vertices than allowed
    uint64_t seeds_culled = 0;     ///< seed culled at x_b (Fig. 3 margin)
    uint64_t pdf_walks = 0;        ///< Alg. 2 walks (MIS densities of BSDF-sampled paths)
    uint64_t pdf_walks_found = 0;  ///< ... that reproduced the input path
    uint64_t iteration_histogram[kIterationBins] = {};

    Counters& operator+=(const Counters& o) {
        walks_started += o.walks_started;
        walks_converged += o.walks_converged;
        walk_iterations_success += o.walk_iterations_success;
        walk_fail_no_convergence += o.walk_fail_no_convergence;
        walk_fail_singular += o.walk_fail_singular;
        walk_fail_projection += o.walk_fail_projection;
        walk_fail_scattering += o.walk_fail_scattering;
        walk_fail_occluded += o.walk_fail_occluded;
        walk_time_ns += o.walk_time_ns;
        seeds_occluded += o.seeds_occluded;
        seeds_too_many += o.seeds_too_many;
        seeds_culled += o.seeds_culled;
        pdf_walks += o.pdf_walks;
        pdf_walks_found += o.pdf_walks_found;
        for (int i = 0; i < kIterationBins; ++i) iteration_histogram[i] += o.iteration_histogram[i];
        rays += o.rays;
        shadow_rays += o.shadow_rays;
        paths += o.paths;
        discarded_nan += o.discarded_nan;
        discarded_inf += o.discarded_inf;
        discarded_negative += o.discarded_negative;
        return *this;
    }
};

/// The calling thread's counters.
Counters& thread_counters();
/// Sum over all threads since the last reset.
Counters total_counters();
void reset_counters();

}  // namespace snell
