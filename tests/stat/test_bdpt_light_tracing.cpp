// BDPT's light-tracing strategy (t = 1): light vertices connected to the pinhole and splatted
// onto the film. A caustic seen directly (light -> smooth glass -> diffuse floor -> camera) is
// reached only by BSDF sampling from the floor (`path`) or by light tracing: BDPT must agree
// with `path` there. Splats are merged in a fixed order (thread-independent images), normalised
// over the output window (a crop renders the same pixels as the whole film does), and the
// per-strategy debug layers sum to the image.
#include <string>

#include "camera/film.h"
#include "stat/box_scene.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// The box with a smooth glass sphere and a light 2/5 of the default side at the same power:
// the sphere's caustic on the floor is seen directly by the camera. (Smaller lights make
// light tracing matter even more but `path` too noisy to test against in seconds.)
std::string caustic_box() {
    std::string xml = kCornellBox;
    const std::string rough = R"(<bsdf type="roughdielectric"><float name="alpha" value="0.3"/>)";
    xml.replace(xml.find(rough), rough.size(), R"(<bsdf type="dielectric">)");
    return xml;
}
const Defines kSmallLight = {{"light_scale", "0.2"}, {"radiance", "37.5"}, {"res", "24"}};

RenderResult render_once(const LoadedScene& ls, const FilmSpec& spec, int spp, uint64_t seed, int threads = 0,
                         bool layers = false) {
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed;
    opt.threads = threads;
    opt.progress = false;
    opt.debug_layers = layers;
    return render(*ls.scene, *ls.integrator, spec, opt);
}

}  // namespace

// `pt` at 2048 spp (per-block errors ~0.6%), shared by the agreement and sensitivity tests.
const std::vector<Estimate>& path_reference() {
    static const std::vector<Estimate> e = [] {
        Defines d = kSmallLight;
        d["integrator"] = "pt";
        const LoadedScene p = load_xml(caustic_box(), d);
        return block_estimates(p, *p.integrator, 2048, 12, 12, 6000);
    }();
    return e;
}

std::vector<Estimate> bdpt_blocks(const std::string& radiance) {
    Defines d = kSmallLight;
    d["integrator"] = "bdpt";
    d["radiance"] = radiance;
    const LoadedScene b = load_xml(caustic_box(), d);
    return block_estimates(b, *b.integrator, 128, 12, 12, 5000);
}

TEST(BdptLightTracing, MatchesPathOnADirectlySeenCaustic) {
    expect_agreement(bdpt_blocks("37.5"), path_reference(), 0.01, "caustic box: bdpt vs path");
}

// The same comparison must reject a light 3% brighter.
TEST(BdptLightTracing, DetectsALightThreePercentBrighter) {
    EXPECT_GT(count_disagreements(bdpt_blocks("38.625"), path_reference(), 0.01), 0);
}

TEST(BdptLightTracing, ImageDoesNotDependOnThreadCount) {
    Defines d = kSmallLight;
    d["integrator"] = "bdpt";
    d["res"] = "40";  // several tile groups of splats
    const LoadedScene ls = load_xml(caustic_box(), d);
    const RenderResult a = render_once(ls, ls.film, 2, 11, 1), c = render_once(ls, ls.film, 2, 11, 2);
    for (int y = 0; y < a.film.height(); ++y)
        for (int x = 0; x < a.film.width(); ++x) ASSERT_EQ(a.film.xyz(x, y).y, c.film.xyz(x, y).y) << x << "," << y;
}

// Camera importance is normalised over the output window: a crop renders the crop's pixels of
// the whole film (same expectation), although only the crop's camera rays are traced.
TEST(BdptLightTracing, CropWindowMatchesTheWholeFilm) {
    Defines d = kSmallLight;
    d["integrator"] = "bdpt";
    const LoadedScene ls = load_xml(caustic_box(), d);
    FilmSpec crop = ls.film;
    crop.crop_x = 6, crop.crop_y = 12, crop.crop_w = 12, crop.crop_h = 12;
    const int replicas = 12, block = 6;
    std::vector<std::vector<double>> full(4), part(4);
    for (int r = 0; r < replicas; ++r) {
        const RenderResult f = render_once(ls, ls.film, 16, 100 + uint64_t(r));
        const RenderResult c = render_once(ls, crop, 16, 900 + uint64_t(r));
        for (int b = 0; b < 4; ++b) {
            double sf = 0, sc = 0;
            for (int y = 0; y < block; ++y)
                for (int x = 0; x < block; ++x) {
                    const int cx = (b % 2) * block + x, cy = (b / 2) * block + y;
                    sc += c.film.xyz(cx, cy).y;
                    sf += f.film.xyz(cx + crop.crop_x, cy + crop.crop_y).y;
                }
            full[size_t(b)].push_back(sf), part[size_t(b)].push_back(sc);
        }
    }
    const auto estimate = [](const std::vector<double>& v) {
        double m = 0, var = 0;
        for (double x : v) m += x;
        m /= double(v.size());
        for (double x : v) var += (x - m) * (x - m);
        return Estimate{m, std::sqrt(var / double(v.size() - 1) / double(v.size())), int(v.size())};
    };
    std::vector<Estimate> ef, ec;
    for (int b = 0; b < 4; ++b) ef.push_back(estimate(full[size_t(b)])), ec.push_back(estimate(part[size_t(b)]));
    expect_agreement(ef, ec, 0.01, "crop vs whole film");
}

