// Path-tracer features that `path` vs `nee` agreement cannot see, because both estimators
// share them: Russian roulette (unbiased only if survivors are reweighted), hide_emitters,
// hide_specular_emitters and max_depth (which emission is counted), Beer-Lambert absorption
// inside dielectrics.
#include <algorithm>
#include <utility>

#include "stat/replica_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// A closed white box with a large light and one red wall, 16x16: long paths matter here
// (albedo 0.8), so a roulette that forgot to reweight survivors darkens the image by far
// more than the ~0.4% relative standard error of the whole-image difference.
const char* kBox = R"(<scene version="3.0.0">
  <default name="rr_depth" value="5"/>
  <integrator type="nee">
    <integer name="max_depth" value="10"/><integer name="rr_depth" value="$rr_depth"/>
  </integrator>
  <sensor type="perspective">
    <float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0, 1, 2.9" target="0, 1, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/><translate y="1"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="90"/><translate x="-1" y="1"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.2, 0.2"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="-90"/><translate x="1" y="1"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><translate y="2"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="180"/><translate y="1" z="3"/></transform><ref id="white"/></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="1.99"/></transform>
    <emitter type="area"><rgb name="radiance" value="4"/></emitter>
  </shape>
</scene>)";

// Pixels the `removed` image lights: shown = hidden + removed up to float rounding; every other
// pixel bit-identical in shown and hidden. Returns {pixels removed lights, other pixels lit}.
std::pair<size_t, size_t> expect_only_removed_pixels_change(const std::vector<float>& shown,
                                                            const std::vector<float>& hidden,
                                                            const std::vector<float>& removed) {
    EXPECT_EQ(shown.size(), hidden.size());
    size_t removed_px = 0, lit_px = 0;
    for (size_t i = 0; i + 2 < std::min(shown.size(), hidden.size()); i += 3) {
        const bool changes = removed[i] != 0 || removed[i + 1] != 0 || removed[i + 2] != 0;
        removed_px += changes;
        lit_px += !changes && shown[i + 1] > 0;
        for (size_t c = i; c < i + 3; ++c) {
            if (changes) {
                const double scale = std::abs(shown[c]) + std::abs(removed[c]) + 1e-6;
                EXPECT_NEAR(shown[c], hidden[c] + removed[c], 1e-5 * scale) << "pixel " << i / 3;
            } else {
                EXPECT_EQ(hidden[c], shown[c]) << "pixel " << i / 3;
            }
        }
    }
    return {removed_px, lit_px};
}

}  // namespace

// Roulette from the first bounce against (practically) no roulette: same expectation.
TEST(RussianRoulette, IsUnbiased) {
    LoadedScene early = load_xml(kBox, {{"rr_depth", "1"}});
    LoadedScene never = load_xml(kBox, {{"rr_depth", "100"}});
    expect_replicas_agree(replica_stats(early, 64, 4, 10), replica_stats(never, 64, 4, 20), "rr_depth 1 vs 100");
}

// A light seen directly, and a floor it lights. Emission found at the camera vertex uses no
// random numbers, so with the same seed the three renders below trace the same paths:
// shown = hidden + direct up to float rounding, where `hidden` sets hide_emitters and `direct`
// sets max_depth 1 (only directly seen emitters). Pixels that do not see the light directly
// must be bit-identical with and without hide_emitters, and lit (emission at depth >= 1 kept).
TEST(HideEmittersAndMaxDepth, OnlyDirectlySeenEmissionChanges) {
    const char* xml = R"(<scene version="3.0.0">
      <default name="integrator" value="pt"/><default name="hide" value="false"/><default name="depth" value="-1"/>
      <integrator type="$integrator">
        <boolean name="hide_emitters" value="$hide"/><integer name="max_depth" value="$depth"/>
      </integrator>
      <sensor type="perspective"><float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, 1, 3" target="0, 0.6, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film></sensor>
      <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate x="1" angle="-90"/></transform></shape>
      <shape type="rectangle"><transform name="to_world"><scale value="0.4"/><rotate x="1" angle="40"/><translate y="1.2" z="-0.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>
    </scene>)";
    for (const char* integ : {"pt", "nee"}) {
        SCOPED_TRACE(integ);
        const auto shown = render_rgb(load_xml(xml, {{"integrator", integ}}), 16, 5);
        const auto hidden = render_rgb(load_xml(xml, {{"integrator", integ}, {"hide", "true"}}), 16, 5);
        const auto direct = render_rgb(load_xml(xml, {{"integrator", integ}, {"depth", "1"}}), 16, 5);
        const auto [light_px, lit_px] = expect_only_removed_pixels_change(shown, hidden, direct);
        EXPECT_GT(light_px, 8u);
        std::printf("%s: %zu pixels see the light, %zu of the others are lit\n", integ, light_px, lit_px);
        EXPECT_GT(lit_px, 40u);  // the equality checks above are not vacuous (64 and 253 seen)
    }
}

