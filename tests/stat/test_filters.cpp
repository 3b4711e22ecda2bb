// Pixel reconstruction filters (camera/filter.h): sample() against pdf() by chi-square, exact
// inversion of each axis' CDF, normalisation, the filter-importance-sampling estimator against
// quadrature, sample weights, the splat support helper, and loading <rfilter> from scene files.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "camera/factory.h"
#include "camera/filter.h"
#include "loader/scene_loader.h"
#include "stat/chi2_plane.h"
#include "unit/loader_errors.h"

using namespace snell;
using snell::test::adaptive_simpson;
using snell::test::Chi2PlaneOptions;
using snell::test::Chi2Result;

namespace {

struct Case {
    std::string label;
    std::shared_ptr<const Filter> filter;
    uint64_t seed;  ///< fixed, different per case so the statistics are independent
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.label; }

std::vector<Case> cases() {
    return {{"box", box_filter(), 11},
            {"tent_r1", std::make_shared<TentFilter>(1.0), 12},
            {"tent_r1_7", std::make_shared<TentFilter>(1.7), 13},
            {"gaussian_s0_5", std::make_shared<GaussianFilter>(0.5), 14},
            {"gaussian_s1_3", std::make_shared<GaussianFilter>(1.3), 15}};
}
constexpr int kChi2Tests = 5;  // one per case (Sidak correction)

Vec2 next_2d(PCG32& rng) {
    const double x = rng.next_double();
    return {x, rng.next_double()};
}

/// Integral of h over the filter's support, split at the axes (the tent's kink), by nested
/// adaptive Simpson. The upper limits are the last doubles inside the half-open box.
template <class H>
double integrate_support(const Filter& f, const H& h, double eps = 1e-11) {
    const Vec2 r = f.radius();
    const double rx = std::nextafter(r.x, 0.0), ry = std::nextafter(r.y, 0.0);
    double sum = 0;
    for (auto [y0, y1] : {std::pair{-r.y, 0.0}, std::pair{0.0, ry}})
        for (auto [x0, x1] : {std::pair{-r.x, 0.0}, std::pair{0.0, rx}})
            sum += adaptive_simpson(
                [&](double y) { return adaptive_simpson([&](double x) { return h(Vec2(x, y)); }, x0, x1, eps, 8); }, y0,
                y1, eps, 8);
    return sum;
}

/// The 1D factor f1 of a separable filter, from eval: f1(x) = eval(x, 0) / sqrt(eval(0, 0)).
double factor_1d(const Filter& f, double x) { return f.eval(Vec2(x, 0)) / std::sqrt(f.eval(Vec2(0, 0))); }

class FilterTest : public ::testing::TestWithParam<Case> {};

}  // namespace

// sample() must produce offsets distributed as pdf(): 40x40 bins over the support, 10^6 samples.
TEST_P(FilterTest, Chi2SampleMatchesPdf) {
    const Filter& f = *GetParam().filter;
    Chi2PlaneOptions opt;
    opt.test_count = kChi2Tests;
    opt.seed = GetParam().seed;
    const Vec2 r = f.radius();
    const Chi2Result res =
        test::chi2_plane_test([&](PCG32& rng) -> std::optional<Vec2> { return f.sample(next_2d(rng)).offset; },
                              [&](const Vec2& o) { return f.pdf(o); }, Vec2(-r.x, -r.y), r, opt);
    std::cout << "[chi2] " << GetParam().label << ": " << res.message << "\n";
    RecordProperty("p_value", std::to_string(res.p_value));
    EXPECT_TRUE(res.passed) << res.message;
    EXPECT_NEAR(res.pdf_integral, 1.0, 1e-6);
    EXPECT_EQ(res.valid_samples, opt.samples);  // no offset outside the support
}

