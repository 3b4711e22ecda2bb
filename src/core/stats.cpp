#include "core/stats.h"

#include <tbb/enumerable_thread_specific.h>

namespace snell {

namespace {
tbb::enumerable_thread_specific<Counters>& registry() {
    static tbb::enumerable_thread_specific<Counters> r;
    return r;
}
}  // namespace

Counters& thread_counters() {
    // enumerable_thread_specific::local() hashes the thread id into a table on every call,
    // which showed at ~2% of a path-traced render (one call per ray). Its elements never move
    // and the registry is never cleared (reset assigns), so each thread keeps its pointer.
    thread_local Counters* local = &registry().local();
    return *local;
}

Counters total_counters() {
    Counters sum;
    for (const Counters& c : registry()) sum += c;
    return sum;
}

void reset_counters() {
    for (Counters& c : registry()) c = Counters();
}

}  // namespace snell
