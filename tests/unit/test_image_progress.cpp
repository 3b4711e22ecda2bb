#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "core/progress.h"

using namespace snell;

TEST(Progress, FormatDuration) {
    EXPECT_EQ(format_duration(0), "0s");
    EXPECT_EQ(format_duration(42.4), "42s");
    EXPECT_EQ(format_duration(187), "3m07s");
    EXPECT_EQ(format_duration(2 * 3600 + 5 * 60 + 10), "2h05m");
    EXPECT_EQ(format_duration(-1), "--");
}

TEST(Progress, FormatLine) {
    EXPECT_EQ(format_progress_line("render", 0.5, 62, 62, 10), "render [#####-----]  50.0%  elapsed 1m02s  ETA 1m02s");
    EXPECT_EQ(format_progress_line("x", 1.7, 1, 0, 4), "x [####] 100.0%  elapsed 1s  ETA 0s");  // clamped
    EXPECT_EQ(format_progress_line("x", 0.0, 0, -1, 4), "x [----]   0.0%  elapsed 0s  ETA --");
}

TEST(Progress, ConcurrentAddCountsEveryUnit) {
    ProgressBar bar("test", 8 * 10000);
    bar.set_enabled(false);  // counting only; drawing is exercised below
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t)
        threads.emplace_back([&] {
            for (int i = 0; i < 10000; ++i) bar.add(1);
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(bar.done(), 80000u);
    EXPECT_EQ(bar.fraction(), 1.0);
    bar.finish();
    bar.finish();  // idempotent
}

TEST(Progress, DrawsToStderrWhenEnabled) {
    ::testing::internal::CaptureStderr();
    {
        ProgressBar bar("drawn", 4);
        bar.set_enabled(true);
        bar.add(2);  // the first add draws at once
        bar.add(2);
        bar.finish();
    }
    const std::string out = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(out.find("\rdrawn ["), std::string::npos) << out;
    EXPECT_NE(out.find("100.0%"), std::string::npos) << out;
    EXPECT_EQ(out.back(), '\n');
}

TEST(Progress, SilentWhenStderrIsNotATty) {
    // Under ctest stderr is a pipe or file, so a default bar prints nothing.
    ::testing::internal::CaptureStderr();  // redirects stderr to a file: not a TTY
    {
        ProgressBar bar("quiet", 10);
        EXPECT_FALSE(bar.enabled());
        bar.add(10);
    }
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(Progress, TimeModeFractionFollowsClock) {
    auto bar = ProgressBar::for_time("timed", 1e6);
    bar.set_enabled(false);
    bar.add(123);  // ignored for the fraction in time mode
    const double f = bar.fraction();
    EXPECT_GE(f, 0.0);
    EXPECT_LT(f, 1e-3);                               // 1e6 s budget: only a tiny fraction can have elapsed
    auto done = ProgressBar::for_time("timed", 0.0);  // zero budget is already complete
    done.set_enabled(false);
    EXPECT_EQ(done.fraction(), 1.0);
}
