#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "camera/film.h"
#include "camera/outlier_clamp.h"
#include "core/rng.h"
#include "core/spectrum.h"

using namespace snell;

namespace {
Vec3 pixel(const std::vector<float>& rgb, int w, int x, int y) {
    const size_t i = (size_t(y) * w + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}
}  // namespace

TEST(Film, ConstantSpectrumIsEqualEnergyWhite) {
    // Constant spectrum 1 has Y = 1 by normalisation; its x and z equal y up to the accuracy of
    // the analytic CMF fit (the tabulated CIE integrals of x̄, ȳ, z̄ agree to ~0.1%; the Wyman fit
    // to ~1%). Illuminant E in linear sRGB is M * (1,1,1) = row sums of the XYZ->sRGB matrix.
    Film film(3, 2);
    const Vec3 xyz = spectrum_to_xyz(Spectrum::constant(1.0));
    EXPECT_NEAR(xyz.y, 1.0, 1e-6);
    EXPECT_NEAR(xyz.x, 1.0, 0.02);
    EXPECT_NEAR(xyz.z, 1.0, 0.02);
    film.add(2, 1, xyz * 0.5);
    film.add(2, 1, xyz * 1.5);  // mean is xyz
    const std::vector<float> rgb = film.to_linear_srgb();
    ASSERT_EQ(rgb.size(), size_t(3 * 2 * 3));
    const Vec3 expect_e(3.2404542 - 1.5371385 - 0.4985314, -0.9692660 + 1.8760108 + 0.0415560,
                        0.0556434 - 0.2040259 + 1.0572252);
    const Vec3 c = pixel(rgb, 3, 2, 1);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], expect_e[k], 0.03) << k;
    // Exact agreement with the colour pipeline (float rounding only).
    const Vec3 exact = xyz_to_linear_srgb(xyz);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], exact[k], 1e-6 * std::abs(exact[k])) << k;
}

TEST(Film, WhiteIlluminantMapsToOne) {
    Film film(1, 1);
    film.add(0, 0, spectrum_to_xyz(Spectrum::from_rgb_illuminant(RGB(1, 1, 1)).scaled(0.25)));
    const Vec3 c = pixel(film.to_linear_srgb(), 1, 0, 0);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.25, 1e-4) << k;
}

TEST(Film, LayoutAndEmptyPixels) {
    // Row-major, 3 floats per pixel, x fastest; unsampled pixels are exactly zero.
    Film film(4, 3);
    film.add_sum(3, 0, linear_srgb_to_xyz(Vec3(3, 6, 9)), 3);  // mean (1,2,3)
    film.add(0, 2, linear_srgb_to_xyz(Vec3(0.5, 0.25, 0.125)));
    const std::vector<float> rgb = film.to_linear_srgb();
    ASSERT_EQ(rgb.size(), size_t(4 * 3 * 3));
    const Vec3 a = pixel(rgb, 4, 3, 0), b = pixel(rgb, 4, 0, 2);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(a[k], double(k + 1), 1e-5 * (k + 1));
        EXPECT_NEAR(b[k], 0.5 / (1 << k), 1e-6);
    }
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            if ((x == 3 && y == 0) || (x == 0 && y == 2)) continue;
            const Vec3 z = pixel(rgb, 4, x, y);
            EXPECT_EQ(z, Vec3()) << x << "," << y;
        }
}

TEST(Film, SampledWavelengthsConvergeToSpectrumXyz) {
    // Monte Carlo over wavelength, as the integrators do: four hero wavelengths per sample,
    // converted by SampledWavelengths::to_xyz. The pixel mean must agree with the deterministic spectrum_to_xyz within
    // 4 standard errors (per channel; 3 channels, so a false alarm has probability < 2e-4).
    const Spectrum s = Spectrum::from_rgb_illuminant(RGB(0.9, 0.4, 0.2));
    const int n = 200000;
    Film film(1, 1);
    PCG32 rng(12345, 7);
    Vec3 sum, sum2;
    for (int i = 0; i < n; ++i) {
        const double u = rng.next_double();
        const SampledWavelengths wl = SampledWavelengths::sample_visible(Vec2(u, rng.next_double()));
        const Vec3 xyz = wl.to_xyz(s.eval(wl));
        film.add(0, 0, xyz);
        const Vec3 rgb = xyz_to_linear_srgb(xyz);  // per-sample sRGB for the standard error
        sum += rgb;
        sum2 += rgb * rgb;
    }
    const Vec3 mean = pixel(film.to_linear_srgb(), 1, 0, 0);
    const Vec3 expect = xyz_to_linear_srgb(spectrum_to_xyz(s));
    for (int k = 0; k < 3; ++k) {
        const double m = sum[k] / n;
        const double se = std::sqrt((sum2[k] / n - m * m) / (n - 1));
        EXPECT_NEAR(mean[k], m, 1e-5 * std::abs(m) + 1e-7) << k;  // film mean == sample mean
        EXPECT_NEAR(mean[k], expect[k], 4.0 * se) << "channel " << k << " se " << se;
    }
}

