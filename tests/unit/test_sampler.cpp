#include <gtest/gtest.h>

#include "core/distribution.h"
#include "sampler/independent.h"

using namespace snell;

TEST(Sampler, StreamsArePureFunctionsOfPixelAndIndex) {
    IndependentSampler a(7), b(7);
    a.start_pixel_sample(3, 4, 10);
    (void)a.next_1d();
    a.start_pixel_sample(5, 6, 2);
    b.start_pixel_sample(5, 6, 2);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(a.next_1d(), b.next_1d());
}

TEST(Sampler, UniformMean) {
    IndependentSampler s(1);
    s.start_pixel_sample(0, 0, 0);
    double sum = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const double u = s.next_1d();
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        sum += u;
    }
    // Standard error of the mean is sqrt(1/12/n) ~ 6.5e-4; 5 sigma.
    EXPECT_NEAR(sum / n, 0.5, 5 * std::sqrt(1.0 / 12.0 / n));
}

TEST(Distribution1D, SamplesProportionally) {
    Distribution1D d({1.0, 0.0, 3.0});
    EXPECT_DOUBLE_EQ(d.pmf(0), 0.25);
    EXPECT_DOUBLE_EQ(d.pmf(1), 0.0);
    EXPECT_DOUBLE_EQ(d.pmf(2), 0.75);
    int counts[3] = {0, 0, 0};
    IndependentSampler s(3);
    s.start_pixel_sample(0, 0, 0);
    for (int i = 0; i < 40000; ++i) counts[d.sample_discrete(s.next_1d())]++;
    EXPECT_EQ(counts[1], 0);
    EXPECT_NEAR(counts[0] / 40000.0, 0.25, 0.01);
}
