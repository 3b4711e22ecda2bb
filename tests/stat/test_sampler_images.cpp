// The pixel samplers in whole renders: on a directly lit scene every stratified sampler gives
// a lower per-pixel variance than `independent` at the same spp (across seeds), and renders
// stay a pure function of the seed whatever the thread count.
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// A plane under a rectangular area light, with a sphere casting a soft shadow and a sky:
// direct lighting only (max_depth 2), so the integrand of a pixel is smooth in few dimensions.
const char* kDirect = R"(<scene version="3.0.0">
  <integrator type="nee"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 2, 3" target="0, 0.2, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0.2" y="0.4" z="0"/><float name="radius" value="0.4"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate x="-0.5" y="2" z="0.3"/></transform>
    <emitter type="area"><rgb name="radiance" value="8, 8, 8"/></emitter></shape>
  <emitter type="constant"><rgb name="radiance" value="0.1, 0.1, 0.1"/></emitter>
</scene>)";

/// Mean over pixels and channels of the variance across `seeds` renders at `spp`.
double mean_pixel_variance(const LoadedScene& ls, const std::string& sampler, int spp, int seeds) {
    std::vector<double> sum, sq;
    for (int s = 0; s < seeds; ++s) {
        RenderOptions opt;
        opt.spp = spp;
        opt.seed = uint64_t(1000 + 17 * s);
        opt.progress = false;
        opt.sampler.type = sampler;
        const std::vector<float> rgb = render(*ls.scene, *ls.integrator, ls.film, opt).film.to_linear_srgb();
        sum.resize(rgb.size(), 0.0);
        sq.resize(rgb.size(), 0.0);
        for (size_t i = 0; i < rgb.size(); ++i) sum[i] += rgb[i], sq[i] += double(rgb[i]) * rgb[i];
    }
    double v = 0;
    for (size_t i = 0; i < sum.size(); ++i) {
        const double m = sum[i] / seeds;
        v += (sq[i] - seeds * m * m) / (seeds - 1);
    }
    return v / double(sum.size());
}

}  // namespace

class SamplerImages : public ::testing::TestWithParam<const char*> {};

TEST_P(SamplerImages, LowerVarianceThanIndependent) {
    const LoadedScene ls = load_xml(kDirect);
    const double indep = mean_pixel_variance(ls, "independent", 16, 24);
    const double v = mean_pixel_variance(ls, GetParam(), 16, 24);
    std::printf("%s: per-pixel variance %.3g, independent %.3g, ratio %.3f\n", GetParam(), v, indep, v / indep);
    // With 24 seeds the ratio of two variance estimates has a relative error of ~0.3 at worst
    // per pixel, far less averaged over 576 values; stratification must buy a clear factor.
    EXPECT_LT(v, 0.7 * indep) << GetParam();
}

TEST_P(SamplerImages, DeterministicWhateverTheThreadCount) {
    const LoadedScene ls = load_xml(kDirect);
    std::vector<std::vector<float>> images;
    for (int threads : {1, 2, 3}) {
        RenderOptions opt;
        opt.spp = 8;
        opt.seed = 3;
        opt.threads = threads;
        opt.tile_size = 5;
        opt.progress = false;
        opt.sampler.type = GetParam();
        images.push_back(render(*ls.scene, *ls.integrator, ls.film, opt).film.to_linear_srgb());
    }
    EXPECT_EQ(images[0], images[1]);
    EXPECT_EQ(images[0], images[2]);
}

INSTANTIATE_TEST_SUITE_P(Types, SamplerImages, ::testing::Values("stratified", "multijitter", "ldsampler", "sobol"));
