#pragma once
// Statistics registry (pbrt-v4's STAT_COUNTER idea): a counter is declared where it is counted,
// incremented without atomics on hot paths (each thread owns a block of slots), and summed over
// all threads when a render ends. Declare a statistic at namespace scope in the .cpp of the
// component that counts it, and expose it with `extern` in that component's header:
//
//     extern StatCounter walks_started;          // manifold/walk_counters.h
//     StatCounter walks_started{"mnee.walks_started", "manifold walks started"};  // ... .cpp
//     ++walks_started;                           // anywhere, on any thread
//     stat_totals()[walks_started]               // once the threads have joined, or by name
//     stat_totals().get("mnee.walks_started")    // from code that cannot see the declaration
//
// Names are "<component>.<what>" and global: two statistics declared with the same name, kind and
// size share their slots. A statistic registers when its translation unit's static initialisers
// run, i.e. before main() for every object file the program links; an object file of a static
// library is linked when something references it, which the code that counts always does.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace snell {

enum class StatKind : uint8_t {
    Count,        ///< events (StatCounter)
    Nanoseconds,  ///< accumulated time (StatTimer)
    Histogram,    ///< counts per bin (StatHistogram)
    Moments,      ///< count, sum, sum of squares and maximum of values (StatMoments)
};

/// A registered statistic: where its values live in every thread's block of slots.
struct StatInfo {
    std::string name;         ///< "<component>.<what>", e.g. "mnee.walks_started"
    std::string description;  ///< one line for people
    StatKind kind = StatKind::Count;
    uint32_t offset = 0;  ///< first slot
    uint32_t size = 1;    ///< slots (bins of a histogram, else 1)
};

/// Slots every thread's block holds. Slot 0 is never handed out: a statistic used before its
/// static initialiser ran (initialisation order across translation units) counts there, unseen.
inline constexpr uint32_t kMaxStatSlots = 1024;

namespace detail {
/// Registers a statistic (or finds the one with the same name) and returns its first slot.
/// Aborts when the name is taken by a statistic of another kind or size, or slots run out.
uint32_t register_stat(const char* name, const char* description, StatKind kind, uint32_t size);
/// Gives the calling thread its block of slots (once per thread).
uint64_t* attach_thread();
/// The calling thread's block; constant-initialised, so reading it is one TLS load.
inline thread_local uint64_t* t_stat_slots = nullptr;
inline uint64_t* thread_stat_slots() {
    uint64_t* s = t_stat_slots;
    return s ? s : attach_thread();
}
}  // namespace detail

/// Counts events. `++c` and `c += n` touch the calling thread's slot only.
class StatCounter {
public:
    StatCounter(const char* name, const char* description)
        : m_slot(detail::register_stat(name, description, StatKind::Count, 1)) {}
    StatCounter(const StatCounter&) = delete;
    StatCounter& operator=(const StatCounter&) = delete;
    void operator++() { detail::thread_stat_slots()[m_slot]++; }
    void operator++(int) { detail::thread_stat_slots()[m_slot]++; }
    void operator+=(uint64_t n) { detail::thread_stat_slots()[m_slot] += n; }
    uint32_t slot() const { return m_slot; }
    /// The calling thread's count so far: the difference of two readings is the work one call
    /// did, whatever other threads do (a deterministic cost, unlike a clock).
    uint64_t this_thread() const { return detail::thread_stat_slots()[m_slot]; }

private:
    uint32_t m_slot;
};

/// Accumulates time in nanoseconds (e.g. `t.add_ns(elapsed)`, or a StatTimer::Scope).
class StatTimer {
public:
    StatTimer(const char* name, const char* description)
        : m_slot(detail::register_stat(name, description, StatKind::Nanoseconds, 1)) {}
    StatTimer(const StatTimer&) = delete;
    StatTimer& operator=(const StatTimer&) = delete;
    void add_ns(uint64_t ns) { detail::thread_stat_slots()[m_slot] += ns; }
    uint32_t slot() const { return m_slot; }

private:
    uint32_t m_slot;
};

/// Counts per bin; `add(b)` clamps b to [0, bins - 1], so the last bin collects the rest.
class StatHistogram {
public:
    StatHistogram(const char* name, const char* description, uint32_t bins)
        : m_slot(detail::register_stat(name, description, StatKind::Histogram, bins)), m_bins(bins) {}
    StatHistogram(const StatHistogram&) = delete;
    StatHistogram& operator=(const StatHistogram&) = delete;
    void add(int64_t bin, uint64_t n = 1) {
        const uint32_t b = bin <= 0 ? 0 : bin >= int64_t(m_bins) ? m_bins - 1 : uint32_t(bin);
        detail::thread_stat_slots()[m_slot + b] += n;
    }
    uint32_t slot() const { return m_slot; }
    uint32_t bins() const { return m_bins; }

private:
    uint32_t m_slot;
    uint32_t m_bins;
};

