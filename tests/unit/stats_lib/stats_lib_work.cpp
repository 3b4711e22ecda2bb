#include "stats_lib.h"
#include "stats_lib_counters.h"

namespace snell::stats_lib {

namespace {
StatCounter calls{"stats_lib.calls", "calls of do_work()"};
}  // namespace

void do_work(uint64_t n) {
    ++calls;
    items += n;
    sizes.add(int64_t(n), n);
}

}  // namespace snell::stats_lib
