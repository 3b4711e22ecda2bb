// ExactSum (issue 27): the sum of the same terms in any order, in any grouping, is the same
// bits, and its value is the sum to within the term rounding of 2^-80.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/exact_sum.h"

using namespace snell;

namespace {

std::vector<double> wide_terms(int n, uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> mant(0.5, 1.0), expo(-60.0, 60.0);
    std::vector<double> v;
    for (int i = 0; i < n; ++i) {
        const double x = std::ldexp(mant(rng), int(expo(rng)));
        v.push_back(i % 7 == 0 ? -x : x);  // a few negative terms (filters with negative lobes)
    }
    return v;
}

}  // namespace

TEST(ExactSum, AnyOrderAndGroupingGivesTheSameBits) {
    std::vector<double> v = wide_terms(5000, 1);
    ExactSum forward;
    for (double x : v) forward.add(x);
    std::mt19937 rng(2);
    for (int trial = 0; trial < 5; ++trial) {
        std::shuffle(v.begin(), v.end(), rng);
        // Grouped as three partial sums added in reverse, as merged partial films are.
        ExactSum a, b, c;
        for (size_t i = 0; i < v.size(); ++i) (i < 1000 ? a : i < 3000 ? b : c).add(v[i]);
        ExactSum total = c;
        total += b;
        total += a;
        EXPECT_EQ(total, forward) << trial;
        EXPECT_EQ(total.value(), forward.value());
    }
    // Floating-point addition of the same terms does depend on the order (so the test can fail).
    double d1 = 0, d2 = 0;
    for (double x : v) d1 += x;
    std::reverse(v.begin(), v.end());
    for (double x : v) d2 += x;
    EXPECT_NE(d1, d2);
}

TEST(ExactSum, ValueIsTheSum) {
    const std::vector<double> v = wide_terms(2000, 3);
    ExactSum s;
    long double ref = 0;
    for (double x : v) {
        s.add(x);
        ref += x;
    }
    EXPECT_NEAR(s.value(), double(ref), 1e-12 * std::abs(double(ref)));
    ExactSum one(1.0);
    one.add(-0.25);
    EXPECT_EQ(one.value(), 0.75);
    ExactSum neg(-3.5);
    EXPECT_EQ(neg.value(), -3.5);
    neg += ExactSum(3.5);
    EXPECT_EQ(neg.value(), 0.0);
    EXPECT_EQ(neg, ExactSum());
}

TEST(ExactSum, TermsBeyondTheRangeSaturateAndSay) {
    ExactSum s;
    EXPECT_FALSE(s.add(1e300));
    EXPECT_EQ(s.value(), ExactSum::kMaxTerm);
    EXPECT_FALSE(s.add(NAN));
    EXPECT_TRUE(s.add(1.0));
    // 2^30 of the largest term still fit (the largest --spp).
    ExactSum big(ExactSum::kMaxTerm * 0.999);
    ExactSum many;
    for (int k = 0; k < 30; ++k) {
        many = big;
        many += big;
        big = many;
    }
    EXPECT_GT(big.value(), 0);
    EXPECT_NEAR(big.value(), std::ldexp(ExactSum::kMaxTerm * 0.999, 30), 1e-9 * big.value());
}

TEST(ExactSum, TinyTermsAreKeptToTwoToTheMinusEighty) {
    ExactSum s;
    s.add(std::ldexp(1.0, -80));
    EXPECT_EQ(s.value(), std::ldexp(1.0, -80));
    ExactSum t;
    t.add(std::ldexp(1.0, -81));  // below the resolution: dropped
    EXPECT_EQ(t.value(), 0.0);
}
