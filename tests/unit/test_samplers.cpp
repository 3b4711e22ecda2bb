// The pixel samplers of src/sampler/: stratification as each claims, determinism, independence of
// dimensions, and lower integration error than the independent sampler.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sampler/factory.h"
#include "sampler/hashing.h"
#include "sampler/ldsampler.h"
#include "sampler/multijitter.h"
#include "sampler/orthogonal.h"
#include "sampler/stratified.h"

using namespace snell;

namespace {

const std::vector<std::string> kAllTypes = {"independent", "stratified", "multijitter",
                                            "orthogonal",  "ldsampler",  "sobol"};

std::unique_ptr<Sampler> make(const std::string& type, int n, uint64_t seed, bool jitter = true) {
    SamplerSpec spec;
    spec.type = type;
    spec.jitter = jitter;
    return create_sampler(spec, n, seed);
}

/// One draw pattern, like a renderer's: 2D (pixel position), 1D (wavelength), then an integrator's.
/// 'p' is next_2d, 'u' next_1d.
const std::string kPattern = "pupppuuppu";

/// Draws `pattern` for samples [first, first + count) of pixel (px, py); result[call][sample].
std::vector<std::vector<Vec2>> draw(Sampler& s, int px, int py, uint64_t first, int count,
                                    const std::string& pattern = kPattern) {
    std::vector<std::vector<Vec2>> out(pattern.size(), std::vector<Vec2>(count));
    for (int i = 0; i < count; ++i) {
        s.start_pixel_sample(px, py, first + uint64_t(i));
        for (size_t c = 0; c < pattern.size(); ++c)
            out[c][i] = pattern[c] == 'p' ? s.next_2d() : Vec2(s.next_1d(), 0.0);
    }
    return out;
}

/// True when the points put exactly one point in each cell of a cols x rows grid.
bool one_per_cell(const std::vector<Vec2>& pts, int cols, int rows) {
    std::vector<int> count(size_t(cols) * rows, 0);
    for (const Vec2& p : pts) {
        if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) return false;
        const int cx = int(p.x * cols), cy = int(p.y * rows);
        if (++count[size_t(cy) * cols + cx] > 1) return false;
    }
    for (int c : count)
        if (c != 1) return false;
    return true;
}

/// True when 2^m points form a (0,m,2)-net in base 2: one point in every elementary interval
/// [a/2^i, (a+1)/2^i) x [b/2^(m-i), (b+1)/2^(m-i)), for all shapes i = 0..m.
bool is_02_net(const std::vector<Vec2>& pts, int m) {
    if (pts.size() != size_t(1) << m) return false;
    for (int i = 0; i <= m; ++i)
        if (!one_per_cell(pts, 1 << i, 1 << (m - i))) return false;
    return true;
}

std::vector<Vec2> prefix(const std::vector<Vec2>& v, size_t n) { return {v.begin(), v.begin() + long(n)}; }

/// The 1D values of a next_1d column, as points (u, 0.5) for one_per_cell(pts, n, 1).
std::vector<Vec2> as_1d(const std::vector<Vec2>& v) {
    std::vector<Vec2> out;
    for (const Vec2& p : v) out.push_back({p.x, 0.5});
    return out;
}

std::vector<Vec2> transposed(const std::vector<Vec2>& v) {
    std::vector<Vec2> out;
    for (const Vec2& p : v) out.push_back({p.y, p.x});
    return out;
}

}  // namespace

TEST(Samplers, FactoryKnowsEveryTypeAndRoundsLikeMitsuba) {
    EXPECT_EQ(sampler_types(), kAllTypes);
    for (const auto& t : kAllTypes) EXPECT_NE(make(t, 16, 0), nullptr) << t;
    EXPECT_THROW(make("halton", 16, 0), std::invalid_argument);
    EXPECT_THROW(make("sobol", 0, 0), std::invalid_argument);

    SamplerSpec s;
    s.type = "stratified";
    EXPECT_EQ(rounded_sample_count(s, 16), 16);
    EXPECT_EQ(rounded_sample_count(s, 20), 25);
    s.type = "multijitter";
    EXPECT_EQ(rounded_sample_count(s, 32), 32);  // 8 x 4
    EXPECT_EQ(rounded_sample_count(s, 64), 64);
    EXPECT_EQ(rounded_sample_count(s, 7), 8);  // Mitsuba: 2 rows x ceil(7/2) columns
    s.type = "ldsampler";
    EXPECT_EQ(rounded_sample_count(s, 1), 4);
    EXPECT_EQ(rounded_sample_count(s, 16), 16);
    EXPECT_EQ(rounded_sample_count(s, 20), 64);
    s.type = "sobol";
    EXPECT_EQ(rounded_sample_count(s, 20), 20);
    EXPECT_EQ(StratifiedSampler(20, 0).resolution(), 5);
    EXPECT_EQ(MultiJitterSampler(32, 0).columns() * MultiJitterSampler(32, 0).rows(), 32);
    EXPECT_EQ(LowDiscrepancySampler(20, 0).sample_count(), 64);
}