// The chi-square test has power: a sampler checked against a slightly wrong pdf is rejected.
TEST(FilterChi2, RejectsAMismatchedPdf) {
    const GaussianFilter sampled(0.5), claimed(0.53);
    const Vec2 r = claimed.radius();
    Chi2PlaneOptions opt;
    const Chi2Result res =
        test::chi2_plane_test([&](PCG32& rng) -> std::optional<Vec2> { return sampled.sample(next_2d(rng)).offset; },
                              [&](const Vec2& o) { return claimed.pdf(o); }, Vec2(-r.x, -r.y), r, opt);
    std::cout << "[chi2 power] gaussian 0.5 vs pdf of 0.53: p = " << res.p_value << "\n";
    EXPECT_FALSE(res.passed) << res.message;
    const TentFilter tent(1.0);
    const Chi2Result res2 =
        test::chi2_plane_test([&](PCG32& rng) -> std::optional<Vec2> { return tent.sample(next_2d(rng)).offset; },
                              [&](const Vec2& o) { return box_filter()->pdf(o); }, Vec2(-1, -1), Vec2(1, 1), opt);
    std::cout << "[chi2 power] tent vs pdf of box: p = " << res2.p_value << "\n";
    EXPECT_FALSE(res2.passed) << res2.message;
}

// Each axis is sampled by exact inversion: the 1D CDF at the sampled offset gives back u, and
// sampling is monotone in u (deterministic, no hidden randomness).
TEST_P(FilterTest, SamplingInvertsTheCdf) {
    const Filter& f = *GetParam().filter;
    const double r = f.radius().x;
    double prev = -kInfinity;
    for (int i = 0; i <= 400; ++i) {
        const double u = std::min(i / 400.0, 0x1.fffffffffffffp-1);
        const FilterSample s = f.sample(Vec2(u, 0.37));
        const FilterSample again = f.sample(Vec2(u, 0.37));
        EXPECT_EQ(s.offset, again.offset);
        EXPECT_GE(s.offset.x, prev);
        prev = s.offset.x;
        const double cdf = s.offset.x <= -r
                               ? 0.0
                               : adaptive_simpson([&](double x) { return factor_1d(f, x); }, -r, s.offset.x, 1e-13, 16);
        EXPECT_NEAR(cdf, u, 1e-9) << "u = " << u << ", offset " << s.offset.x;
    }
}

// eval (and pdf) integrate to 1 over the plane.
TEST_P(FilterTest, EvalIntegratesToOne) {
    const Filter& f = *GetParam().filter;
    EXPECT_NEAR(integrate_support(f, [&](const Vec2& o) { return f.eval(o); }), 1.0, 1e-8);
    EXPECT_NEAR(integrate_support(f, [&](const Vec2& o) { return f.pdf(o); }), 1.0, 1e-8);
    // Nothing outside the support.
    const Vec2 r = f.radius();
    for (double t : {1.0, 1.01, 1.5, 3.0}) {
        EXPECT_EQ(f.eval(Vec2(r.x * t, 0)), 0.0);
        EXPECT_EQ(f.eval(Vec2(0, r.y * t)), 0.0);
        if (t > 1) {  // the box holds -0.5
            EXPECT_EQ(f.eval(Vec2(0, -r.y * t)), 0.0);
        }
    }
}

// Filter importance sampling estimates integral f g for a smooth g: mean of g(offset) * weight
// agrees with quadrature within 4 standard errors.
TEST_P(FilterTest, EstimatorMatchesQuadrature) {
    const Filter& f = *GetParam().filter;
    auto g = [](const Vec2& o) {
        return 1 + 0.5 * std::sin(2 * o.x + 0.3) * std::cos(1.3 * o.y) + 0.2 * o.x * o.y + 0.1 * o.x * o.x;
    };
    const double ref = integrate_support(f, [&](const Vec2& o) { return f.eval(o) * g(o); });
    PCG32 rng(GetParam().seed, 5);
    const int n = 200000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const FilterSample s = f.sample(next_2d(rng));
        const double v = g(s.offset) * s.weight;
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    std::cout << "[fis] " << GetParam().label << ": estimate " << mean << " +- " << se << ", quadrature " << ref
              << "\n";
    EXPECT_GT(se, 0);
    EXPECT_NEAR(mean, ref, 4 * se);
}

