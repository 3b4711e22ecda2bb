// Statistical tests of the emitters, fixed seeds, thresholds from the statistics themselves:
// Monte Carlo irradiance against closed forms / fine quadrature (k standard errors), and a
// chi-square goodness-of-fit test of environment-map sampling against pdf_li.
#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "core/warp.h"
#include "geometry/sphere.h"
#include "light/area.h"
#include "light/constant.h"
#include "light/envmap.h"
#include "stat/chi2.h"
#include "unit/test_light_disk.h"

using namespace snell;

namespace {

Vec2 next2(PCG32& rng) {
    const double a = rng.next_double();
    return {a, rng.next_double()};
}

// Five standard errors: a false alarm has probability ~6e-7 per comparison.
constexpr double kSigmas = 5.0;

struct MeanSE {
    double mean, se;
};
template <typename F>
MeanSE estimate(int n, F&& sample) {
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        const double x = sample(i);
        s += x;
        s2 += x * x;
    }
    const double m = s / n;
    return {m, std::sqrt(std::max(0.0, s2 / n - m * m) / (n - 1))};
}

Image test_image(int W, int H, bool black_poles = false) {
    Image img;
    img.width = W;
    img.height = H;
    img.rgb.assign(size_t(3) * W * H, 0.f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const double s = 0.5 + 0.5 * std::sin(0.7 * x) * std::cos(0.9 * y);
            img.at(x, y, 0) = float(0.1 + s);
            img.at(x, y, 1) = float(0.2 + 0.3 * s * s);
            img.at(x, y, 2) = float(0.05 + 0.02 * x);
            if (x >= 5 && x < 8) img.at(x, y, 0) = img.at(x, y, 1) = img.at(x, y, 2) = 0.f;  // black wedge
        }
    img.at(10, 4, 0) = img.at(10, 4, 1) = img.at(10, 4, 2) = 60.f;  // a sun
    if (black_poles)  // rows 0, 1, H-2, H-1: the polar bins get zero density
        for (int y : {0, 1, H - 2, H - 1})
            for (int x = 0; x < W; ++x) img.at(x, y, 0) = img.at(x, y, 1) = img.at(x, y, 2) = 0.f;
    return img;
}

}  // namespace

// Irradiance on axis at height h below a Lambertian disk of radius R facing the point:
// E = pi L R^2 / (h^2 + R^2).
TEST(LightStat, AreaLightIrradianceMatchesDiskClosedForm) {
    const double R = 0.4, h = 1.3, Lv = 2.0;
    auto disk = std::make_shared<test::TestDisk>(Vec3(1, 2, 3 + h), Vec3(0, 0, -1), R);
    AreaLight light(Spectrum::constant(Lv), disk);
    const LightSampleContext ref{Vec3(1, 2, 3), Vec3(0, 0, 1)};
    const double E = kPi * Lv * R * R / (h * h + R * R);
    PCG32 rng(21, 22);
    const int n = 200000;
    const MeanSE sa = estimate(n, [&](int) {
        auto ls = light.sample_li(ref, next2(rng), SampledWavelengths::single(550));
        return ls ? ls->Le[0] * std::max(0.0, dot(ref.n, ls->wi)) / ls->pdf : 0.0;
    });
    EXPECT_LT(std::abs(sa.mean - E), kSigmas * sa.se) << sa.mean << " vs " << E << " se " << sa.se;
    EXPECT_LT(sa.se, 0.01 * E);  // the test has power
    // The same estimate through the area density: Le cos cos' / (d^2 pdf_area).
    const MeanSE ar = estimate(n, [&](int) {
        auto ls = light.sample_li(ref, next2(rng), SampledWavelengths::single(550));
        if (!ls) return 0.0;
        const double cos_l = std::abs(dot(ls->n, ls->wi));
        return ls->Le[0] * std::max(0.0, dot(ref.n, ls->wi)) * cos_l / (sqr(ls->dist) * ls->pdf_area);
    });
    EXPECT_LT(std::abs(ar.mean - E), kSigmas * ar.se) << ar.mean << " vs " << E;
}

// A spherical area light (cone sampling in Sphere::sample_from) seen from a point whose normal
// faces the centre: E = pi L sin^2(theta_max) = pi L r^2 / d^2. Also checks the solid-angle to
// area conversion of pdf_area against the cone density.
TEST(LightStat, SphereLightIrradianceMatchesClosedForm) {
    const double r = 0.5, d = 2.0, Lv = 3.0;
    auto sphere = std::make_shared<Sphere>(Vec3(0, d, 0), r);
    AreaLight light(Spectrum::constant(Lv), sphere);
    const LightSampleContext ref{Vec3(0, 0, 0), Vec3(0, 1, 0)};
    const double E = kPi * Lv * r * r / (d * d);
    PCG32 rng(31, 32);
    const int n = 200000;
    const MeanSE sa = estimate(n, [&](int) {
        auto ls = light.sample_li(ref, next2(rng), SampledWavelengths::single(600));
        if (!ls) return 0.0;
        EXPECT_LT(std::abs(ls->pdf - light.pdf_li(ref, ls->p, ls->n, ls->wi)), 1e-12 * ls->pdf);
        return ls->Le[0] * std::max(0.0, dot(ref.n, ls->wi)) / ls->pdf;
    });
    EXPECT_LT(std::abs(sa.mean - E), kSigmas * sa.se) << sa.mean << " vs " << E << " se " << sa.se;
    EXPECT_LT(sa.se, 0.01 * E);
    const MeanSE ar = estimate(n, [&](int) {
        auto ls = light.sample_li(ref, next2(rng), SampledWavelengths::single(600));
        if (!ls) return 0.0;
        const double cos_l = std::abs(dot(ls->n, ls->wi));
        return ls->Le[0] * std::max(0.0, dot(ref.n, ls->wi)) * cos_l / (sqr(ls->dist) * ls->pdf_area);
    });
    EXPECT_LT(std::abs(ar.mean - E), kSigmas * ar.se) << ar.mean << " vs " << E;
}

