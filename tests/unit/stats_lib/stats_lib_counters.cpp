#include "stats_lib_counters.h"

namespace snell::stats_lib {

StatCounter items{"stats_lib.items", "work items done"};
StatCounter never_counted{"stats_lib.never_counted", "a statistic nobody increments"};
StatHistogram sizes{"stats_lib.sizes", "work items per call", 4};

}  // namespace snell::stats_lib
