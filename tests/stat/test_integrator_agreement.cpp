// `pt` (BSDF sampling alone, the paper's PT) and `nee` are independent estimators of the same image: their means must
// agree within the standard errors measured from independent replicas, per pixel block (errors confined to a region: a
// light that leaks, a BSDF on one object) and in whole-image luminance (small errors spread over everything: a MIS
// weight a few percent off, a wrong light pdf).
#include "stat/box_scene.h"
#include "stat/replica_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// A glossy (GGX, alpha 0.15) metal floor reflecting a large light, direct lighting only: BSDF
// sampling carries most of the estimate here, light sampling most of it in the box (stat/box_scene.h), so
// an error in either MIS weight shows in one of the two scenes.
const char* kGlossy = R"(<scene version="3.0.0">
  <default name="integrator" value="nee"/>
  <integrator type="$integrator"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 1, 3" target="0, 0, -0.5" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.15"/></bsdf></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="1.5"/><rotate x="1" angle="90"/><translate y="1.5" z="-3"/></transform>
    <emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>
</scene>)";

void expect_path_and_nee_agree(const char* xml, int spp_path, int spp_nee, int block) {
    LoadedScene path = load_xml(xml, {{"integrator", "pt"}});
    LoadedScene nee = load_xml(xml, {{"integrator", "nee"}});
    expect_replicas_agree(replica_stats(path, spp_path, block, 1000), replica_stats(nee, spp_nee, block, 2000),
                          "path vs nee");
}

}  // namespace

// Power (measured by injecting bugs, see docs/testing.md): the whole-image luminance has a
// relative standard error of ~0.25% (path) and ~0.3% (nee) here, so the Bonferroni threshold
// (alpha 0.01 over 17 tests, |t| > ~3.9 at ~20 dof) flags shifts of ~1.6% and above. Light-side
// MIS weights 5% too small shift this image by 2.3%; a missing cosine in NEE by ~30%.
TEST(IntegratorAgreement, PathAndNeeAgreeInABox) { expect_path_and_nee_agree(kCornellBox, 128, 64, 8); }

// Here BSDF-side MIS weights 5% too small shift the image by 2.3% (in the box only by 0.06%:
// light sampling owns that image); the relative standard error of the difference is ~0.33%.
TEST(IntegratorAgreement, PathAndNeeAgreeOnAGlossyReflection) { expect_path_and_nee_agree(kGlossy, 1024, 256, 4); }

// Sensitivity check: the tests above must be able to fail. A light 3% brighter, with the same
// estimator and the same sample counts, must be detected.
TEST(IntegratorAgreement, DetectsALightThreePercentBrighter) {
    LoadedScene base = load_xml(kCornellBox, {{"integrator", "nee"}});
    LoadedScene brighter = load_xml(kCornellBox, {{"integrator", "nee"}, {"radiance", "6.18"}});
    const ReplicaStats a = replica_stats(base, 64, 8, 3000);
    const ReplicaStats b = replica_stats(brighter, 64, 8, 4000);
    EXPECT_GT(disagreements(a, b, 0.01, false), 0);
}

// `path` means what it means in Mitsuba and pbrt: emitter sampling with MIS. A Mitsuba scene with
// `<integrator type="path">` and a point light must not render black (BSDF sampling alone cannot
// hit a point light): `path` is `nee`, sample for sample, and lit.
TEST(IntegratorNames, PathWithAPointLightIsNee) {
    const char* xml = R"(<scene version="3.0.0">
  <default name="integrator" value="path"/>
  <integrator type="$integrator"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 1, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="12"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform></shape>
  <emitter type="point"><point name="position" x="0" y="2" z="0"/><rgb name="intensity" value="10"/></emitter>
</scene>)";
    const auto image = [&](const char* integ) {
        LoadedScene ls = load_xml(xml, {{"integrator", integ}});
        EXPECT_EQ(ls.integrator->name(), integ);
        return render_rgb(ls, 4);
    };
    const auto path = image("path"), nee = image("nee"), pt = image("pt");
    double lit = 0, dark = 0;
    for (size_t i = 0; i < path.size(); ++i) {
        ASSERT_EQ(path[i], nee[i]) << "component " << i;
        lit += path[i];
        dark += pt[i];
    }
    EXPECT_GT(lit, 0.1 * double(path.size()));
    EXPECT_EQ(dark, 0.0) << "pt, the paper's pure path tracing, cannot reach a point light";
}

