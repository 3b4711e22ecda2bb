// The shared scattering-step bookkeeping (integrators/scatter.h): Russian roulette keeps the
// throughput's expectation, undoes the radiance compression of refraction, and a dispersive
// refraction switches to the hero wavelength exactly once.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "integrators/scatter.h"

using namespace snell;

namespace {
BSDFSample transmission(double eta, double weight, bool hero_only) {
    BSDFSample bs;
    bs.lobe = kTransmission | kSpecular;
    bs.eta = eta;
    bs.weight = SampledSpectrum(weight);
    bs.hero_only = hero_only;
    return bs;
}
}  // namespace

TEST(Throughput, RouletteKeepsTheExpectation) {
    // Survival probability 0.3: the mean of beta over survivors and the dead is beta itself.
    PCG32 rng(5, 1);
    const int n = 400000;
    double sum = 0, survived = 0;
    for (int i = 0; i < n; ++i) {
        Throughput tp;
        tp.beta = SampledSpectrum(0.3);
        if (tp.survives_roulette(rng.next_double())) {
            sum += tp.beta[0];
            survived += 1;
        }
    }
    EXPECT_NEAR(survived / n, 0.3, 4 * std::sqrt(0.3 * 0.7 / n));
    // Each survivor carries beta / q = 1; the estimate of 0.3 has a binomial standard error.
    EXPECT_NEAR(sum / n, 0.3, 4 * std::sqrt(0.3 * 0.7 / n));
}

TEST(Throughput, RouletteUndoesTheRadianceCompressionOfRefraction) {
    const SampledWavelengths wl = SampledWavelengths::sample_visible(Vec2(0.3, 0.6));
    Throughput tp;
    // Entering glass of eta 1.5: radiance is scaled by 1 / 1.5^2, roulette must not read that
    // as absorption (survival stays at the 0.95 cap).
    tp.scatter(transmission(1.5, 1 / 2.25, false), wl, TransportMode::Radiance);
    EXPECT_DOUBLE_EQ(tp.eta_scale, 2.25);
    EXPECT_TRUE(tp.survives_roulette(0.949));
    EXPECT_NEAR(tp.beta[0], 1 / 2.25 / 0.95, 1e-15);
    // Importance transport carries no such compression.
    Throughput imp;
    imp.scatter(transmission(1.5, 1.0, false), wl, TransportMode::Importance);
    EXPECT_DOUBLE_EQ(imp.eta_scale, 1.0);
}

TEST(Throughput, DispersiveRefractionKeepsTheHeroOnce) {
    const SampledWavelengths wl = SampledWavelengths::sample_visible(Vec2(0.3, 0.6));
    Throughput tp;
    tp.scatter(transmission(1.33, 0.5, true), wl, TransportMode::Radiance);
    EXPECT_TRUE(tp.hero_only);
    EXPECT_DOUBLE_EQ(tp.beta[0], 0.5 * wl.count());
    for (int i = 1; i < kSpectrumSamples; ++i) EXPECT_EQ(tp.beta[i], 0.0);
    // A second dispersive refraction does not scale the hero again.
    tp.scatter(transmission(1 / 1.33, 0.5, true), wl, TransportMode::Radiance);
    EXPECT_DOUBLE_EQ(tp.beta[0], 0.25 * wl.count());
}