// Weights are f / pdf at the offset: exactly 1 for every filter (all three are sampled exactly),
// and offsets stay inside the support (the box's half-open).
TEST_P(FilterTest, WeightsAndSupport) {
    const Filter& f = *GetParam().filter;
    const Vec2 r = f.radius();
    PCG32 rng(3, 9);
    double wmin = kInfinity, wmax = -kInfinity, rmin = kInfinity, rmax = -kInfinity;
    for (int i = 0; i < 100000; ++i) {
        const Vec2 u = i < 4 ? Vec2(i & 1 ? 0x1.fffffffffffffp-1 : 0.0, i & 2 ? 0x1.fffffffffffffp-1 : 0.0)
                             : next_2d(rng);  // the corners of [0,1)^2 first
        const FilterSample s = f.sample(u);
        ASSERT_LE(std::abs(s.offset.x), r.x);
        ASSERT_LE(std::abs(s.offset.y), r.y);
        if (f.name() == "box") {
            ASSERT_LT(s.offset.x, 0.5);
            ASSERT_LT(s.offset.y, 0.5);
        }
        EXPECT_EQ(s.weight, 1.0);
        wmin = std::min(wmin, s.weight);
        wmax = std::max(wmax, s.weight);
        const double e = f.eval(s.offset), p = f.pdf(s.offset);
        if (p > 0) {
            const double ratio = e / p;
            EXPECT_NEAR(ratio, s.weight, 1e-12);
            rmin = std::min(rmin, ratio);
            rmax = std::max(rmax, ratio);
        } else {  // only on the support's boundary, which has probability zero
            EXPECT_EQ(e, 0.0);
            EXPECT_TRUE(std::abs(s.offset.x) == r.x || std::abs(s.offset.y) == r.y) << s.offset.x << " " << s.offset.y;
        }
    }
    std::cout << "[weights] " << GetParam().label << ": weight in [" << wmin << ", " << wmax << "], eval/pdf in ["
              << rmin << ", " << rmax << "]\n";
}

// for_each_pixel_in_support visits exactly the pixels with a positive weight, with weight
// eval(raster - centre); the weights sum to 1 exactly for box and integer-radius tents, nearly
// for the gaussian (Poisson-summation ripple), and exactly on average over positions.
TEST_P(FilterTest, SupportHelperWeights) {
    const Filter& f = *GetParam().filter;
    PCG32 rng(5, 1);
    double max_dev = 0;
    for (int i = 0; i < 2000; ++i) {
        Vec2 p(10 + 10 * rng.next_double(), 10 + 10 * rng.next_double());
        if (i < 50) p = Vec2(std::floor(p.x), std::floor(p.y) + (i % 2 ? 0.5 : 0.0));  // pixel edges
        std::map<std::pair<int, int>, double> seen;
        double sum = 0;
        for_each_pixel_in_support(f, p, [&](int px, int py, double w) {
            EXPECT_TRUE(seen.emplace(std::pair{px, py}, w).second);
            sum += w;
        });
        // Brute force over a wide window.
        for (int py = int(p.y) - 8; py <= int(p.y) + 8; ++py)
            for (int px = int(p.x) - 8; px <= int(p.x) + 8; ++px) {
                const double w = f.eval(Vec2(p.x - (px + 0.5), p.y - (py + 0.5)));
                auto it = seen.find({px, py});
                if (w > 0) {
                    ASSERT_NE(it, seen.end()) << "missed pixel " << px << "," << py;
                    EXPECT_EQ(it->second, w);
                } else {
                    EXPECT_EQ(it, seen.end());
                }
            }
        if (f.name() == "box") {
            ASSERT_EQ(seen.size(), 1u);
            EXPECT_EQ(seen.begin()->first, (std::pair{int(std::floor(p.x)), int(std::floor(p.y))}));
        }
        max_dev = std::max(max_dev, std::abs(sum - 1));
    }
    // Pointwise: exact partitions of unity, else the ripple seen (a regression guard): the
    // gaussian's is about 2 (2 exp(-2 pi^2 sigma^2)) = 0.029 at sigma 0.5 (Poisson summation);
    // a tent of non-integer radius ripples by up to ~14% at radius 1.7.
    const std::string& label = GetParam().label;
    const double bound = label == "box" || label == "tent_r1" ? 1e-12
                         : label == "gaussian_s0_5"           ? 0.035
                         : label == "gaussian_s1_3"           ? 1e-4
                                                              : 0.2;
    EXPECT_LE(max_dev, bound);
    // Averaged over a pixel cell (midpoint rule on a 64x64 grid) the sum is the integral, 1.
    double avg = 0;
    const int m = 64;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
            for_each_pixel_in_support(f, Vec2(20 + (i + 0.5) / m, 30 + (j + 0.5) / m),
                                      [&](int, int, double w) { avg += w; });
    avg /= m * m;
    std::cout << "[support] " << label << ": max |sum - 1| = " << max_dev << ", cell average " << avg << "\n";
    EXPECT_NEAR(avg, 1.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Filters, FilterTest, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.label; });

