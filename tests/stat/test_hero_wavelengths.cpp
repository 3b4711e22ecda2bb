// Hero wavelengths (Wilkie et al. 2014): four stratified wavelengths per path remove the colour
// noise of one wavelength per path without changing what any estimator converges to.
#include "stat/furnace_scene.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

struct Whiteness {
    double chroma_rms = 0, chroma_max = 0;  ///< per pixel: |R/G - 1| and |B/G - 1|
    double mean_max = 0;                    ///< image mean: largest |channel - 1|
};

/// How white a 64 spp furnace render is. The radiance of every path is the same function of
/// wavelength (the white illuminant), so a pixel's colour error (its R/G and B/G) is spectral
/// noise alone, whatever noise the integrator's light sampling adds to its brightness.
Whiteness furnace_whiteness(const std::string& integrator, int spectral_samples, const std::string& sampler) {
    const LoadedScene ls =
        load_xml(kFurnace, {{"integrator", integrator}, {"spectral_samples", std::to_string(spectral_samples)}});
    RenderOptions opt;
    opt.spp = 64;
    opt.seed = 5;
    opt.progress = false;
    opt.sampler.type = sampler;
    const std::vector<float> rgb = render(*ls.scene, *ls.integrator, ls.film, opt).film.to_linear_srgb();
    Whiteness w;
    double sq = 0, mean[3] = {0, 0, 0};
    const size_t n = rgb.size() / 3;
    for (size_t i = 0; i < n; ++i) {
        const double r = rgb[3 * i], g = rgb[3 * i + 1], b = rgb[3 * i + 2];
        for (double c : {r / g - 1, b / g - 1}) sq += c * c, w.chroma_max = std::max(w.chroma_max, std::abs(c));
        mean[0] += r / n, mean[1] += g / n, mean[2] += b / n;
    }
    w.chroma_rms = std::sqrt(sq / double(2 * n));
    for (double m : mean) w.mean_max = std::max(w.mean_max, std::abs(m - 1));
    return w;
}

// A droplet with dispersion (Abbe number 30) on a coloured floor, a small area light and a
// dim sky: caustic, refraction seen through the drop, reflections, and a wavelength-dependent
// refraction that keeps the hero alone.
const char* kDispersiveDroplet = R"(<scene version="3.0.0">
  <default name="integrator" value="nee"/>
  <default name="spectral_samples" value="4"/>
  <default name="radiance" value="60"/>
  <integrator type="$integrator"><integer name="max_depth" value="8"/>
    <integer name="spectral_samples" value="$spectral_samples"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="35"/>
    <transform name="to_world"><lookat origin="0, 2.6, 3.2" target="0, 0.3, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="18"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0" y="0.45" z="0"/><float name="radius" value="0.6"/>
    DROP_BSDF</shape>
  <shape type="sphere"><point name="center" x="-2" y="3" z="0.5"/><float name="radius" value="0.3"/>
    <emitter type="area"><rgb name="radiance" value="$radiance"/></emitter></shape>
  <emitter type="constant"><rgb name="radiance" value="0.05, 0.05, 0.08"/></emitter>
</scene>)";

/// Block estimates (4 x 3 blocks of 6 x 6 pixels) of one channel of the droplet.
std::vector<Estimate> droplet_blocks(const std::string& integrator, int spectral_samples, int spp, uint64_t seed,
                                     int channel, const std::string& alpha = "0", const std::string& radiance = "60") {
    // alpha 0: the smooth `dielectric`; otherwise `roughdielectric` (Beckmann).
    const std::string bsdf =
        alpha == "0" ? R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/>)"
                       R"(<float name="abbe" value="30"/></bsdf>)"
                     : R"(<bsdf type="roughdielectric"><float name="alpha" value=")" + alpha +
                           R"("/><float name="int_ior" value="1.5"/><float name="abbe" value="30"/></bsdf>)";
    std::string xml = kDispersiveDroplet;
    xml.replace(xml.find("DROP_BSDF"), 9, bsdf);
    const LoadedScene ls = load_xml(
        xml,
        {{"integrator", integrator}, {"spectral_samples", std::to_string(spectral_samples)}, {"radiance", radiance}});
    return block_estimates(ls, *ls.integrator, spp, 12, 6, seed, channel);
}

}  // namespace