TEST(Samplers, StratifiedPutsOnePointPerStratumInEveryDimension) {
    for (int n : {16, 25, 64}) {
        for (auto [px, py] : {std::pair{0, 0}, std::pair{3, 7}, std::pair{1000, 5}}) {
            StratifiedSampler s(n, 42);
            const int res = s.resolution();
            // Block 0 and block 1 (equal-time renders past sample_count) are each stratified.
            for (uint64_t block : {0, 1}) {
                const auto d = draw(s, px, py, block * n, n);
                for (size_t c = 0; c < kPattern.size(); ++c) {
                    if (kPattern[c] == 'p')
                        EXPECT_TRUE(one_per_cell(d[c], res, res)) << "n " << n << " call " << c;
                    else
                        EXPECT_TRUE(one_per_cell(as_1d(d[c]), n, 1)) << "n " << n << " call " << c;
                }
            }
            // ... and randomised independently.
            const auto b0 = draw(s, px, py, 0, n), b1 = draw(s, px, py, n, n);
            EXPECT_NE(b0[0][0].x, b1[0][0].x);
        }
    }
    // Without jitter every point sits at its stratum's centre.
    StratifiedSampler s(16, 3, false);
    s.start_pixel_sample(2, 2, 5);
    const Vec2 p = s.next_2d();
    EXPECT_DOUBLE_EQ(std::fmod(p.x * 4, 1.0), 0.5);
    EXPECT_DOUBLE_EQ(std::fmod(p.y * 4, 1.0), 0.5);
    EXPECT_DOUBLE_EQ(std::fmod(s.next_1d() * 16, 1.0), 0.5);
}

TEST(Samplers, MultiJitterIsStratifiedIn2DAndIn1DProjections) {
    for (int n : {16, 32, 12, 64}) {
        for (bool jitter : {true, false}) {
            MultiJitterSampler s(n, 9, jitter);
            ASSERT_EQ(s.sample_count(), n);
            for (uint64_t block : {0, 3}) {
                const auto d = draw(s, 17, 4, block * n, n);
                for (size_t c = 0; c < kPattern.size(); ++c) {
                    if (kPattern[c] == 'p') {
                        EXPECT_TRUE(one_per_cell(d[c], s.columns(), s.rows())) << "n " << n << " call " << c;
                        EXPECT_TRUE(one_per_cell(d[c], n, 1)) << "x projection, n " << n << " call " << c;
                        EXPECT_TRUE(one_per_cell(transposed(d[c]), n, 1)) << "y projection, n " << n << " call " << c;
                    } else {
                        EXPECT_TRUE(one_per_cell(as_1d(d[c]), n, 1)) << "n " << n << " call " << c;
                    }
                }
            }
        }
    }
}