TEST(FilterSupport, ClippedToTheFilm) {
    const GaussianFilter g(0.5);
    std::set<std::pair<int, int>> seen;
    for_each_pixel_in_support(g, Vec2(0.2, 5.9), 8, 6, [&](int px, int py, double w) {
        EXPECT_TRUE(px >= 0 && px < 8 && py >= 0 && py < 6);
        EXPECT_GT(w, 0);
        seen.insert({px, py});
    });
    // x in (0.2 - 2.5, 0.2 + 1.5] -> 0, 1 (of -2..1); y in (3.4, 7.4] -> 4, 5 (of 4..7).
    EXPECT_EQ(seen, (std::set<std::pair<int, int>>{{0, 4}, {1, 4}, {0, 5}, {1, 5}}));
}

TEST(FilterDefaults, MitsubaParameters) {
    EXPECT_EQ(box_filter()->radius(), Vec2(0.5, 0.5));
    EXPECT_EQ(TentFilter().radius(), Vec2(1, 1));
    EXPECT_EQ(GaussianFilter().stddev(), 0.5);
    EXPECT_EQ(GaussianFilter().radius(), Vec2(2, 2));  // 4 stddev
    // Mitsuba's gaussian: max(0, exp(-x^2 / (2 s^2)) - exp(-8)), up to normalisation.
    const GaussianFilter g(0.5);
    const double w0 = 1 - std::exp(-8.0), w1 = std::exp(-0.7 * 0.7 / 0.5) - std::exp(-8.0);
    EXPECT_NEAR(g.eval(Vec2(0.7, 0)) / g.eval(Vec2(0, 0)), w1 / w0, 1e-14);
    EXPECT_NEAR(TentFilter(2).eval(Vec2(0.5, -1)) / TentFilter(2).eval(Vec2(0, 0)), 0.75 * 0.5, 1e-15);
    // A programmatic film has no filter: the one-pixel box.
    FilmSpec film;
    EXPECT_EQ(film.filter, nullptr);
    EXPECT_EQ(film.pixel_filter().name(), "box");
}

// --- loading ------------------------------------------------------------------------------

namespace {

const std::string kDataDir = std::string(SNELL_SOURCE_DIR) + "/tests/data/scenes/full";

/// A scene whose film holds `film_body` from line 4 on (the film element is on line 3).
std::string film_scene(const std::string& film_body) {
    return "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>\n"
           "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"6\"/>\n" +
           film_body + "\n</film>\n</sensor>\n</scene>";
}

std::shared_ptr<const Filter> load_filter(const std::string& xml) {
    return load_scene_string(xml, "test.xml", kDataDir).film.filter;
}

void expect_error(const std::string& xml, const std::string& where, const std::string& what) {
    test::expect_load_error(xml, kDataDir, where, what);
}

}  // namespace