namespace {

// A glossy floor, a diffuse block, a glass ball and a large light: direct illumination from
// light sampling and from BSDF sampling both matter, and the ball shows the light through a
// delta BSDF (one bounce).
std::string direct_scene(const std::string& integrator) {
    return R"(<scene version="3.0.0">)" + integrator + R"(
  <sensor type="perspective"><float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 1.5, 3.5" target="0, 0.3, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf></shape>
  <shape type="cube"><transform name="to_world"><scale value="0.3"/><translate x="-0.7" y="0.3" z="0"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0.6" y="0.4" z="0.2"/><float name="radius" value="0.4"/>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="1.2"/><rotate x="1" angle="90"/><translate y="2.5" z="-0.5"/></transform>
    <emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>
</scene>)";
}

}  // namespace

// Mitsuba's `direct` is direct illumination only: emission plus one bounce towards the lights,
// which is what `nee` estimates with max_depth 2. With one sample of each kind, with several of
// each (the MIS weights then count samples), and with BSDF samples alone, it agrees with it.
// (Light samples alone miss the light seen through the glass ball, as in Mitsuba.)
TEST(IntegratorAgreement, DirectAgreesWithNeeOfMaxDepthTwo) {
    LoadedScene nee =
        load_xml(direct_scene(R"(<integrator type="nee"><integer name="max_depth" value="2"/></integrator>)"));
    const auto ref = replica_stats(nee, 256, 6, 3000);
    for (const auto& [e, b] : std::vector<std::pair<int, int>>{{1, 1}, {4, 2}, {0, 3}}) {
        const std::string integ = R"(<integrator type="direct"><integer name="emitter_samples" value=")" +
                                  std::to_string(e) + R"("/><integer name="bsdf_samples" value=")" + std::to_string(b) +
                                  R"("/></integrator>)";
        LoadedScene direct = load_xml(direct_scene(integ));
        EXPECT_EQ(direct.integrator->name(), "direct");
        expect_replicas_agree(
            ref, replica_stats(direct, 64, 6, 4000 + 10 * e + b),
            ("direct, emitter_samples " + std::to_string(e) + ", bsdf_samples " + std::to_string(b)).c_str());
    }
}

// A `null` surface changes nothing: a floor under a light renders the same with a null sheet
// across the view and across the light (shadow rays it blocks are made up by BSDF sampling
// through it); a `mask` of opacity 0 is a null surface too. (Unbounded depth: crossing a null
// surface is a bounce, as in Mitsuba's path tracer, so a max_depth would cut paths here.)
TEST(IntegratorAgreement, NullAndTransparentMaskSurfacesChangeNothing) {
    const auto scene = [](const std::string& sheet) {
        return R"(<scene version="3.0.0"><integrator type="nee"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 2, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="2"/><rotate x="1" angle="-90"/></transform></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="0.8"/><rotate x="1" angle="90"/><translate y="1.5"/></transform>
    <emitter type="area"><rgb name="radiance" value="4"/></emitter></shape>
  )" + sheet + R"(
</scene>)";
    };
    const std::string sheet = R"(<shape type="rectangle">
    <transform name="to_world"><scale value="3"/><rotate x="1" angle="-60"/><translate y="0.8"/></transform>)";
    LoadedScene none = load_xml(scene(""));
    LoadedScene null = load_xml(scene(sheet + R"(<bsdf type="null"/></shape>)"));
    LoadedScene mask = load_xml(scene(sheet + R"(<bsdf type="mask"><float name="opacity" value="0"/>
      <bsdf type="diffuse"/></bsdf></shape>)"));
    const auto ref = replica_stats(none, 64, 4, 5000);
    expect_replicas_agree(ref, replica_stats(null, 256, 4, 5100), "null sheet");
    expect_replicas_agree(ref, replica_stats(mask, 256, 4, 5200), "mask of opacity 0");
}