// The share of a pixel's luminance carried by its largest sample: 1 / n for n equal samples,
// near 1 for a firefly; pixel_dominance counts the pixels above one half.
TEST(Film, LargestSampleShareAndDominance) {
    Film film(4, 1);
    for (int i = 0; i < 4; ++i) film.add(0, 0, Vec3(0.1, 1.0, 0.2));  // four equal samples
    film.add_sum(1, 0, Vec3(0, 3.0, 0), 3, Vec3(0, 1.0, 0));          // three samples, largest 1
    film.add(1, 0, Vec3(0, 0, 0));
    // One sample of 9 among 8: a firefly, delivered by technique 3 (SampleTracer::technique_names).
    film.add_sum(2, 0, Vec3(0, 10.0, 0), 8, Vec3(0, 9.0, 0), 3);
    film.add_sum(3, 0, Vec3(0, 2.0, 0), 4, Vec3(0, 2.0, 0), 1);  // one lit sample of 4, beside a bright pixel
    film.add_sum(3, 0, Vec3(), 0, Vec3(0, 1.5, 0), 5);           // a smaller largest keeps technique 1
    EXPECT_DOUBLE_EQ(film.largest_sample_share(0, 0), 0.25);
    EXPECT_DOUBLE_EQ(film.largest_sample_share(1, 0), 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(film.largest_sample_share(2, 0), 0.9);
    EXPECT_DOUBLE_EQ(film.largest_sample_share(3, 0), 1.0);
    const PixelDominance d = pixel_dominance(film);
    EXPECT_EQ(d.pixels, 4u);
    EXPECT_EQ(d.dominated, 2u);
    // Pixel 2's sample (9) is over ten times its neighbours' mean (0.75 and 0.5); pixel 3's (2)
    // is not (its neighbour is 1.25).
    EXPECT_EQ(d.outliers, 1u);
    EXPECT_DOUBLE_EQ(d.max_share, 1.0);
    // Dominated pixels by the technique of their largest sample.
    EXPECT_EQ(film.largest_sample_technique(0, 0), -1);
    EXPECT_EQ(film.largest_sample_technique(3, 0), 1);
    EXPECT_EQ(d.dominated_by_technique, (std::vector<uint64_t>{0, 1, 0, 1}));
    EXPECT_EQ(Film(1, 1).largest_sample_share(0, 0), 0.0) << "an empty pixel has no share";
}

// The outlier clamp (mnee's biased mode): a pixel's largest sample is scaled, colour and all,
// to max_sample_share / (1 - max_sample_share) times the sum of the others; pixels without a
// dominating sample, and pixels of one sample, are unchanged; the order samples arrive in does
// not matter; pixel_dominance reports the clamped pixels and the luminance removed.
TEST(Film, MaxSampleShareClampsTheLargestSampleOnly) {
    const Vec3 firefly(2.0, 9.0, 4.0), plain(0.5, 1.0, 0.25);
    Film a(3, 1), b(3, 1);
    for (int i = 0; i < 3; ++i) a.add(0, 0, plain);
    a.add(0, 0, firefly);
    b.add(0, 0, firefly);  // the same samples in another order, and a whole-pixel sum
    b.add_sum(0, 0, plain * 3.0, 3, plain);
    for (Film* f : {&a, &b}) {
        for (int i = 0; i < 4; ++i) f->add(1, 0, plain * (1.0 + 0.1 * i));  // largest share 0.28
        f->add(2, 0, firefly);                                              // one sample: nothing to compare
        apply_outlier_clamp(*f, 0.5);
    }
    // Pixel 0: Y = 3 + 9; the firefly is scaled to 3 (the sum of the others): factor 1/3.
    const Vec3 expect = (plain * 3.0 + firefly * (3.0 / 9.0)) / 4.0;
    for (const Film* f : {&a, &b}) {
        const Vec3 v = f->xyz(0, 0);
        EXPECT_NEAR(v.x, expect.x, 1e-12);
        EXPECT_NEAR(v.y, expect.y, 1e-12);
        EXPECT_NEAR(v.z, expect.z, 1e-12);
        EXPECT_DOUBLE_EQ(f->largest_sample_share(0, 0), 0.5);
        EXPECT_DOUBLE_EQ(f->clamped_y(0, 0), 6.0);
        EXPECT_EQ(f->clamped_y(1, 0), 0.0);
        EXPECT_NEAR(f->xyz(1, 0).y, 1.15, 1e-12);
        EXPECT_EQ(f->clamped_y(2, 0), 0.0);
        EXPECT_DOUBLE_EQ(f->xyz(2, 0).y, 9.0);
        const PixelDominance d = pixel_dominance(*f);
        EXPECT_EQ(d.dominated, 1u) << "the single-sample pixel is all one sample";
        EXPECT_EQ(d.clamped, 1u);
        EXPECT_NEAR(d.clamped_share, 6.0 / (12.0 + 4.6 + 9.0), 1e-12);
    }
    // A tighter share: the firefly carries at most 0.25, i.e. a third of the others (1).
    apply_outlier_clamp(a, 0.25);
    EXPECT_DOUBLE_EQ(a.largest_sample_share(0, 0), 0.25);
    EXPECT_NEAR(a.xyz(0, 0).y, 4.0 / 4.0, 1e-12);
    apply_outlier_clamp(a, 0);
    EXPECT_NEAR(a.xyz(0, 0).y, 12.0 / 4.0, 1e-12) << "0 turns the clamp off";
}

// The clamp is consistent: on heavy-tailed samples (Pareto, index 1.5: finite mean 3, infinite
// variance) the luminance it removes shrinks as the pixels' sample count grows.
TEST(Film, MaxSampleShareBiasVanishesWithMoreSamples) {
    PCG32 rng(7, 11);
    const auto bias = [&](int n) {
        Film f(256, 1);
        for (int x = 0; x < 256; ++x)
            for (int i = 0; i < n; ++i) f.add(x, 0, Vec3(0, std::pow(1.0 - rng.next_double(), -1.0 / 1.5), 0));
        apply_outlier_clamp(f, 0.5);
        return pixel_dominance(f).clamped_share;
    };
    const double b4 = bias(4), b64 = bias(64), b1024 = bias(1024);
    std::cout << "[clamp] luminance removed at 4, 64, 1024 samples: " << b4 << ", " << b64 << ", " << b1024 << "\n";
    EXPECT_GT(b4, 0.02);
    EXPECT_LT(b64, b4 / 3);
    EXPECT_LT(b1024, b64 / 3);
}

namespace {
/// The image's summed luminance (pixel means).
double image_y(const Film& f) {
    double s = 0;
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x) s += f.xyz(x, y).y;
    return s;
}
}  // namespace

