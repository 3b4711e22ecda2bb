// The statistics registry (core/stats.h): per-thread counts sum over threads, reset zeroes
// them, statistics are found by handle and by name, and those of a static library's
// translation units are registered although the reading code never names them.
#include <gtest/gtest.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "core/stats.h"
#include "unit/stats_lib/stats_lib.h"

using namespace snell;

namespace {

StatCounter g_events{"test.events", "events counted by the tests"};
StatCounter g_events_again{"test.events", "the same statistic, declared twice"};
StatTimer g_time{"test.time_ns", "time counted by the tests"};
StatHistogram g_bins{"test.bins", "a histogram", 5};

}  // namespace

TEST(Stats, ParallelForSumsEveryThreadsCounts) {
    reset_stats();
    constexpr int n = 200000;
    // Every chunk waits (boundedly) until two threads have joined, so that more than one counts.
    const int want = std::min(2, tbb::this_task_arena::max_concurrency());
    std::atomic<int> joined{0};
    tbb::enumerable_thread_specific<int> used(0);
    tbb::parallel_for(tbb::blocked_range<int>(0, n, n / 64), [&](const tbb::blocked_range<int>& r) {
        if (!used.local()) {
            used.local() = 1;
            joined++;
        }
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (joined < want && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        for (int i = r.begin(); i < r.end(); ++i) {
            ++g_events;
            g_time.add_ns(uint64_t(i % 3));
            g_bins.add(i % 7);  // 5 and 6 land in the last bin
        }
    });
    const StatTotals t = stat_totals();
    EXPECT_EQ(t[g_events], uint64_t(n));
    uint64_t time = 0;
    for (int i = 0; i < n; ++i) time += uint64_t(i % 3);
    EXPECT_EQ(t[g_time], time);
    EXPECT_DOUBLE_EQ(t.seconds(g_time), double(time) * 1e-9);
    std::vector<uint64_t> bins(5, 0);
    for (int i = 0; i < n; ++i) bins[size_t(std::min(i % 7, 4))]++;
    EXPECT_EQ(t.bins(g_bins), bins);
    EXPECT_GE(joined, want);
}

// Counts of threads that have exited stay in the totals.
TEST(Stats, ExitedThreadsKeepTheirCounts) {
    reset_stats();
    std::vector<std::thread> threads;
    for (int k = 1; k <= 4; ++k)
        threads.emplace_back([k] {
            for (int i = 0; i < 1000 * k; ++i) ++g_events;
        });
    for (std::thread& th : threads) th.join();
    EXPECT_EQ(stat_totals()[g_events], 10000u);
}

TEST(Stats, ResetZeroesEveryThread) {
    tbb::parallel_for(0, 1000, [](int) { ++g_events; });
    g_bins.add(2, 3);
    EXPECT_GE(stat_totals()[g_events], 1000u);
    reset_stats();
    const StatTotals t = stat_totals();
    EXPECT_EQ(t[g_events], 0u);
    EXPECT_EQ(t.bins(g_bins), std::vector<uint64_t>(5, 0));
    ++g_events;
    EXPECT_EQ(stat_totals()[g_events], 1u);
}

TEST(Stats, NamesFindTheSameSlots) {
    reset_stats();
    ++g_events;
    ++g_events_again;  // same name, kind and size: one statistic
    g_bins.add(-3);    // clamped to the first bin
    g_bins.add(99);    // and to the last
    const StatTotals t = stat_totals();
    EXPECT_EQ(g_events.slot(), g_events_again.slot());
    EXPECT_EQ(t[g_events], 2u);
    EXPECT_EQ(t.get("test.events"), 2u);
    EXPECT_EQ(t.get("test.bins"), 2u);  // a histogram's name reads the sum of its bins
    EXPECT_EQ(t.bins(g_bins), (std::vector<uint64_t>{1, 0, 0, 0, 1}));
    EXPECT_EQ(t.get("test.no_such_statistic"), 0u);
    EXPECT_FALSE(find_stat("test.no_such_statistic"));
    const std::optional<StatInfo> info = find_stat("test.bins");
    ASSERT_TRUE(info);
    EXPECT_EQ(info->kind, StatKind::Histogram);
    EXPECT_EQ(info->size, 5u);
    EXPECT_EQ(info->offset, g_bins.slot());
    EXPECT_EQ(info->description, "a histogram");
    EXPECT_EQ(t.values(*info), t.bins(g_bins));
    EXPECT_EQ(find_stat("test.time_ns")->kind, StatKind::Nanoseconds);
    // Registration order, no overlaps, slot 0 never handed out.
    uint32_t next = 1;
    for (const StatInfo& s : registered_stats()) {
        EXPECT_EQ(s.offset, next) << s.name;
        next += s.size;
    }
}

// The static library's statistics live in a translation unit this test never references (only
// do_work(), in another one, does): they are registered all the same and read by name.
TEST(Stats, StaticLibraryCountersAreRegistered) {
    EXPECT_TRUE(find_stat("stats_lib.never_counted"));
    reset_stats();
    tbb::parallel_for(1, 4, [](int i) { stats_lib::do_work(uint64_t(i)); });
    const StatTotals t = stat_totals();
    EXPECT_EQ(t.get("stats_lib.calls"), 3u);
    EXPECT_EQ(t.get("stats_lib.items"), 6u);
    EXPECT_EQ(t.get("stats_lib.never_counted"), 0u);
    const std::optional<StatInfo> sizes = find_stat("stats_lib.sizes");
    ASSERT_TRUE(sizes);
    EXPECT_EQ(t.values(*sizes), (std::vector<uint64_t>{0, 1, 2, 3}));
}

// A statistic registered while threads already hold their blocks (here: lazily, on first use)
// counts from zero on every thread.
TEST(Stats, LateRegistration) {
    tbb::parallel_for(0, 100, [](int) { ++g_events; });  // every worker has its block
    const StatTotals before = stat_totals();
    static StatCounter late{"test.late", "registered after threads started counting"};
    tbb::parallel_for(0, 500, [](int) { ++late; });
    const StatTotals t = stat_totals();
    EXPECT_EQ(t[late], 500u);
    EXPECT_EQ(before[late], 0u);  // past the older snapshot: zero
    StatTotals sum = before;
    sum += t;
    EXPECT_EQ(sum[late], 500u);
    EXPECT_EQ(sum[g_events], before[g_events] + t[g_events]);
}

namespace {
StatMoments g_moments{"test.moments", "values whose moments the tests check"};
}  // namespace

// Moments add as doubles over threads (not as the integers other statistics are): count, mean,
// relative variance and maximum of values drawn on several threads equal those computed in one.
TEST(Stats, MomentsOfValuesFromSeveralThreads) {
    reset_stats();
    constexpr int n = 100000;
    tbb::parallel_for(tbb::blocked_range<int>(0, n, n / 64), [&](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i < r.end(); ++i) g_moments.add(i % 10 == 0 ? 10.0 + 0.001 * i : 0.5);
    });
    double sum = 0, sum_sq = 0, max = 0;
    for (int i = 0; i < n; ++i) {
        const double x = i % 10 == 0 ? 10.0 + 0.001 * i : 0.5;
        sum += x;
        sum_sq += x * x;
        max = std::max(max, x);
    }
    const StatTotals t = stat_totals();
    const Moments m = t.moments(g_moments);
    EXPECT_EQ(m.count, uint64_t(n));
    EXPECT_NEAR(m.mean(), sum / n, 1e-12 * sum / n);
    const double mean = sum / n, relvar = (sum_sq / n - mean * mean) / (mean * mean);
    EXPECT_NEAR(m.relative_variance(), relvar, 1e-9 * relvar);
    EXPECT_EQ(m.max, max);
    EXPECT_EQ(t.get("test.moments"), uint64_t(n)) << "by name: the count";

    // Two snapshots add as moments too.
    StatTotals twice = t;
    twice += t;
    const Moments m2 = twice.moments(g_moments);
    EXPECT_EQ(m2.count, uint64_t(2 * n));
    EXPECT_NEAR(m2.mean(), m.mean(), 1e-12 * m.mean());
    EXPECT_EQ(m2.max, max);
    EXPECT_EQ(Moments().relative_variance(), 0.0);
}