TEST(FilterLoading, EachTypeWithItsParameters) {
    auto box = load_filter(film_scene("<rfilter type=\"box\"/>"));
    ASSERT_TRUE(box);
    EXPECT_EQ(box->name(), "box");
    EXPECT_EQ(box->radius(), Vec2(0.5, 0.5));

    auto tent = load_filter(film_scene("<rfilter type=\"tent\"><float name=\"radius\" value=\"1.5\"/></rfilter>"));
    ASSERT_TRUE(tent);
    EXPECT_EQ(tent->name(), "tent");
    EXPECT_EQ(tent->radius(), Vec2(1.5, 1.5));
    EXPECT_EQ(load_filter(film_scene("<rfilter type=\"tent\"/>"))->radius(), Vec2(1, 1));

    auto gauss = load_filter(film_scene("<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"0.8\"/></rfilter>"));
    ASSERT_TRUE(gauss);
    EXPECT_EQ(gauss->name(), "gaussian");
    auto* g = dynamic_cast<const GaussianFilter*>(gauss.get());
    ASSERT_NE(g, nullptr);
    EXPECT_EQ(g->stddev(), 0.8);
    EXPECT_NEAR(g->radius().x, 3.2, 1e-15);
}

TEST(FilterLoading, MitsubaDefaultIsGaussian) {
    for (const std::string& xml :
         {film_scene(""), std::string("<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n</scene>")}) {
        auto f = load_filter(xml);
        ASSERT_TRUE(f);
        EXPECT_EQ(f->name(), "gaussian");
        auto* g = dynamic_cast<const GaussianFilter*>(f.get());
        ASSERT_NE(g, nullptr);
        EXPECT_EQ(g->stddev(), 0.5);
    }
}

TEST(FilterLoading, Errors) {
    expect_error(film_scene("<rfilter type=\"mitchell\"/>"), "test.xml:4: <rfilter>",
                 "unknown rfilter type 'mitchell'");
    expect_error(film_scene("<rfilter type=\"gaussian\">\n<float name=\"stddev\" value=\"0\"/>\n</rfilter>"),
                 "test.xml:5: <rfilter>", "stddev must be positive");
    expect_error(film_scene("<rfilter type=\"gaussian\">\n<float name=\"stddev\" value=\"-1\"/>\n</rfilter>"),
                 "test.xml:5: <rfilter>", "stddev must be positive");
    expect_error(film_scene("<rfilter type=\"tent\">\n\n<float name=\"radius\" value=\"0\"/>\n</rfilter>"),
                 "test.xml:6: <rfilter>", "radius must be positive");
    expect_error(film_scene("<rfilter type=\"box\">\n<float name=\"radius\" value=\"1\"/>\n</rfilter>"),
                 "test.xml:5: <rfilter>", "unused parameter 'radius'");
    expect_error(film_scene("<rfilter type=\"gaussian\">\n<float name=\"radius\" value=\"1\"/>\n</rfilter>"),
                 "test.xml:5: <rfilter>", "unused parameter 'radius'");
    expect_error(film_scene("<rfilter type=\"box\"/>\n<rfilter type=\"tent\"/>"), "test.xml:5: <rfilter>",
                 "more than one <rfilter>");
}

TEST(FilterLoading, FactoryDirect) {
    Props p("rfilter", "tent", SourceLoc{"f.xml", 3});
    p.set("radius", 2.5, SourceLoc{"f.xml", 4});
    auto f = create_filter(p);
    p.check_unused();
    EXPECT_EQ(f->radius(), Vec2(2.5, 2.5));
    Props q("rfilter", "lanczos", SourceLoc{"f.xml", 7});
    try {
        create_filter(q);
        FAIL() << "lanczos accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("f.xml:7: <rfilter>", 0), 0u) << e.what();
    }
}