// The clamp's spread on a firefly amid an even background (4 samples of Y = 1 per pixel; one
// pixel's fourth sample is 40): the clamp takes 37 of its 40 (9.25 of the pixel's mean). Over the
// 3x3 disc each piece (1.03) would carry half of a pixel of mean 1; over the 21 pixels of radius
// 2 a piece (0.44) carries 0.31. So the smallest disc that leaves no pixel dominated is radius 2,
// the image keeps all its light, and no pixel is dominated; radius 0 drops the light instead.
TEST(Film, ClampSpreadKeepsTheLightOnTheSmallestUndominatedDisc) {
    const auto make = [] {
        Film f(16, 16);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (int i = 0; i < 4; ++i)
                    f.add(x, y, Vec3(0.5, 1.0, 0.5) * (x == 7 && y == 8 && i == 3 ? 40.0 : 1.0));
        return f;
    };
    Film raw = make(), dropped = make(), spread = make();
    apply_outlier_clamp(dropped, 0.5);
    apply_outlier_clamp(spread, 0.5, 8);
    EXPECT_NEAR(image_y(raw) - image_y(dropped), 37.0 / 4.0, 1e-9);
    EXPECT_NEAR(image_y(spread), image_y(raw), 1e-9) << "the spread keeps the light the clamp takes";
    EXPECT_EQ(spread.spread_radius_at(7, 8), 2);
    EXPECT_EQ(spread.spread_radius_at(0, 0), 0) << "unclamped pixels spread nothing";
    EXPECT_NEAR(spread.xyz(9, 9).y, 1.0 + 9.25 / 21.0, 1e-12) << "(2, 1) from the firefly: in the disc";
    EXPECT_DOUBLE_EQ(spread.xyz(9, 10).y, 1.0) << "(2, 2): outside it";
    EXPECT_NEAR(spread.xyz(9, 9).x / spread.xyz(9, 9).y, 0.5, 1e-12) << "the pieces keep the firefly's colour";
    const double p = 9.25 / 21.0;  // the piece outweighs the pixel's own largest sample (1 of 4: 0.25)
    EXPECT_NEAR(spread.largest_sample_share(9, 9), p / (1 + p), 1e-12) << "a piece counts as a contribution";
    const PixelDominance d = pixel_dominance(spread);
    EXPECT_EQ(d.dominated, 0u);
    EXPECT_EQ(d.clamped, 1u);
    EXPECT_EQ(d.spread_radius, 2);
    EXPECT_NEAR(d.spread_share, d.clamped_share, 1e-12);
    EXPECT_EQ(pixel_dominance(dropped).spread_share, 0.0);
}

