#pragma once
// Per-thread event counters (pbrt-v4's STAT_COUNTER idea): incremented without atomics on
// hot paths, summed when a render ends.
#include <cstdint>

namespace snell {

struct Counters {
    uint64_t rays = 0;           ///< closest-hit queries
    uint64_t shadow_rays = 0;    ///< any-hit queries
    uint64_t paths = 0;          ///< camera paths traced
    uint64_t discarded_nan = 0;  ///< samples dropped because they were NaN
    uint64_t discarded_inf = 0;  ///< samples dropped because they were infinite
    uint64_t discarded_negative = 0;  ///< samples dropped because they were negative

    Counters& operator+=(const Counters& o) {
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