// Four wavelengths with the sobol sampler (the bundled scenes' set-up) make the furnace white:
// the wavelength pair is stratified across a pixel's samples too, so 64 samples carry 256
// well-spread wavelengths. One wavelength (the paper's set-up) leaves several percent of colour
// noise per pixel, and so do four with independent samples. Measured (this scene, seed 5):
// pt 0.17 % rms per pixel (4, sobol), 2.3 % (1, sobol), 5.1 % (4, independent); nee 1.2 %,
// 9.8 %, 5.3 %; image means within 0.11 % of white.
TEST(HeroWavelengths, FurnaceIsWhitePerChannel) {
    for (const char* integ : {"pt", "nee", "bdpt"}) {
        const Whiteness four = furnace_whiteness(integ, 4, "sobol"), one = furnace_whiteness(integ, 1, "sobol");
        const Whiteness indep = furnace_whiteness(integ, 4, "independent");
        std::printf(
            "%s at 64 spp: per-pixel colour error rms %.4f max %.4f, image mean off white by %.4f "
            "(4 wavelengths, sobol); rms %.4f (1, sobol); rms %.4f (4, independent)\n",
            integ, four.chroma_rms, four.chroma_max, four.mean_max, one.chroma_rms, indep.chroma_rms);
        // `pt` returns exactly the illuminant for every sample: its colour error is spectral
        // alone. nee and bdpt weight samples unequally (light sampling, MIS), which spoils part
        // of the stratification of the wavelengths across samples.
        if (std::string(integ) == "pt") {
            EXPECT_LT(four.chroma_rms, 0.005) << integ;
        }
        EXPECT_LT(four.chroma_rms, one.chroma_rms / 4) << integ;
        EXPECT_LT(four.mean_max, 0.005) << integ;
        EXPECT_GT(one.chroma_rms, 0.02) << integ;  // the colour noise the hero wavelengths remove
    }
}

// Each technique converges to the same image with four wavelengths as with one, per block and
// per colour channel (red and blue differ most between wavelengths), on a dispersive droplet:
// the smooth drop keeps the hero alone through refraction, the rough one too (its refracted
// directions depend on the wavelength), while reflections and everything outside the drop keep
// all four.
class HeroAgreement : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(HeroAgreement, FourWavelengthsAgreeWithOne) {
    const auto [integ, alpha] = GetParam();
    // `pt` finds the small light only by BSDF sampling: its replicas are heavy-tailed and need
    // more samples for Welch's test to hold; bdpt costs more per sample.
    const std::string name = integ;
    const int spp = name == "pt" ? 256 : name == "nee" ? 256 : name == "bdpt" ? 32 : 64;
    for (int channel : {0, 2}) {
        const auto four = droplet_blocks(integ, 4, spp, 100, channel, alpha);
        // One wavelength has several times the variance per sample: give it four times the samples.
        const auto one = droplet_blocks(integ, 1, spp * 4, 200, channel, alpha);
        const std::string what = std::string(integ) + " alpha " + alpha + " channel " + std::to_string(channel);
        expect_agreement(four, one, 0.01, what.c_str());
        const Estimate a = whole_image(four), b = whole_image(one);
        EXPECT_GT(welch_p_value(a, b), 0.01)
            << what << ": whole image " << a.mean << " +- " << a.stderr_ << " vs " << b.mean << " +- " << b.stderr_;
    }
}

INSTANTIATE_TEST_SUITE_P(Techniques, HeroAgreement,
                         ::testing::Combine(::testing::Values("pt", "nee", "mnee", "bdpt"),
                                            ::testing::Values("0", "0.1")),
                         [](const auto& info) {
                             return std::string(std::get<0>(info.param)) +
                                    (std::string(std::get<1>(info.param)) == "0" ? "_smooth" : "_rough");
                         });

// The same comparison, per block and for the whole image, sees a light 3 % brighter (so it can
// fail).
TEST(HeroAgreement, DetectsALightThreePercentBrighter) {
    int flagged = 0;
    for (int channel : {0, 2}) {
        const auto four = droplet_blocks("nee", 4, 256, 100, channel, "0", "61.8");
        const auto one = droplet_blocks("nee", 1, 1024, 200, channel, "0", "60");
        flagged += count_disagreements(four, one, 0.01);
        flagged += welch_p_value(whole_image(four), whole_image(one)) < 0.01;
    }
    EXPECT_GT(flagged, 0);
}