// `snell render --strategies`: the weighted contributions of all strategies of the lengths the
// layers cover add up to the image (max_depth 3 <= the 6 lengths the layers hold).
TEST(BdptLightTracing, StrategyLayersSumToTheImage) {
    std::string xml = caustic_box();
    const std::string depth = R"(<integer name="max_depth" value="6"/>)";
    xml.replace(xml.find(depth), depth.size(), R"(<integer name="max_depth" value="3"/>)");
    Defines d = kSmallLight;
    d["integrator"] = "bdpt";
    d["res"] = "16";
    const LoadedScene ls = load_xml(xml, d);
    const auto names = [&] {
        RenderOptions opt;
        opt.debug_layers = true;
        return dynamic_cast<const TileIntegrator&>(*ls.integrator).prepare(*ls.scene, ls.film, opt)->layer_names();
    }();
    ASSERT_EQ(names.size(), 1u + 3u + 4u);  // lengths 1..3: (0,2); (0,3) (1,2) (2,1); (0,4) ... (3,1)
    EXPECT_EQ(names.front(), "d1_s0_t2");
    EXPECT_EQ(names.back(), "d3_s3_t1");
    const RenderResult r = render_once(ls, ls.film, 4, 5, 0, true);
    double image = 0, layers = 0;
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x) {
            image += r.film.xyz(x, y).y;
            for (int k = 1; k <= int(names.size()); ++k) layers += r.film.layer_xyz(k, x, y).y;
        }
    EXPECT_GT(image, 0);
    EXPECT_NEAR(layers, image, 1e-9 * image);
    // Light tracing reaches the caustic: its layers are not empty.
    double t1 = 0;
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x) t1 += r.film.layer_xyz(int(names.size()), x, y).y;
    EXPECT_GT(t1, 0);
}

// An equal-time render of a splatting integrator keeps whole passes only: every pixel has the
// same number of samples, which the splat normalisation assumes.
TEST(BdptLightTracing, TimedRenderKeepsWholePasses) {
    Defines d = kSmallLight;
    d["integrator"] = "bdpt";
    const LoadedScene ls = load_xml(caustic_box(), d);
    RenderOptions opt;
    opt.time_limit = 0.3;
    opt.progress = false;
    const RenderResult r = render(*ls.scene, *ls.integrator, ls.film, opt);
    ASSERT_GT(r.spp_completed, 0u);
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x) ASSERT_EQ(r.film.samples(x, y), r.spp_completed) << x << "," << y;
    EXPECT_DOUBLE_EQ(r.spp_mean, double(r.spp_completed));
}

// Lights at infinity start light subpaths too (from a disk facing the sampled direction). A sun
// and a sky over a glass ball: BDPT must agree with `nee`, an independent estimator, wherever
// `nee` sees all the light. The sun's caustic under the ball (blocks 9 and 10) is reachable
// only by light tracing or MNEE, and MNEE is no reference there: with a directional light, BSDF
// sampling cannot cover the solutions the walk misses (the fold, paper Fig. 7), so MNEE is
// biased low. Measured at 256 spp x 12 replicas (with one and with four wavelengths): block 9
// bdpt 0.597 +- 0.002, mnee 0.582 +- 0.001; block 10 bdpt 0.655 +- 0.003, mnee 0.615 +- 0.008
// (issue 10 adds the missing solutions). The ball's refracted sunlight also reaches the floor
// beside the caustic (blocks 6 and 11), which `nee` misses too: at 4096 spp bdpt is 1.2 % and
// 1.0 % brighter there, 3.6 % and 56 % in blocks 9 and 10, and within 0.6 % elsewhere (issue 26:
// with the glass no longer dispersive by default the test's streams changed and block 11 showed
// it). A constant sky adds light from all directions (escaping camera paths, s = 0, against light
// subpaths from the sky).
namespace {
const char* kSunAndSky = R"(<scene version="3.0.0">
  <default name="integrator" value="bdpt"/>
  <default name="irradiance" value="3"/>
  <integrator type="$integrator"><integer name="max_depth" value="6"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 2.2, 2.2" target="0, 0.2, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="1.5"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0" y="0.55" z="0"/><float name="radius" value="0.35"/>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>
  <emitter type="directional"><vector name="direction" x="0.25" y="-1" z="-0.15"/>
    <rgb name="irradiance" value="$irradiance"/></emitter>
  <emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>
</scene>)";

std::vector<Estimate> sun_blocks(const std::string& integrator, const std::string& irradiance, int spp, uint64_t seed) {
    const LoadedScene ls = load_xml(kSunAndSky, {{"integrator", integrator}, {"irradiance", irradiance}});
    std::vector<Estimate> blocks = block_estimates(ls, *ls.integrator, spp, 12, 6, seed);
    // Drop the caustic under the ball and its halo (blocks 6, 9, 10 and 11 of 4 x 4), which nee
    // cannot render.
    blocks.erase(blocks.begin() + 9, blocks.begin() + 12);
    blocks.erase(blocks.begin() + 6);
    return blocks;
}

}  // namespace

TEST(BdptLightTracing, SunAndSkyMatchNee) {
    expect_agreement(sun_blocks("bdpt", "3", 64, 7000), sun_blocks("nee", "3", 64, 8000), 0.01,
                     "sun and sky: bdpt vs nee");
}

TEST(BdptLightTracing, SunAndSkyDetectASunThreePercentBrighter) {
    EXPECT_GT(count_disagreements(sun_blocks("bdpt", "3.09", 64, 7000), sun_blocks("nee", "3", 64, 8000), 0.01), 0);
}
