// White furnace and the spectral round trip through the whole renderer.
#include "stat/furnace_scene.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

class Furnace : public ::testing::TestWithParam<const char*> {};

TEST_P(Furnace, WhiteSphereInWhiteWorldIsWhite) {
    LoadedScene ls = load_xml(kFurnace, {{"integrator", GetParam()}});
    for (int c = 0; c < 3; ++c) {
        // One block covering the whole image; replicas give the standard error.
        const auto e = block_estimates(ls, *ls.integrator, 8, 6, 16, 77, c);
        ASSERT_EQ(e.size(), 1u);
        // 4 standard errors, plus the white illuminant's fit error: its sRGB is (1,1,1) to
        // 1e-4 per channel (Spectrum.WhiteIlluminantIsSrgbWhite checks that bound).
        EXPECT_NEAR(e[0].mean, 1.0, 4 * e[0].stderr_ + 1e-4) << "channel " << c;
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Furnace, ::testing::Values("pt", "path", "nee", "hslt"));
