#include "core/stats.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>

namespace snell {

namespace {

// Own cache lines, so that threads counting in neighbouring blocks do not share one.
struct alignas(64) Block {
    std::array<uint64_t, kMaxStatSlots> slots{};
};

struct Registry {
    std::mutex mutex;
    std::vector<StatInfo> stats;
    uint32_t used = 1;  // slot 0: the unseen slot of statistics not yet registered
    // One block per thread that ever counted. Blocks are never freed: a thread that exits
    // keeps its counts in the totals, and its block stays valid for the thread's pointer.
    std::vector<std::unique_ptr<Block>> blocks;
};

// Never destroyed, so that threads still counting during static destruction find it.
Registry& registry() {
    static Registry* r = new Registry;
    return *r;
}

[[noreturn]] void fail(const char* what, const char* name) {
    std::fprintf(stderr, "snell: statistic '%s': %s\n", name, what);
    std::abort();
}

const StatInfo* find_locked(const Registry& r, std::string_view name) {
    for (const StatInfo& s : r.stats)
        if (s.name == name) return &s;
    return nullptr;
}

}  // namespace

namespace detail {

uint32_t register_stat(const char* name, const char* description, StatKind kind, uint32_t size) {
    if (!name || !*name) fail("empty name", "");
    if (size == 0) fail("a histogram needs at least one bin", name);
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    if (const StatInfo* s = find_locked(r, name)) {
        if (s->kind != kind || s->size != size) fail("declared twice with different kinds or sizes", name);
        return s->offset;
    }
    if (r.used + size > kMaxStatSlots) fail("out of slots (raise kMaxStatSlots in core/stats.h)", name);
    r.stats.push_back({name, description ? description : "", kind, r.used, size});
    r.used += size;
    // Blocks are zeroed when allocated and every slot is zeroed on reset, so the new slots
    // read zero in the blocks of threads that are already counting.
    return r.stats.back().offset;
}

uint64_t* attach_thread() {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    r.blocks.push_back(std::make_unique<Block>());
    t_stat_slots = r.blocks.back()->slots.data();
    return t_stat_slots;
}

}  // namespace detail

std::vector<StatInfo> registered_stats() {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    return r.stats;
}

std::optional<StatInfo> find_stat(std::string_view name) {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    if (const StatInfo* s = find_locked(r, name)) return *s;
    return std::nullopt;
}

std::vector<uint64_t> StatTotals::values(const StatInfo& info) const {
    std::vector<uint64_t> v(info.size);
    for (uint32_t i = 0; i < info.size; ++i) v[i] = slot(info.offset + i);
    return v;
}

std::vector<uint64_t> StatTotals::bins(const StatHistogram& h) const {
    std::vector<uint64_t> v(h.bins());
    for (uint32_t i = 0; i < h.bins(); ++i) v[i] = slot(h.slot() + i);
    return v;
}

uint64_t StatTotals::get(std::string_view name) const {
    const std::optional<StatInfo> s = find_stat(name);
    if (!s) return 0;
    if (s->kind == StatKind::Moments) return slot(s->offset);  // the count
    uint64_t sum = 0;
    for (uint32_t i = 0; i < s->size; ++i) sum += slot(s->offset + i);
    return sum;
}

Moments StatTotals::moments_at(uint32_t offset) const {
    Moments m;
    m.count = slot(offset);
    m.sum = StatMoments::from_bits(slot(offset + 1));
    m.sum_sq = StatMoments::from_bits(slot(offset + 2));
    m.max = StatMoments::from_bits(slot(offset + 3));
    return m;
}

namespace {

// Adds the slots of `from` into `into`: counts add as integers; the doubles of a StatMoments
// (sum, sum of squares) add as doubles and its maximum is the larger one.
void accumulate(const std::vector<StatInfo>& stats, uint64_t* into, const uint64_t* from, uint32_t used) {
    std::vector<bool> moments(used, false);
    for (const StatInfo& s : stats)
        if (s.kind == StatKind::Moments && s.offset + 4 <= used) {
            const uint32_t o = s.offset;
            into[o] += from[o];
            into[o + 1] =
                StatMoments::to_bits(StatMoments::from_bits(into[o + 1]) + StatMoments::from_bits(from[o + 1]));
            into[o + 2] =
                StatMoments::to_bits(StatMoments::from_bits(into[o + 2]) + StatMoments::from_bits(from[o + 2]));
            into[o + 3] = StatMoments::to_bits(
                std::max(StatMoments::from_bits(into[o + 3]), StatMoments::from_bits(from[o + 3])));
            for (uint32_t i = o; i < o + 4; ++i) moments[i] = true;
        }
    for (uint32_t i = 1; i < used; ++i)
        if (!moments[i]) into[i] += from[i];
}

}  // namespace

StatTotals& StatTotals::operator+=(const StatTotals& o) {
    if (m_slots.size() < o.m_slots.size()) m_slots.resize(o.m_slots.size(), 0);
    accumulate(registered_stats(), m_slots.data(), o.m_slots.data(), uint32_t(o.m_slots.size()));
    return *this;
}

StatTotals stat_totals() {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    StatTotals t;
    t.m_slots.assign(r.used, 0);
    for (const auto& b : r.blocks) accumulate(r.stats, t.m_slots.data(), b->slots.data(), r.used);
    return t;
}

void reset_stats() {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    for (const auto& b : r.blocks) std::fill(b->slots.begin(), b->slots.end(), 0);
}

}  // namespace snell