// A caustic's dim halo at a few samples per pixel: each of 16 samples lands in the light with
// probability 1/16 and then carries 16 (mean 1). Most lit pixels have one such sample, which the
// clamp alone takes whole (the others sum to 0): the halo loses 40 % of its light. Spread, the
// pieces of neighbouring samples add up to an image whose mean is the halo's, in which no pixel
// is dominated. A lone firefly on black would dominate every pixel of any disc: its light is
// cut where it would dominate (everywhere), as by the clamp alone, and the pixel is counted.
TEST(Film, ClampSpreadTurnsARareSampleHaloIntoItsMean) {
    PCG32 rng(3, 5);
    const auto halo = [&] {
        Film f(64, 64);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x)
                for (int i = 0; i < 16; ++i) f.add(x, y, Vec3(0, rng.next_double() < 1.0 / 16 ? 16.0 : 0.0, 0));
        return f;
    };
    Film dropped = halo(), spread = halo();
    apply_outlier_clamp(dropped, 0.5);
    apply_outlier_clamp(spread, 0.5, 8);
    const double pixels = 64.0 * 64.0;
    std::cout << "[spread] halo mean " << image_y(spread) / pixels << " (clamp alone " << image_y(dropped) / pixels
              << "), widest disc " << pixel_dominance(spread).spread_radius << "\n";
    EXPECT_LT(image_y(dropped) / pixels, 0.7) << "the clamp alone takes the light of every one-sample pixel";
    EXPECT_NEAR(image_y(spread) / pixels, 1.0, 0.03);
    const PixelDominance d = pixel_dominance(spread);
    EXPECT_EQ(d.dominated, 0u);
    EXPECT_GT(d.spread_radius, 1);
    EXPECT_LT(d.clamped_share - d.spread_share, 0.01) << "little is dropped (at the image's edge)";

    Film lone(32, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            if (x == 10 && y == 10)
                lone.add_sum(x, y, Vec3(0, 50, 0), 4, Vec3(0, 50, 0), 3);  // one sample of 50, three of 0
            else
                lone.add_sum(x, y, Vec3(), 4, Vec3(), 0);
    apply_outlier_clamp(lone, 0.5, 3);
    EXPECT_NEAR(image_y(lone), 0.0, 1e-12);
    const PixelDominance l = pixel_dominance(lone);
    EXPECT_EQ(l.dominated, 0u);
    EXPECT_EQ(l.clamped, 1u);
    EXPECT_EQ(l.spread_dropped, 1u);
    EXPECT_EQ(l.spread_share, 0.0);
}