// Irradiance from the envmap by light sampling against a fine quadrature of le_escaped.
TEST(LightStat, EnvmapIrradianceMatchesQuadrature) {
    EnvironmentMap env(test_image(24, 12), 0.8, Transform::rotate(Vec3(0.3, 1, 0.2), 50));
    const double lambda = 560;
    const Vec3 nrm = normalize(Vec3(0.2, 0.9, -0.3));
    double Eq = 0;
    const int nt = 1500, np = 3000;
    for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) / nt * kPi;
        for (int j = 0; j < np; ++j) {
            const double ph = (j + 0.5) / np * 2 * kPi;
            const Vec3 w(std::sin(t) * std::cos(ph), std::sin(t) * std::sin(ph), std::cos(t));
            const double c = dot(nrm, w);
            if (c > 0) Eq += env.le_escaped(w, SampledWavelengths::single(lambda))[0] * c * std::sin(t);
        }
    }
    Eq *= (kPi / nt) * (2 * kPi / np);
    PCG32 rng(23, 24);
    const LightSampleContext ref{Vec3(), nrm};
    const MeanSE e = estimate(400000, [&](int) {
        auto ls = env.sample_li(ref, next2(rng), SampledWavelengths::single(lambda));
        return ls ? ls->Le[0] * std::max(0.0, dot(nrm, ls->wi)) / ls->pdf : 0.0;
    });
    // Quadrature of a continuous, piecewise-bilinear integrand on this grid is accurate to
    // well below 0.1%; allow that on top of the Monte Carlo error.
    EXPECT_LT(std::abs(e.mean - Eq), kSigmas * e.se + 1e-3 * Eq) << e.mean << " vs " << Eq << " se " << e.se;
    EXPECT_LT(e.se, 0.01 * Eq);
}

// Chi-square test of envmap direction sampling against pdf_li (tests/stat/chi2.h), in world
// (cos theta, phi) bins that are not aligned with the map's (u, v) bins because of the
// rotation. Two rotations, so the Sidak correction counts two tests. The map's polar rows are
// black here: the lat-long density has an integrable 1/sin(theta) singularity at the poles
// that adaptive Simpson quadrature cannot integrate (the unit test PdfIntegratesToOne covers
// the poles with a midpoint rule).
TEST(LightStat, EnvmapSamplingChiSquare) {
    const Transform rotations[2] = {Transform::rotate(Vec3(1, 0.2, 0.5), 70), Transform()};
    for (const Transform& r : rotations) {
        EnvironmentMap env(test_image(24, 12, true), 1.0, r);
        test::Chi2Options opt;
        opt.theta_res = 20;
        opt.phi_res = 40;
        opt.samples = 1000000;
        opt.test_count = 2;
        opt.integration_eps = 1e-9;
        const auto res = test::chi2_sphere_test(
            [&](PCG32& rng) -> std::optional<Vec3> {
                double pdf;
                const Vec3 w = env.sample_direction(next2(rng), &pdf);
                if (!(pdf > 0)) return std::nullopt;
                return w;
            },
            [&](const Vec3& w) { return env.pdf_li({}, Vec3(), Vec3(), w); }, opt);
        EXPECT_TRUE(res.passed) << res.message;
        EXPECT_NEAR(res.pdf_integral, 1.0, 1e-3);
    }
}

// sample_li uses exactly that direction and density.
TEST(LightStat, EnvmapSampleLiUsesSampleDirection) {
    EnvironmentMap env(test_image(24, 12), 1.0, Transform::rotate(Vec3(0, 1, 1), 30));
    PCG32 rng(29, 30);
    for (int i = 0; i < 1000; ++i) {
        const Vec2 u = next2(rng);
        double pdf;
        const Vec3 w = env.sample_direction(u, &pdf);
        auto ls = env.sample_li({Vec3(1, 1, 1), Vec3()}, u, SampledWavelengths::single(500));
        if (!ls) continue;
        EXPECT_EQ(ls->wi, w);
        EXPECT_EQ(ls->pdf, pdf);
    }
}

// The chi-square machinery must reject a wrong density: uniform directions against the
// envmap's pdf. Guards against a test that cannot fail.
TEST(LightStat, ChiSquareRejectsMismatchedDensity) {
    EnvironmentMap env(test_image(24, 12), 1.0, Transform());
    test::Chi2Options opt;
    opt.samples = 100000;
    const auto res = test::chi2_sphere_test(
        [&](PCG32& rng) -> std::optional<Vec3> { return warp::square_to_uniform_sphere(next2(rng)); },
        [&](const Vec3& w) { return env.pdf_li({}, Vec3(), Vec3(), w); }, opt);
    EXPECT_FALSE(res.passed) << res.message;
    EXPECT_LT(res.p_value, 1e-6);
}