// Orthogonal-array sampling (strength 2): *every* pair of the first p + 1 dimensions is
// stratified p x p, whether drawn by next_1d or next_2d, and every dimension into p^2 intervals;
// past p + 1 dimensions a new round starts with the same properties. A shuffled column (a mutation
// that reuses one column for two dimensions) fails the pairwise check.
TEST(Samplers, OrthogonalIsStratifiedInEveryPairOfDimensions) {
    EXPECT_EQ(OrthogonalSampler::round_sample_count(25), 25);
    EXPECT_EQ(OrthogonalSampler::round_sample_count(26), 49);
    EXPECT_EQ(OrthogonalSampler::round_sample_count(4), 4);
    EXPECT_EQ(OrthogonalSampler::round_sample_count(1), 4);
    for (int p : {5, 7}) {
        const int n = p * p;
        for (bool jitter : {true, false}) {
            OrthogonalSampler s(n, 11, jitter);
            ASSERT_EQ(s.sample_count(), n);
            for (uint64_t block : {0, 2}) {
                // 2 (p + 1) next_1d calls: two rounds of p + 1 columns.
                const auto d = draw(s, 3, 8, block * n, n, std::string(size_t(2 * (p + 1)), 'u'));
                for (size_t r = 0; r < 2; ++r)
                    for (size_t j = 0; j <= size_t(p); ++j) {
                        const auto& dj = d[r * (p + 1) + j];
                        EXPECT_TRUE(one_per_cell(as_1d(dj), n, 1)) << "p " << p << " dim " << j;
                        for (size_t k = j + 1; k <= size_t(p); ++k) {
                            const auto& dk = d[r * (p + 1) + k];
                            std::vector<Vec2> pair(static_cast<size_t>(n));
                            for (int i = 0; i < n; ++i) pair[size_t(i)] = Vec2(dj[size_t(i)].x, dk[size_t(i)].x);
                            EXPECT_TRUE(one_per_cell(pair, p, p)) << "p " << p << " dims " << j << ", " << k;
                        }
                    }
                // next_2d: both coordinates of each call stratified p x p and n x 1.
                const auto q = draw(s, 3, 8, block * n, n, "ppp");
                for (const auto& c : q) {
                    EXPECT_TRUE(one_per_cell(c, p, p));
                    EXPECT_TRUE(one_per_cell(c, n, 1));
                    EXPECT_TRUE(one_per_cell(transposed(c), n, 1));
                }
            }
        }
    }
}

TEST(Samplers, LdSamplerEveryPowerOfTwoPrefixIsA02Net) {
    const int n = 256;
    for (auto [px, py] : {std::pair{0, 0}, std::pair{5, 9}, std::pair{640, 480}}) {
        LowDiscrepancySampler s(n, 1234);
        for (uint64_t block : {0, 2}) {
            const auto d = draw(s, px, py, block * n, n);
            for (size_t c = 0; c < kPattern.size(); ++c)
                for (int m = 0; m <= 8; ++m) {
                    if (kPattern[c] == 'p')
                        EXPECT_TRUE(is_02_net(prefix(d[c], size_t(1) << m), m)) << "call " << c << " m " << m;
                    else
                        EXPECT_TRUE(one_per_cell(as_1d(prefix(d[c], size_t(1) << m)), 1 << m, 1))
                            << "call " << c << " m " << m;
                }
        }
    }
}

TEST(Samplers, SobolEveryPowerOfTwoPrefixIsA02Net) {
    const int m_max = 10;
    const int n = 1 << m_max;
    // A long pattern reaches dimension pairs far down the path (pairs 0 .. 60).
    std::string pattern = kPattern;
    while (pattern.size() < 60) pattern += "pu";
    for (auto [px, py] : {std::pair{0, 0}, std::pair{7, 3}, std::pair{1919, 1079}}) {
        auto s = make("sobol", 64, 99);  // sample_count does not bound the sequence
        // The first 2^10 samples, and the aligned block [2^10, 2^11) that an equal-time render continues with.
        for (uint64_t first : {uint64_t(0), uint64_t(n)}) {
            const auto d = draw(*s, px, py, first, n, pattern);
            for (size_t c = 0; c < pattern.size(); ++c)
                for (int m = 0; m <= m_max; ++m) {
                    if (pattern[c] == 'p')
                        EXPECT_TRUE(is_02_net(prefix(d[c], size_t(1) << m), m)) << "call " << c << " m " << m;
                    else
                        EXPECT_TRUE(one_per_cell(as_1d(prefix(d[c], size_t(1) << m)), 1 << m, 1))
                            << "call " << c << " m " << m;
                }
        }
    }
}

