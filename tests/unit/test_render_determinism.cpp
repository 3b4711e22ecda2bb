// The image is a pure function of (scene, seed, spp): thread count must not change a bit.
#include <gtest/gtest.h>

#include <string>

#include "io/stats_json.h"
#include "stat/render_stats.h"

using namespace snell;

namespace {

// A nee scene seen from (0, 0, 4) on a width x height film, with `body` (shapes, emitters).
std::string nee_scene(int width, int height, const std::string& body) {
    return R"(<scene version="3.0.0">
      <integrator type="nee"/>
      <sensor type="perspective"><transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
        <film type="hdrfilm"><integer name="width" value=")" +
           std::to_string(width) + R"("/><integer name="height" value=")" + std::to_string(height) +
           R"("/></film></sensor>)" + body + "</scene>";
}

RenderOptions quiet(int spp, int threads) {
    RenderOptions opt;
    opt.spp = spp;
    opt.progress = false;
    opt.threads = threads;
    return opt;
}

}  // namespace

TEST(Render, IndependentOfThreadCount) {
    LoadedScene ls = test::load_xml(nee_scene(40, 30, R"(
      <shape type="sphere"><bsdf type="dielectric"/></shape>
      <shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-1.5"/></transform></shape>
      <emitter type="point"><point name="position" x="1" y="2" z="3"/><rgb name="intensity" value="10,10,10"/></emitter>
      <emitter type="constant"><rgb name="radiance" value="0.2,0.2,0.2"/></emitter>)"));
    RenderOptions opt = quiet(5, 1);
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
    // So are the counts, summed over however many threads counted them; the stats JSON
    // finds them by the names their components registered (core/stats.h).
    RenderReport ra, rb;
    ra.set_counters(a.counters);
    rb.set_counters(b.counters);
    EXPECT_EQ(ra.paths, 40u * 30u * 5u);
    EXPECT_GT(ra.rays, ra.paths);
    EXPECT_GT(ra.shadow_rays, 0u);
    EXPECT_EQ(ra.rays, rb.rays);
    EXPECT_EQ(ra.shadow_rays, rb.shadow_rays);
    // Counts are integers and sum exactly; moments (per-technique contributions) are sums of
    // doubles whose last bits depend on which thread added what, so they agree to rounding.
    for (const auto& [name, value] : ra.counters.items()) {
        ASSERT_TRUE(rb.counters.contains(name)) << name;
        if (!value.is_object()) {
            EXPECT_EQ(value, rb.counters.at(name)) << name;
            continue;
        }
        EXPECT_EQ(value.at("count"), rb.counters.at(name).at("count")) << name;
        EXPECT_EQ(value.at("max"), rb.counters.at(name).at("max")) << name;
        for (const char* key : {"mean", "relative_variance"}) {
            const double x = value.at(key), y = rb.counters.at(name).at(key);
            EXPECT_NEAR(x, y, 1e-9 * std::abs(x)) << name << "." << key;
        }
    }
    EXPECT_EQ(ra.counters.size(), rb.counters.size());
    EXPECT_EQ(ra.counters.at("render.paths"), ra.paths);
    EXPECT_EQ(ra.counters.at("scene.rays"), ra.rays);
    EXPECT_EQ(ra.counters.at("mnee.walks_started"), 0u);  // registered (linked), not counted
    EXPECT_EQ(ra.counters.at("mnee.iteration_histogram"), nlohmann::json::array());
    // A different seed gives a different image.
    opt.seed = 1;
    const RenderResult c = render(*ls.scene, *ls.integrator, ls.film, opt);
    EXPECT_NE(c.film.to_linear_srgb(), ia);
}

// A sample's technique comes back in its estimate (SampleEstimate), not through a side channel:
// every pixel whose largest sample carries light knows the technique behind it, whatever
// thread rendered it.
TEST(Render, EachPixelsLargestSampleNamesItsTechnique) {
    LoadedScene ls = test::load_xml(nee_scene(24, 18, R"(
      <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform></shape>
      <emitter type="point"><point name="position" x="1" y="2" z="3"/><rgb name="intensity" value="10,10,10"/></emitter>)"));
    const RenderResult r = render(*ls.scene, *ls.integrator, ls.film, quiet(4, 2));
    ASSERT_FALSE(r.technique_names.empty());
    size_t lit = 0;
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x) {
            if (!(r.film.largest_sample_y(x, y) > 0)) continue;
            ++lit;
            const int t = r.film.largest_sample_technique(x, y);
            ASSERT_GE(t, 0) << "pixel " << x << "," << y;
            // Only a shadow ray lights a diffuse plane under a point light.
            EXPECT_EQ(r.technique_names[size_t(t)], "nee") << "pixel " << x << "," << y;
        }
    EXPECT_GT(lit, size_t(24 * 18 / 2));
}