// A small light above a mirror floor, seen in the mirror; a wall lit by it. With
// hide_specular_emitters the light's mirror image (the path camera, mirror, light: C S L) is
// black and nothing else changes. With a black wall, every light that reaches the camera comes
// that way, so the image with both hide flags is black, for every integrator of the path family
// and `direct`. With a grey wall the same seed traces the same paths, so the grey scene's shown -
// hidden equals the black scene's mirror image, and the pixels without one are bit-identical
// (for bdpt too: s = 0 is the mirror image's one strategy, and both renders splat alike).
TEST(HideSpecularEmitters, HidesTheLightsMirrorImageAlone) {
    const char* xml = R"(<scene version="3.0.0">
      <default name="integrator" value="pt"/><default name="hide" value="false"/><default name="albedo" value="0"/>
      <integrator type="$integrator">
        <boolean name="hide_emitters" value="true"/><boolean name="hide_specular_emitters" value="$hide"/>
      </integrator>
      <sensor type="perspective"><float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, 1, 3" target="0, 0.2, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film></sensor>
      <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="conductor"><string name="material" value="none"/></bsdf></shape>
      <shape type="rectangle"><transform name="to_world"><scale value="2"/><translate y="1" z="-1.5"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="$albedo"/></bsdf></shape>
      <shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="90"/><translate y="1.5" z="-0.6"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>
    </scene>)";
    for (const char* integ : {"pt", "nee", "mnee", "bdpt", "direct"}) {
        SCOPED_TRACE(integ);
        const auto image = render_rgb(load_xml(xml, {{"integrator", integ}}), 16, 3);
        const auto black = render_rgb(load_xml(xml, {{"integrator", integ}, {"hide", "true"}}), 16, 3);
        size_t image_px = 0;
        for (size_t i = 0; i < image.size(); i += 3) {
            image_px += image[i + 1] > 0;
            for (size_t c = i; c < i + 3; ++c) EXPECT_EQ(black[c], 0.0f) << "pixel " << i / 3;
        }
        std::printf("%s: the mirror image covers %zu pixels\n", integ, image_px);
        EXPECT_GT(image_px, 10u);  // the check above is not vacuous
        const auto shown = render_rgb(load_xml(xml, {{"integrator", integ}, {"albedo", "0.5"}}), 16, 3);
        const auto hidden =
            render_rgb(load_xml(xml, {{"integrator", integ}, {"albedo", "0.5"}, {"hide", "true"}}), 16, 3);
        EXPECT_GT(expect_only_removed_pixels_change(shown, hidden, image).second, 40u);
    }
    // hslt has no such switch: it says so instead of rendering the glints.
    EXPECT_THROW(load_xml(xml, {{"integrator", "hslt"}, {"hide", "true"}}), SceneError);
    EXPECT_NO_THROW(load_xml(xml, {{"integrator", "hslt"}}));
}

// Looking through an absorbing, index-matched cube ([-1,1]^3, IOR 1.0001 in air: Fresnel
// reflectance 2.5e-9, bending 1e-4) at a white sky: every camera ray travels 2 / cos(theta)
// inside, so the pixel ratio absorbing / clear is exp(-2 sigma_a / cos(theta)). Same seed, so
// both renders take the same paths and wavelengths and the ratio has no sampling noise; the
// 3e-4 tolerance covers the spread of cos(theta) over a pixel at this 4-degree field of view.
TEST(BeerLambert, AbsorptionInsideADielectricFollowsPathLength) {
    const char* xml = R"(<scene version="3.0.0">
      <default name="sigma" value="0"/>
      <integrator type="path"/>
      <sensor type="perspective"><float name="fov" value="4"/>
        <transform name="to_world"><lookat origin="0, 0, 6" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
      <shape type="cube"><bsdf type="dielectric">
        <float name="int_ior" value="1.0001"/><float name="ext_ior" value="1"/><float name="sigma_a" value="$sigma"/>
      </bsdf></shape>
      <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
    </scene>)";
    const double sigma = 0.5;
    const LoadedScene clear = load_xml(xml);
    const LoadedScene absorbing = load_xml(xml, {{"sigma", "0.5"}});
    const auto a = render_rgb(clear, 16, 9);
    const auto b = render_rgb(absorbing, 16, 9);
    const PerspectiveCamera& cam = *clear.scene->camera()->pinhole();
    const int w = clear.film.out_width();
    for (size_t i = 0; i < a.size(); i += 3) {
        const int px = int(i / 3) % w, py = int(i / 3) / w;
        const Ray r = cam.generate_ray(Vec2(px + 0.5, py + 0.5));
        const double expected = std::exp(-2 * sigma / std::abs(normalize(r.d).z));
        // Luminance (CIE Y, never negative): one wavelength per path makes R, G, B noisy and of
        // either sign, but the ratio is a Y-weighted mean of per-sample transmittances.
        const double ya = 0.2126 * a[i] + 0.7152 * a[i + 1] + 0.0722 * a[i + 2];
        const double yb = 0.2126 * b[i] + 0.7152 * b[i + 1] + 0.0722 * b[i + 2];
        ASSERT_GT(ya, 0.01);
        EXPECT_NEAR(yb / ya, expected, 3e-4) << "pixel " << px << "," << py;
    }
}
