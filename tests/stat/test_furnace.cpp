// White furnace and the spectral round trip through the whole renderer.
#include <cstdio>
#include <string>

#include "stat/furnace_scene.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

class Furnace : public ::testing::TestWithParam<const char*> {};

TEST_P(Furnace, WhiteSphereInWhiteWorldIsWhite) {
    LoadedScene ls = load_xml(kFurnace, {{"integrator", GetParam()}});
    // hslt reaches the sky by its large steps alone (path tracing, 30 % of its mutations): 8
    // mutations per pixel left its blue channel a standard error of 3 %, too wide to see 3 %.
    const int spp = std::string(GetParam()) == "hslt" ? 256 : 8;
    for (int c = 0; c < 3; ++c) {
        // One block covering the whole image; replicas give the standard error.
        const auto e = block_estimates(ls, *ls.integrator, spp, 6, 16, 77, c);
        ASSERT_EQ(e.size(), 1u);
        // 4 standard errors, plus the white illuminant's fit error: its sRGB is (1,1,1) to
        // 1e-4 per channel (Spectrum.WhiteIlluminantIsSrgbWhite checks that bound).
        std::printf("%s, channel %d: %.5f +- %.5f\n", GetParam(), c, e[0].mean, e[0].stderr_);
        EXPECT_NEAR(e[0].mean, 1.0, 4 * e[0].stderr_ + 1e-4) << "channel " << c;
        // The power to see a light 3 % too bright or too dark (issue 29 asks it of hslt).
        EXPECT_LT(4 * e[0].stderr_ + 1e-4, 0.03)
            << "channel " << c << ": a 3 % error could pass: " << e[0].mean << " +- " << e[0].stderr_;
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Furnace, ::testing::Values("pt", "path", "nee", "hslt"));
