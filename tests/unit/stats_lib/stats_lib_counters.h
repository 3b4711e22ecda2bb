#pragma once
// The library's statistics, as a component's header declares them.
#include "core/stats.h"

namespace snell::stats_lib {

extern StatCounter items;          ///< "stats_lib.items"
extern StatCounter never_counted;  ///< "stats_lib.never_counted": registered, never incremented
extern StatHistogram sizes;        ///< "stats_lib.sizes", 4 bins

}  // namespace snell::stats_lib
