// The work split every render loop shares (render/team_pass.h, issue 27): a pass hands every
// item to exactly one thread once, stops when told, reports work cut short; a bootstrap
// computes each value on one process only and gives every process all of them.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "render/team_pass.h"

using namespace snell;

namespace {

// Rank `rank` of a team of `size` whose other processes hold zeros: sum_exactly leaves the
// values as they are, as if the others contributed nothing (team_bootstrap's split shows).
class SplitTeam final : public RenderTeam {
public:
    SplitTeam(int rank, int size) : m_rank(rank), m_size(size) {}
    int rank() const override { return m_rank; }
    int size() const override { return m_size; }
    void begin_pass(int64_t tiles, int threads, std::function<bool()> stop) override {
        m_local.begin_pass(tiles, threads, std::move(stop));
    }
    WorkGrant next_tile() override { return m_local.next_tile(); }
    WorkGrant end_pass(bool* complete) override { return m_local.end_pass(complete); }
    void sum_exactly(std::vector<double>& /*values*/) override {}
    bool any(bool local) override { return local; }
    void reduce(Film& /*film*/, StatTotals& /*stats*/) override {}
    [[noreturn]] void fail(const std::string& message, int /*exit_code*/) override {
        throw std::runtime_error(message);
    }

private:
    int m_rank, m_size;
    LocalTeam m_local;
};

}  // namespace

TEST(RunTeamPass, EveryItemRunsOnceOnOneSlot) {
    LocalTeam team;
    const int threads = 4;
    tbb::task_arena arena(threads);
    std::vector<std::atomic<int>> runs(1000);
    std::atomic<int> bad_slot{0};
    int groups = 0;
    const PassOutcome o = run_team_pass(
        team, arena, threads, int64_t(runs.size()), [] { return false; }, 64,
        [&](int64_t item, int slot) {
            if (slot < 0 || slot >= threads) ++bad_slot;
            ++runs[size_t(item)];
            return true;
        },
        [&] { ++groups; });
    EXPECT_TRUE(o.complete);
    EXPECT_FALSE(o.stop);
    EXPECT_EQ(bad_slot.load(), 0);
    for (size_t i = 0; i < runs.size(); ++i) ASSERT_EQ(runs[i].load(), 1) << "item " << i;
    EXPECT_GE(groups, 1000 / 64);  // the group hook runs between groups of 64 items
}

TEST(RunTeamPass, AStopEndsThePassIncomplete) {
    LocalTeam team;
    tbb::task_arena arena(2);
    std::atomic<int> ran{0};
    const PassOutcome o = run_team_pass(
        team, arena, 2, 1000, [&] { return ran.load() >= 10; }, SIZE_MAX,
        [&](int64_t, int) {
            ++ran;
            return true;
        });
    EXPECT_FALSE(o.complete);
    EXPECT_TRUE(o.stop);
    EXPECT_LT(ran.load(), 1000);
}

TEST(RunTeamPass, WorkCutShortMakesThePassIncomplete) {
    LocalTeam team;
    tbb::task_arena arena(1);
    const PassOutcome o = run_team_pass(
        team, arena, 1, 100, [] { return false; }, SIZE_MAX, [](int64_t item, int) { return item != 5; });
    EXPECT_FALSE(o.complete);
    EXPECT_FALSE(o.stop);
}

TEST(TeamBootstrap, OneProcessComputesEveryValueOnce) {
    LocalTeam team;
    tbb::task_arena arena(3);
    std::vector<std::atomic<int>> calls(777);
    const std::vector<double> v = team_bootstrap(team, arena, calls.size(), [&](size_t i) {
        ++calls[i];
        return 0.5 * double(i) + 1;
    });
    ASSERT_EQ(v.size(), calls.size());
    for (size_t i = 0; i < v.size(); ++i) {
        EXPECT_EQ(calls[i].load(), 1);
        EXPECT_EQ(v[i], 0.5 * double(i) + 1);
    }
}

TEST(TeamBootstrap, EachRankComputesItsIndicesAlone) {
    // Rank r of 3 computes indices r, r + 3, ...; the others are zero until summed over the team.
    tbb::task_arena arena(2);
    for (int rank = 0; rank < 3; ++rank) {
        SplitTeam team(rank, 3);
        for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(10)}) {
            const std::vector<double> v = team_bootstrap(team, arena, n, [](size_t i) { return double(i) + 1; });
            ASSERT_EQ(v.size(), n);
            for (size_t i = 0; i < n; ++i)
                EXPECT_EQ(v[i], i % 3 == size_t(rank) ? double(i) + 1 : 0.0) << "rank " << rank << " index " << i;
        }
    }
}
