#pragma once
// A static library for test_stats: its statistics are defined in one translation unit
// (stats_lib_counters.cpp) and counted in another (stats_lib_work.cpp), as in
// manifold/walk_counters.{h,cpp}. The test calls do_work() and reads the totals by name only.
#include <cstdint>

namespace snell::stats_lib {

/// Counts `n` work items ("stats_lib.items"), one call ("stats_lib.calls", defined beside
/// this function) and `n` into bin n of "stats_lib.sizes".
void do_work(uint64_t n);

}  // namespace snell::stats_lib