TEST(Samplers, DeterministicPerSeedPixelAndIndexAndClonesAgree) {
    for (const auto& t : kAllTypes) {
        auto a = make(t, 16, 7), b = make(t, 16, 7), other_seed = make(t, 16, 8);
        const auto da = draw(*a, 3, 4, 0, 16), db = draw(*b, 3, 4, 0, 16);
        const auto d_seed = draw(*other_seed, 3, 4, 0, 16), d_pixel = draw(*a, 4, 3, 0, 16);
        int same_seed_diff = 0, same_pixel_diff = 0;
        for (size_t c = 0; c < da.size(); ++c)
            for (int i = 0; i < 16; ++i) {
                EXPECT_EQ(da[c][i].x, db[c][i].x) << t;
                EXPECT_EQ(da[c][i].y, db[c][i].y) << t;
                same_seed_diff += da[c][i].x != d_seed[c][i].x;
                same_pixel_diff += da[c][i].x != d_pixel[c][i].x;
            }
        EXPECT_GT(same_seed_diff, 150) << t << ": another seed should change (nearly) every value";
        EXPECT_GT(same_pixel_diff, 150) << t << ": another pixel should change (nearly) every value";

        // Random access: revisiting a sample after others reproduces it.
        a->start_pixel_sample(3, 4, 5);
        const Vec2 p5 = a->next_2d();
        a->start_pixel_sample(9, 9, 2);
        (void)a->next_1d();
        a->start_pixel_sample(3, 4, 5);
        EXPECT_EQ(a->next_2d().x, p5.x) << t;

        // A clone continues the same stream, and restarts identically.
        a->start_pixel_sample(1, 2, 3);
        (void)a->next_2d();
        auto c = a->clone();
        for (int k = 0; k < 8; ++k) EXPECT_EQ(a->next_1d(), c->next_1d()) << t;
        a->start_pixel_sample(6, 1, 40);
        c->start_pixel_sample(6, 1, 40);
        for (int k = 0; k < 8; ++k) EXPECT_EQ(a->next_2d().y, c->next_2d().y) << t;
    }
}

TEST(Samplers, ValuesInUnitIntervalForAnyIndex) {
    for (const auto& t : kAllTypes)
        for (uint64_t first : {uint64_t(0), uint64_t(1000), (uint64_t(1) << 32) - 8, (uint64_t(1) << 40) + 3}) {
            auto s = make(t, 16, 5);
            for (int i = 0; i < 16; ++i) {
                s->start_pixel_sample(i, 2 * i, first + uint64_t(i));
                for (int k = 0; k < 20; ++k) {
                    const double u = s->next_1d();
                    ASSERT_TRUE(u >= 0 && u < 1) << t << " " << u;
                    const Vec2 p = s->next_2d();
                    ASSERT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1) << t;
                }
            }
        }
    // Sobol continues its sequence across 2^32: the 16 samples around it are still distinct.
    auto s = make("sobol", 16, 5);
    std::vector<double> xs;
    for (uint64_t i = (uint64_t(1) << 32) - 8; i < (uint64_t(1) << 32) + 8; ++i) {
        s->start_pixel_sample(0, 0, i);
        xs.push_back(s->next_1d());
    }
    for (size_t i = 0; i < xs.size(); ++i)
        for (size_t j = i + 1; j < xs.size(); ++j) EXPECT_NE(xs[i], xs[j]);
}

// E[u_d u_e] = 1/4 for every pair of distinct dimensions (also x and y of one 2D draw) over many
// pixels; a sampler that reused one point set for two dimensions would give 1/3.
TEST(Samplers, DimensionsAreUncorrelated) {
    const int pixels = 2048, spp = 16;
    const size_t dims =
        2 * std::count(kPattern.begin(), kPattern.end(), 'p') + std::count(kPattern.begin(), kPattern.end(), 'u');
    for (const auto& t : kAllTypes) {
        auto s = make(t, spp, 2024);
        std::vector<double> sum(dims * dims, 0.0);
        double n = 0;
        for (int pix = 0; pix < pixels; ++pix) {
            const auto d = draw(*s, pix % 64, pix / 64, 0, spp);
            for (int i = 0; i < spp; ++i) {
                std::vector<double> u;
                for (size_t c = 0; c < kPattern.size(); ++c) {
                    u.push_back(d[c][i].x);
                    if (kPattern[c] == 'p') u.push_back(d[c][i].y);
                }
                for (size_t a = 0; a < dims; ++a)
                    for (size_t b = a + 1; b < dims; ++b) sum[a * dims + b] += u[a] * u[b];
                n += 1;
            }
        }
        // Var(u_d u_e) = 1/9 - 1/16 = 7/144 for independent uniforms; 5 sigma.
        const double bound = 5 * std::sqrt(7.0 / 144.0 / n);
        for (size_t a = 0; a < dims; ++a)
            for (size_t b = a + 1; b < dims; ++b)
                EXPECT_NEAR(sum[a * dims + b] / n, 0.25, bound) << t << " dimensions " << a << ", " << b;
    }
}

