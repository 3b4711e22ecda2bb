// The image is a pure function of (scene, seed, spp): thread count must not change a bit.
#include <gtest/gtest.h>

#include "stat/render_stats.h"

using namespace snell;

TEST(Render, IndependentOfThreadCount) {
    const char* xml = R"(<scene version="3.0.0">
      <integrator type="nee"/>
      <sensor type="perspective"><transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
        <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="30"/></film></sensor>
      <shape type="sphere"><bsdf type="dielectric"/></shape>
      <shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-1.5"/></transform></shape>
      <emitter type="point"><point name="position" x="1" y="2" z="3"/><rgb name="intensity" value="10,10,10"/></emitter>
      <emitter type="constant"><rgb name="radiance" value="0.2,0.2,0.2"/></emitter>
    </scene>)";
    LoadedScene ls = test::load_xml(xml);
    RenderOptions opt;
    opt.spp = 5;
    opt.progress = false;
    opt.threads = 1;
    const RenderResult a = render(*ls.scene, *ls.integrator, ls.film, opt);
    opt.threads = 2;
    opt.tile_size = 7;
    const RenderResult b = render(*ls.scene, *ls.integrator, ls.film, opt);
    const auto ia = a.film.to_linear_srgb(), ib = b.film.to_linear_srgb();
    ASSERT_EQ(ia.size(), ib.size());
    size_t nonzero = 0;
    for (size_t i = 0; i < ia.size(); ++i) {
        ASSERT_EQ(ia[i], ib[i]) << "pixel component " << i;
        nonzero += ia[i] != 0;
    }
    EXPECT_GT(nonzero, ia.size() / 2);
    EXPECT_EQ(a.spp_completed, 5u);
    // A different seed gives a different image.
    opt.seed = 1;
    const RenderResult c = render(*ls.scene, *ls.integrator, ls.film, opt);
    EXPECT_NE(c.film.to_linear_srgb(), ia);
}
