// White furnace and the spectral round trip through the whole renderer.
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {
// A closed white world: a sphere of white diffuse inside a constant white environment. Every
// path carries radiance exactly 1 at every wavelength, so every pixel must be sRGB (1,1,1).
const char* kFurnace = R"(<scene version="3.0.0">
  <default name="integrator" value="nee"/>
  <default name="bsdf" value="diffuse"/>
  <integrator type="$integrator"/>
  <sensor type="perspective">
    <float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <shape type="sphere"><float name="radius" value="1"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="1, 1, 1"/></bsdf></shape>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
</scene>)";
}  // namespace

class Furnace : public ::testing::TestWithParam<const char*> {};

TEST_P(Furnace, WhiteSphereInWhiteWorldIsWhite) {
    LoadedScene ls = load_xml(kFurnace, {{"integrator", GetParam()}});
    for (int c = 0; c < 3; ++c) {
        // One block covering the whole image; replicas give the standard error.
        const auto e = block_estimates(ls, *ls.scene->integrator(), 8, 6, 16, 77, c);
        ASSERT_EQ(e.size(), 1u);
        // 4 standard errors, plus the white illuminant's fit error: its sRGB is (1,1,1) to
        // 1e-4 per channel (Spectrum.WhiteIlluminantIsSrgbWhite checks that bound).
        EXPECT_NEAR(e[0].mean, 1.0, 4 * e[0].stderr_ + 1e-4) << "channel " << c;
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Furnace, ::testing::Values("path", "nee"));