/// The first moments of a stream of values (e.g. the per-sample contributions of one light
/// transport technique): count, sum, sum of squares and maximum. Four slots hold the count
/// and the three doubles' bits; the totals add them as doubles (and take the maximum).
class StatMoments {
public:
    StatMoments(const char* name, const char* description)
        : m_slot(detail::register_stat(name, description, StatKind::Moments, 4)) {}
    StatMoments(const StatMoments&) = delete;
    StatMoments& operator=(const StatMoments&) = delete;
    void add(double x) {
        uint64_t* s = detail::thread_stat_slots() + m_slot;
        s[0]++;
        add_bits(s[1], x);
        add_bits(s[2], x * x);
        if (x > from_bits(s[3])) s[3] = to_bits(x);
    }
    /// add(0), cheaper: a zero changes only the count.
    void add_zero() { detail::thread_stat_slots()[m_slot]++; }
    uint32_t slot() const { return m_slot; }

    static double from_bits(uint64_t b) {
        double d;
        std::memcpy(&d, &b, sizeof d);
        return d;
    }
    static uint64_t to_bits(double d) {
        uint64_t b;
        std::memcpy(&b, &d, sizeof b);
        return b;
    }

private:
    static void add_bits(uint64_t& slot, double x) { slot = to_bits(from_bits(slot) + x); }
    uint32_t m_slot;
};

/// What a StatMoments holds, summed over threads.
struct Moments {
    uint64_t count = 0;
    double sum = 0, sum_sq = 0, max = 0;
    double mean() const { return count ? sum / double(count) : 0.0; }
    /// Variance of one value over the squared mean (the relative variance of a one-sample
    /// estimator); 0 when the mean is 0.
    double relative_variance() const {
        const double m = mean();
        return m != 0 ? std::max(0.0, sum_sq / double(count) - m * m) / (m * m) : 0.0;
    }
};

/// Every statistic registered so far, in registration order.
std::vector<StatInfo> registered_stats();
/// The statistic of that name, if one is registered.
std::optional<StatInfo> find_stat(std::string_view name);

/// A snapshot of every statistic summed over threads. Statistics registered after the
/// snapshot read as zero.
class StatTotals {
public:
    uint64_t operator[](const StatCounter& c) const { return slot(c.slot()); }
    uint64_t operator[](const StatTimer& t) const { return slot(t.slot()); }
    double seconds(const StatTimer& t) const { return double(slot(t.slot())) * 1e-9; }
    /// One value per bin.
    std::vector<uint64_t> bins(const StatHistogram& h) const;
    Moments moments(const StatMoments& m) const { return moments_at(m.slot()); }
    /// The moments of a StatMoments registered as `info`.
    Moments moments(const StatInfo& info) const { return moments_at(info.offset); }
    /// The value of the statistic of that name (a histogram's: the sum of its bins; moments':
    /// the count); 0 when no statistic has that name.
    uint64_t get(std::string_view name) const;
    /// The slots of a statistic (one, or a histogram's bins), zeros past the snapshot.
    std::vector<uint64_t> values(const StatInfo& info) const;
    /// Adds another snapshot slot by slot (e.g. totals over several renders).
    StatTotals& operator+=(const StatTotals& o);

    /// Raw slots, indexed by StatInfo::offset.
    const std::vector<uint64_t>& slots() const { return m_slots; }
    /// A snapshot from raw slots (another process's, issue 27).
    static StatTotals from_slots(std::vector<uint64_t> slots) {
        StatTotals t;
        t.m_slots = std::move(slots);
        return t;
    }

private:
    friend StatTotals stat_totals();
    uint64_t slot(uint32_t i) const { return i < m_slots.size() ? m_slots[i] : 0; }
    Moments moments_at(uint32_t offset) const;
    std::vector<uint64_t> m_slots;
};

/// Sum over all threads since the last reset. Read it once the counting threads have joined
/// (after tbb::parallel_for returns, say); reading during a render gives approximate values.
StatTotals stat_totals();
/// Zeroes every thread's slots (not while other threads are counting).
void reset_stats();

}  // namespace snell