// Integrates smooth 2D functions with 64 samples per pixel over many pixels; the variance of the
// per-pixel estimates must fall well below the independent sampler's.
TEST(Samplers, StratifiedSamplersBeatIndependentOnSmoothIntegrands) {
    const int pixels = 4000, spp = 64;
    const std::vector<std::pair<std::string, std::function<double(Vec2)>>> integrands = {
        {"soft disk",
         [](Vec2 p) {
             const double r = std::hypot(p.x - 0.45, p.y - 0.55);
             return 1.0 / (1.0 + std::exp((r - 0.3) / 0.02));
         }},
        {"gaussian",
         [](Vec2 p) { return std::exp(-((p.x - 0.4) * (p.x - 0.4) + (p.y - 0.6) * (p.y - 0.6)) / (2 * 0.15 * 0.15)); }},
    };
    for (const auto& [name, f] : integrands) {
        // The pixel position pair (first draw) and a pair deeper in the path (after 1D and 2D draws).
        for (int skip : {0, 3}) {
            auto variance = [&, &f = f](const std::string& type) {
                auto s = make(type, spp, 77);
                double sum = 0, sum2 = 0;
                for (int pix = 0; pix < pixels; ++pix) {
                    double est = 0;
                    for (int i = 0; i < spp; ++i) {
                        s->start_pixel_sample(pix % 100, pix / 100, uint64_t(i));
                        for (int k = 0; k < skip; ++k) k % 2 ? (void)s->next_1d() : (void)s->next_2d();
                        est += f(s->next_2d());
                    }
                    est /= spp;
                    sum += est;
                    sum2 += est * est;
                }
                const double mean = sum / pixels;
                return sum2 / pixels - mean * mean;
            };
            const double v_ind = variance("independent");
            for (const std::string t : {"stratified", "multijitter", "ldsampler", "sobol"}) {
                const double ratio = variance(t) / v_ind;
                std::printf("[ variance ] %-9s pair after %d draws: %-11s / independent = %.4f\n", name.c_str(), skip,
                            t.c_str(), ratio);
                EXPECT_LT(ratio, 0.5) << t << " on " << name;
            }
        }
    }
}

TEST(Samplers, HashingBuildingBlocks) {
    // permute_index is a permutation of [0, n) for any n.
    for (uint32_t n : {1u, 2u, 3u, 7u, 16u, 25u, 100u}) {
        std::vector<int> seen(n, 0);
        for (uint32_t i = 0; i < n; ++i) seen[permute_index(i, n, 0xabcdefULL * n)]++;
        for (int c : seen) EXPECT_EQ(c, 1) << n;
    }
    // shuffle_index maps the aligned block [0, 2^m) onto an aligned block of size 2^m.
    for (int m = 0; m <= 6; ++m) {
        const uint32_t base = shuffle_index(0, 32, 12345) >> m;
        std::vector<int> seen(size_t(1) << m, 0);
        for (uint32_t i = 0; i < (1u << m); ++i) {
            const uint32_t j = shuffle_index(i, 32, 12345);
            EXPECT_EQ(j >> m, base);
            seen[j & ((1u << m) - 1)]++;
        }
        for (int c : seen) EXPECT_EQ(c, 1);
    }
    // Sobol's second dimension: 0, 1/2, 3/4, 1/4, 3/8, 7/8, ...
    EXPECT_EQ(zero_two_y(0), 0u);
    EXPECT_EQ(zero_two_y(1), 0x80000000u);
    EXPECT_EQ(zero_two_y(2), 0xc0000000u);
    EXPECT_EQ(zero_two_y(3), 0x40000000u);
    EXPECT_EQ(zero_two_y(4), 0xa0000000u);
    // The byte tables agree with the bit-by-bit generator on full 32-bit indices.
    PCG32 rng(9, 3);
    for (int k = 0; k < 10000; ++k) {
        const uint32_t i = rng.next_u32();
        ASSERT_EQ(zero_two_y(i), zero_two_y_bitwise(i)) << i;
        ASSERT_EQ(zero_two_y<true>(i), reverse_bits(zero_two_y_bitwise(i))) << i;
        // The reversed-word scramble is the scramble between two reversals.
        ASSERT_EQ(owen_scramble(i, 77u * k), reverse_bits(owen_scramble_reversed(reverse_bits(i), 77u * k)));
    }
    EXPECT_EQ(zero_two_x(1), 0x80000000u);
    EXPECT_EQ(reverse_bits(0x1u), 0x80000000u);
}
