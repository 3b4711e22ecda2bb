#include "core/stats.h"

#include <tbb/enumerable_thread_specific.h>

namespace snell {

namespace {
tbb::enumerable_thread_specific<Counters>& registry() {
    static tbb::enumerable_thread_specific<Counters> r;
    return r;
}
}  // namespace

Counters& thread_counters() { return registry().local(); }

Counters total_counters() {
    Counters sum;
    for (const Counters& c : registry()) sum += c;
    return sum;
}

void reset_counters() {
    for (Counters& c : registry()) c = Counters();
}

}  // namespace snell