// A firefly beside a shadow: every disc around it reaches black pixels, where any piece is all of
// the pixel, so no disc over all pixels hides it. Over the lit pixels alone one does (radius 2),
// and the shadow stays black. The lit pixels have 4 or 8 samples (rows alternate): the shares
// of the light taken and spread back are sums of samples, and agree exactly when nothing is
// dropped.
TEST(Film, ClampSpreadBesideAShadowKeepsTheShadowBlack) {
    const auto make = [] {
        Film f(32, 16);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 32; ++x) {
                const int n = x < 16 && y % 2 ? 8 : 4;
                for (int i = 0; i < n; ++i) {
                    const double v = x >= 16 ? 0.0 : (x == 15 && y == 8 && i == 3 ? 40.0 : 1.0);
                    f.add(x, y, Vec3(v, v, v));
                }
            }
        return f;
    };
    Film raw = make(), spread = make();
    apply_outlier_clamp(spread, 0.5, 8);
    EXPECT_NEAR(image_y(spread), image_y(raw), 1e-9);
    EXPECT_EQ(spread.spread_radius_at(15, 8), 2);
    for (int y = 0; y < 16; ++y)
        for (int x = 16; x < 32; ++x) ASSERT_EQ(spread.xyz(x, y).y, 0.0) << x << ", " << y;
    const PixelDominance d = pixel_dominance(spread);
    EXPECT_EQ(d.dominated, 0u);
    EXPECT_EQ(d.spread_dropped, 0u);
    EXPECT_NEAR(d.spread_share, d.clamped_share, 1e-15);
}

// A firefly no disc hides, not even over the lit pixels alone (cap 1: a 3x3 film whose other
// pixels are dim, 4 samples of 0.01): it stays, and each pixel keeps of its piece only the level
// c at which the piece no longer dominates, c = s (own + c), here c = own. So every corner is
// own + own = 0.02, the centre (own 0.015 after the clamp) 0.03, no pixel is dominated, all nine
// are counted as cut, and the light lost is the rest of the pieces.
TEST(Film, ClampSpreadCutsAnUnhiddenFireflyToTheLevelThatDoesNotDominate) {
    Film f(3, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x)
            for (int i = 0; i < 4; ++i) f.add(x, y, Vec3(1, 1, 1) * (x == 1 && y == 1 && i == 3 ? 40.0 : 0.01));
    apply_outlier_clamp(f, 0.5, 1);
    EXPECT_NEAR(f.xyz(0, 0).y, 0.02, 1e-9);
    EXPECT_NEAR(f.xyz(2, 1).y, 0.02, 1e-9);
    EXPECT_NEAR(f.xyz(1, 1).y, 0.03, 1e-9);
    const PixelDominance d = pixel_dominance(f);
    EXPECT_EQ(d.dominated, 0u);
    EXPECT_EQ(d.spread_dropped, 9u);
    EXPECT_NEAR(d.spread_share / d.clamped_share, (8 * 0.01 + 0.015) / ((40 - 0.03) / 4), 1e-9);
}

TEST(Film, MergedFilmsAreTheFilmOfAllTheirSamples) {
    // Issue 27: samples split over films (threads, ranks, farm tasks) and merged in any order
    // give the film that took them all, bit for bit; splats too.
    PCG32 rng(7, 3);
    Film all(3, 2), a(3, 2), b(3, 2), c(3, 2);
    Film* parts[3] = {&a, &b, &c};
    for (int k = 0; k < 300; ++k) {
        const int x = k % 3, y = (k / 3) % 2;
        const Vec3 xyz(rng.next_double() * 1e3, std::ldexp(rng.next_double(), -int(rng.next_double() * 40)),
                       rng.next_double());
        PixelSamples one;
        one.add(xyz, k % 4);
        all.add_samples(x, y, one);
        parts[k % 3]->add_samples(x, y, one);
        const Vec3 splat(rng.next_double(), rng.next_double() * 1e-9, rng.next_double() * 1e6);
        all.add_splat(x, y, splat, k % 2);
        parts[(k + 1) % 3]->add_splat(x, y, splat, k % 2);
    }
    Film merged = c;
    merged.merge(a);
    merged.merge(b);
    EXPECT_TRUE(merged.same_samples(all));
    EXPECT_EQ(merged.largest_sample_technique(1, 1), all.largest_sample_technique(1, 1));
    // One sample fewer is not the same film.
    Film fewer = c;
    fewer.merge(a);
    EXPECT_FALSE(fewer.same_samples(all));
}
