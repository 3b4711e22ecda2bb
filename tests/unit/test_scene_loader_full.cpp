// Stage 2 of scene loading: the parsed XML instantiated through every factory (BSDFs, shapes,
// emitters, integrators), and the errors that only instantiation can find, with file:line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "bsdf/bsdf.h"
#include "integrators/integrator.h"
#include "integrators/mnee/mnee_integrator.h"
#include "io/image.h"
#include "light/light.h"
#include "loader/scene_loader.h"
#include "unit/loader_errors.h"

using namespace snell;

namespace {

const std::string kDataDir = std::string(SNELL_SOURCE_DIR) + "/tests/data/scenes/full";

/// A minimal valid scene around `body` (the sensor is on line 2, `body` starts on line 3).
std::string scene_with(const std::string& body) {
    return "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/></sensor>\n" +
           body + "\n</scene>";
}

std::string load_error(const std::string& xml, const Defines& defines = {}) {
    return test::load_error(xml, kDataDir, defines);
}

void expect_error(const std::string& xml, const std::string& where, const std::string& what) {
    test::expect_load_error(xml, kDataDir, where, what);
}

}  // namespace

TEST(SceneLoaderFull, LoadsEverySection) {
    const LoadedScene s = load_scene_file(kDataDir + "/scene.xml", {{"spp", "12"}});
    ASSERT_TRUE(s.scene);
    EXPECT_EQ(s.path, kDataDir + "/scene.xml");
    EXPECT_EQ(s.spp, 12);  // -D spp=12 beat <default> 8
    EXPECT_EQ(s.seed, 7u);
    EXPECT_EQ(s.film.width, 32);
    EXPECT_EQ(s.film.height, 24);
    EXPECT_EQ(s.film.crop_x, 4);
    EXPECT_EQ(s.film.crop_w, 16);
    EXPECT_EQ(s.film.crop_h, 24);
    EXPECT_EQ(s.film.out_width(), 16);
    ASSERT_NE(s.scene->camera(), nullptr);
    EXPECT_NEAR(s.scene->camera()->pinhole()->tan_half_x(), std::tan(20.0 * kPi / 180.0), 1e-12);
    const Vec3 eye = s.scene->camera()->pinhole()->position();
    EXPECT_NEAR(eye.z, -4.0, 1e-12);
    ASSERT_TRUE(s.integrator);
    EXPECT_EQ(s.integrator->name(), "path");
    // sphere, rectangle (emissive), OBJ triangle from the included file; area + point light.
    ASSERT_EQ(s.scene->shapes().size(), 3u);
    EXPECT_EQ(s.scene->lights().size(), 2u);
    EXPECT_NE(s.scene->shapes()[1]->emitter(), nullptr);
    EXPECT_EQ(s.scene->shapes()[0]->emitter(), nullptr);
    // The OBJ is found relative to meshes/part.xml; its BSDF is the shared <bsdf id="grey">.
    EXPECT_NEAR(s.scene->shapes()[2]->area(), 0.5, 1e-12);
    EXPECT_EQ(s.scene->shapes()[2]->bsdf()->id(), "grey");
}

TEST(SceneLoaderFull, DefaultIntegratorIsPath) {
    const LoadedScene s = load_scene_string(scene_with("<shape type=\"sphere\"/>"), "test.xml", kDataDir);
    EXPECT_EQ(s.integrator->name(), "path");
    EXPECT_EQ(s.spp, 16);
}

TEST(SceneLoaderFull, SamplerTypesAndParameters) {
    // Without a <sampler>: Mitsuba's default, independent.
    const LoadedScene d = load_scene_string(scene_with("<shape type=\"sphere\"/>"), "test.xml", kDataDir);
    EXPECT_EQ(d.sampler.type, "independent");
    EXPECT_TRUE(d.sampler.jitter);
    for (const std::string type : {"independent", "stratified", "multijitter", "ldsampler", "sobol"}) {
        const bool has_jitter = type == "stratified" || type == "multijitter";
        const std::string xml =
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<sampler type=\"" + type +
            "\">\n<integer name=\"sample_count\" value=\"64\"/>\n<integer name=\"seed\" value=\"5\"/>\n" +
            (has_jitter ? "<boolean name=\"jitter\" value=\"false\"/>\n" : "") +
            "</sampler>\n</sensor>\n<shape type=\"sphere\"/>\n</scene>";
        const LoadedScene s = load_scene_string(xml, "test.xml", kDataDir);
        EXPECT_EQ(s.sampler.type, type);
        EXPECT_EQ(s.sampler.jitter, !has_jitter) << type;
        EXPECT_EQ(s.spp, 64) << type;
        EXPECT_EQ(s.seed, 5u) << type;
    }
    // `jitter` only where Mitsuba has it.
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<sampler type=\"sobol\">\n"
        "<boolean name=\"jitter\" value=\"false\"/>\n</sampler>\n</sensor>\n</scene>",
        "test.xml:4: <sampler>", "unused parameter 'jitter'");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<sampler type=\"halton\">\n"
        "<integer name=\"sample_count\" value=\"4\"/>\n</sampler>\n</sensor>\n</scene>",
        "test.xml:3: <sampler>", "halton");
}

TEST(SceneLoaderFull, UnusedAndUnknownParametersNameTheirLine) {
    expect_error(scene_with("<bsdf type=\"diffuse\">\n<float name=\"roughness\" value=\"0.1\"/>\n</bsdf>"),
                 "test.xml:4: <bsdf>: unused parameter 'roughness' for type 'diffuse'", "reflectance");
    expect_error(scene_with("<shape type=\"sphere\">\n<bsdf type=\"velvet\"/>\n</shape>"), "test.xml:4: <bsdf>",
                 "velvet");
    expect_error(scene_with("<shape type=\"torus\"/>"), "test.xml:3: <shape>", "torus");
    expect_error(scene_with("<emitter type=\"laser\"/>"), "test.xml:3: <emitter>", "laser");
    expect_error(scene_with("<integrator type=\"photonmapper\"/>"), "test.xml:3: <integrator>", "photonmapper");
    expect_error(scene_with("<shape type=\"sphere\">\n<float name=\"radius\" value=\"1\"/>\n<string name=\"radius2\" "
                            "value=\"x\"/>\n</shape>"),
                 "test.xml:5: <shape>", "unused parameter 'radius2'");
    // Wrong type at the parameter's own line.
    expect_error(scene_with("<shape type=\"sphere\">\n<string name=\"radius\" value=\"big\"/>\n</shape>"),
                 "test.xml:4: <shape>", "expected float, got string");
}

// Without a fov, Mitsuba's sensors take a focal length (50 mm unless given) on 35 mm film along
// its diagonal: on a square image the half-width tangent is (43.27 / 2f) / sqrt 2.
TEST(SceneLoaderFull, FocalLengthAsMitsuba) {
    auto half_x = [](const std::string& lens) {
        const LoadedScene ls = load_scene_string(
            "<scene version=\"3.0.0\"><sensor type=\"perspective\">" + lens +
                "<film type=\"hdrfilm\"><integer name=\"width\" value=\"48\"/><integer name=\"height\" "
                "value=\"48\"/></film></sensor></scene>",
            "test.xml", kDataDir);
        return ls.scene->camera()->pinhole()->tan_half_x();
    };
    const double diag = std::sqrt(36.0 * 36.0 + 24.0 * 24.0);
    EXPECT_NEAR(half_x(""), diag / (2 * 50) / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(half_x(R"(<string name="focal_length" value="35mm"/>)"), diag / (2 * 35) / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(half_x(R"(<float name="fov" value="40"/>)"), std::tan(20 * kPi / 180), 1e-12);
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>"
        "<string name=\"focal_length\" value=\"35mm\"/></sensor>\n</scene>",
        "test.xml:2: <sensor>", "either 'fov' or 'focal_length'");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><string name=\"focal_length\" "
        "value=\"wide\"/></sensor>\n</scene>",
        "test.xml:2: <sensor>", "focal_length must read like '50mm'");
}

TEST(SceneLoaderFull, SensorFilmSamplerErrors) {
    expect_error("<scene version=\"3.0.0\">\n<shape type=\"sphere\"/>\n</scene>", "test.xml:1: <scene>", "no <sensor");
    expect_error("<scene version=\"3.0.0\">\n<sensor type=\"fisheye\"/>\n</scene>", "test.xml:2: <sensor>",
                 "unknown sensor type 'fisheye' (supported: perspective, thinlens, orthographic)");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"orthographic\"><float name=\"fov\" value=\"30\"/></sensor>\n"
        "</scene>",
        "test.xml:2: <sensor>", "unused parameter 'fov' for type 'orthographic'");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0\"/>"
        "<float name=\"focus_distance\" value=\"1\"/></sensor>\n</scene>",
        "test.xml:2: <sensor>", "aperture_radius must be > 0");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n"
        "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"crop_width\" "
        "value=\"9\"/></film>\n"
        "</sensor>\n</scene>",
        "test.xml:4: <film>", "does not fit");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n"
        "<sampler type=\"halton\"/>\n</sensor>\n</scene>",
        "test.xml:4: <sampler>", "unknown sampler type 'halton' (supported: independent, stratified");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n"
        "<sampler type=\"orthogonal\"><integer name=\"strength\" value=\"3\"/></sampler>\n</sensor>\n</scene>",
        "test.xml:4: <sampler>", "strength 2");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n"
        "<film type=\"hdrfilm\">\n<float name=\"exposure\" value=\"1\"/>\n</film>\n</sensor>\n</scene>",
        "test.xml:5: <film>", "unused parameter 'exposure'");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n"
        "<film type=\"hdrfilm\">\n<rfilter type=\"lanczos\"/>\n</film>\n</sensor>\n</scene>",
        "test.xml:5: <rfilter>", "lanczos");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" "
        "value=\"200\"/>\n</sensor>\n</scene>",
        "test.xml:3: <sensor>", "fov");
    // Mitsuba's exporters write focus_distance on perspective sensors: accepted (a pinhole is
    // in focus everywhere), and checked.
    EXPECT_EQ(load_error("<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n"
                         "<float name=\"focus_distance\" value=\"4\"/>\n</sensor>\n</scene>"),
              "");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"focus_distance\" "
        "value=\"-1\"/>\n</sensor>\n</scene>",
        "test.xml:3: <sensor>", "focus_distance must be > 0");
}

TEST(SceneLoaderFull, EmitterPlacementErrors) {
    expect_error(scene_with("<emitter type=\"area\"/>"), "test.xml:3: <emitter>", "nested inside");
    expect_error(scene_with("<shape type=\"sphere\">\n<emitter type=\"point\"/>\n</shape>"), "test.xml:4: <emitter>",
                 "area");
    expect_error(scene_with("<shape type=\"sphere\">\n<emitter type=\"area\">\n<float name=\"radiance\" value=\"1\"/>\n"
                            "<float name=\"power\" value=\"1\"/>\n</emitter>\n</shape>"),
                 "test.xml:6: <emitter>", "unused parameter 'power'");
}

TEST(SceneLoaderFull, MissingMeshNamesThePath) {
    const std::string msg =
        load_error(scene_with("<shape type=\"obj\">\n<string name=\"filename\" value=\"nope.obj\"/>\n</shape>"));
    EXPECT_EQ(msg.rfind("test.xml:", 0), 0u) << msg;
    EXPECT_NE(msg.find("nope.obj"), std::string::npos) << msg;
}

TEST(SceneLoaderFull, MissingSceneFileNamesThePath) {
    try {
        load_scene_file(kDataDir + "/no_such_scene.xml");
        FAIL() << "expected an error";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("no_such_scene.xml"), std::string::npos) << e.what();
    }
}

TEST(SceneLoaderFull, ShippedScenesLoad) {
    // Every scenes/<name>/<name>.xml (the convention for shipped scenes; other .xml files there
    // may be fragments meant for <include>) must load with its defaults and with -D overrides.
    namespace fs = std::filesystem;
    int n = 0;
    for (const auto& dir : fs::directory_iterator(std::string(SNELL_SOURCE_DIR) + "/scenes")) {
        const fs::path file = dir.path() / (dir.path().filename().string() + ".xml");
        if (!dir.is_directory() || !fs::exists(file)) continue;
        SCOPED_TRACE(file.string());
        EXPECT_NO_THROW(load_scene_file(file.string()));
        ++n;
    }
    EXPECT_GE(n, 1);
    const std::string droplet = std::string(SNELL_SOURCE_DIR) + "/scenes/droplet/droplet.xml";
    const LoadedScene s = load_scene_file(droplet, {{"integrator", "path"}, {"spp", "3"}});
    EXPECT_EQ(s.integrator->name(), "path");
    EXPECT_EQ(s.spp, 3);
}

namespace {
LoadedScene load_string(const std::string& xml) { return load_scene_string(xml, "test.xml", kDataDir); }
bool has_notice(const LoadedScene& ls, const std::string& what) {
    for (const auto& n : ls.notices)
        if (n.find(what) != std::string::npos) return true;
    return false;
}
}  // namespace

// Mitsuba's moment and aov wrappers render their nested integrator, with a notice that the extra
// images are not written; a wrapper needs exactly one.
TEST(SceneLoaderFull, MomentAndAovWrappersAreUnwrapped) {
    const LoadedScene ls = load_string(scene_with(R"(<integrator type="aov"><string name="aovs" value="nn:sh_normal"/>
<integrator type="moment"><integrator type="path"><integer name="max_depth" value="3"/></integrator></integrator>
</integrator>)"));
    EXPECT_EQ(ls.integrator->name(), "path");
    ASSERT_EQ(ls.notices.size(), 2u);
    EXPECT_EQ(ls.notices[0].rfind("test.xml:3: <integrator type=\"aov\"> is unwrapped", 0), 0u) << ls.notices[0];
    EXPECT_TRUE(has_notice(ls, "AOV images are not written"));
    EXPECT_TRUE(has_notice(ls, "moment images are not written"));
    expect_error(scene_with("<integrator type=\"moment\"/>"), "test.xml:3: <integrator>", "needs a nested");
    expect_error(scene_with("<integrator type=\"moment\">\n<integrator type=\"path\"/>\n<integrator "
                            "type=\"nee\"/>\n</integrator>"),
                 "test.xml:5: <integrator>", "wraps one integrator");
    expect_error(scene_with("<integrator type=\"path\">\n<integrator type=\"nee\"/>\n</integrator>"),
                 "test.xml:4: <integrator>", "takes no nested");
}

// mnee's estimator defaults: SMS's unbiased estimator with the straight seed and surface_weight
// 0.03, in the biased mode with surface_weight 1 (its outlier rule would drop what c < 1 leaves
// to BSDF sampling) and the walks' progress test (stall_window 4); `all` weighs its surface solutions fully. The
// allocation is learned but where q is given, in the biased mode and for the paper's estimator. A surface_weight out of
// (0, 1], or given where no straight and surface solutions meet, names the line, and so does a
// learned allocation in the biased mode.
TEST(SceneLoaderFull, MneeDefaultsAndSurfaceWeight) {
    const auto settings = [](const std::string& params) {
        const LoadedScene ls = load_string(scene_with("<integrator type=\"mnee\">" + params + "</integrator>"));
        const auto* m = dynamic_cast<const MneeIntegrator*>(ls.integrator.get());
        EXPECT_NE(m, nullptr);
        return m ? m->mnee_settings() : MneeSettings();
    };
    const MneeSettings def = settings("");
    EXPECT_EQ(def.solutions, MneeSolutions::Unbiased);
    EXPECT_EQ(def.seeding, MneeSeeding::StraightAndSurface);
    EXPECT_EQ(def.surface_weight, kDefaultSurfaceWeight);
    EXPECT_EQ(settings(R"(<string name="solutions" value="unbiased"/>)").surface_weight, kDefaultSurfaceWeight);
    EXPECT_EQ(settings(R"(<boolean name="biased" value="true"/>)").solutions, MneeSolutions::Unbiased);
    EXPECT_EQ(settings(R"(<boolean name="biased" value="true"/>)").surface_weight, 1.0);
    EXPECT_EQ(def.walk.stall_window, 0);
    EXPECT_EQ(settings(R"(<boolean name="biased" value="true"/>)").walk.stall_window, kBiasedStallWindow);
    EXPECT_EQ(
        settings(R"(<boolean name="biased" value="true"/><integer name="stall_window" value="0"/>)").walk.stall_window,
        0);
    EXPECT_TRUE(def.learned_allocation);
    EXPECT_FALSE(settings(R"(<boolean name="biased" value="true"/>)").learned_allocation);
    EXPECT_FALSE(settings(R"(<string name="solutions" value="one"/>)").learned_allocation);
    EXPECT_FALSE(settings(R"(<float name="connect_probability" value="0.5"/>)").learned_allocation);
    EXPECT_TRUE(settings(R"(<string name="solutions" value="one"/><string name="allocation" value="learned"/>)")
                    .learned_allocation);
    expect_error(scene_with("<integrator type=\"mnee\">\n<boolean name=\"biased\" value=\"true\"/><string "
                            "name=\"allocation\" value=\"learned\"/></integrator>"),
                 "test.xml:4", "allocation=learned may leave a region without walks");
    expect_error(scene_with("<integrator type=\"mnee\">\n<integer name=\"pilot_spp\" value=\"0\"/></integrator>"),
                 "test.xml:4", "pilot_spp must lie in [1, 4096]");
    // Regions choose whether to run the surface trials by default; `always` and `never` say so,
    // and the choice needs the learned allocation and surface solutions weighed apart.
    EXPECT_EQ(def.trial_allocation, TrialAllocation::Learned);
    EXPECT_TRUE(def.splits_surface_solutions());
    EXPECT_EQ(settings(R"(<string name="trial_allocation" value="never"/>)").trial_allocation, TrialAllocation::Never);
    EXPECT_FALSE(settings(R"(<boolean name="biased" value="true"/>)").splits_surface_solutions());
    expect_error(scene_with("<integrator type=\"mnee\">\n<string name=\"allocation\" value=\"fixed\"/><string "
                            "name=\"trial_allocation\" value=\"never\"/></integrator>"),
                 "test.xml:4", "trial_allocation needs allocation=learned");
    expect_error(
        scene_with("<integrator type=\"mnee\">\n<string name=\"trial_allocation\" value=\"sometimes\"/></integrator>"),
        "test.xml:4", "trial_allocation");
    EXPECT_EQ(settings(R"(<string name="solutions" value="all"/>)").surface_weight, 1.0);
    EXPECT_EQ(settings(R"(<float name="surface_weight" value="1"/>)").surface_weight, 1.0);
    expect_error(scene_with("<integrator type=\"mnee\">\n<float name=\"surface_weight\" value=\"0\"/></integrator>"),
                 "test.xml:4", "surface_weight must lie in (0, 1]");
    expect_error(scene_with("<integrator type=\"mnee\">\n<string name=\"solutions\" value=\"one\"/><float "
                            "name=\"surface_weight\" value=\"0.1\"/></integrator>"),
                 "test.xml:4", "needs solutions=all or unbiased with seeding=straight+surface");
    // The reflected connection: on by default, off for the paper's estimator, a probability.
    EXPECT_EQ(def.exterior_reflections, kDefaultExteriorReflections);
    EXPECT_EQ(settings(R"(<string name="solutions" value="one"/>)").exterior_reflections, 0.0);
    EXPECT_EQ(settings(R"(<float name="exterior_reflections" value="0.5"/>)").exterior_reflections, 0.5);
    expect_error(
        scene_with("<integrator type=\"mnee\">\n<float name=\"exterior_reflections\" value=\"1.5\"/></integrator>"),
        "test.xml:4", "exterior_reflections (a probability) must lie in [0, 1]");
    EXPECT_EQ(def.failed_walk_weight, 0.0);
    EXPECT_EQ(settings(R"(<float name="failed_walk_weight" value="0.5"/>)").failed_walk_weight, 0.5);
    expect_error(
        scene_with("<integrator type=\"mnee\">\n<float name=\"failed_walk_weight\" value=\"2\"/></integrator>"),
        "test.xml:4", "failed_walk_weight must lie in [0, 1]");
    expect_error(scene_with("<integrator type=\"mnee\">\n<float name=\"surface_weight\" value=\"1\"/><float "
                            "name=\"failed_walk_weight\" value=\"0.5\"/></integrator>"),
                 "test.xml:4", "failed_walk_weight weighs the surface solutions where the straight walk fails");
    EXPECT_TRUE(def.failed_walk_trials);
    EXPECT_FALSE(settings(R"(<string name="failed_walk_trials" value="never"/>)").failed_walk_trials);
    expect_error(scene_with("<integrator type=\"mnee\">\n<string name=\"trial_allocation\" value=\"always\"/><string "
                            "name=\"failed_walk_trials\" value=\"learned\"/></integrator>"),
                 "test.xml:4", "failed_walk_trials lets each region choose");
    expect_error(scene_with("<integrator type=\"mnee\">\n<float name=\"failed_walk_weight\" value=\"1\"/><string "
                            "name=\"failed_walk_trials\" value=\"learned\"/></integrator>"),
                 "test.xml:4", "failed_walk_trials lets each region choose");
    const MneeSettings keyed = settings(R"(<string name="solutions" value="keyed"/>)");
    EXPECT_EQ(keyed.solutions, MneeSolutions::Keyed);
    EXPECT_EQ(keyed.seeding, MneeSeeding::StraightAndSurface);
    EXPECT_EQ(keyed.trials, kKeyedTrials);
    EXPECT_EQ(keyed.seed_candidates, 1);
    EXPECT_FALSE(keyed.learned_allocation);
    expect_error(scene_with("<integrator type=\"mnee\">\n<string name=\"solutions\" value=\"keyed\"/><float "
                            "name=\"surface_weight\" value=\"0.1\"/></integrator>"),
                 "test.xml:4", "needs solutions=all or unbiased with seeding=straight+surface");
}

// The SMS code's integrators render as mnee with the matching estimator, and say what differs;
// its caustic flags on shapes are accepted with one notice.
TEST(SceneLoaderFull, SmsIntegratorsMapToMnee) {
    const auto solutions = [](const LoadedScene& ls) {
        const auto* m = dynamic_cast<const MneeIntegrator*>(ls.integrator.get());
        EXPECT_NE(m, nullptr);
        return m ? m->mnee_settings() : MneeSettings();
    };
    const LoadedScene unbiased = load_string(scene_with(R"(<integrator type="path_sms_ss">
<integer name="max_depth" value="8"/><integer name="max_trials" value="100"/>
<boolean name="halfvector_constraints" value="true"/><float name="step_scale" value="1"/></integrator>
<shape type="sphere"><boolean name="caustic_caster_single" value="true"/><bsdf type="dielectric"/></shape>
<shape type="rectangle"><boolean name="caustic_receiver" value="true"/></shape>)"));
    EXPECT_EQ(unbiased.integrator->name(), "mnee");
    EXPECT_EQ(solutions(unbiased).solutions, MneeSolutions::Unbiased);
    EXPECT_EQ(solutions(unbiased).max_trials, 100);
    EXPECT_TRUE(has_notice(unbiased, "renders as mnee with SMS's unbiased estimator"));
    EXPECT_TRUE(has_notice(unbiased, "ignored: halfvector_constraints, step_scale"));
    EXPECT_TRUE(has_notice(unbiased, "caustic_* flags are ignored"));
    EXPECT_EQ(unbiased.notices.size(), 2u) << "one notice for all the flags";

    const LoadedScene biased = load_string(scene_with(
        R"(<integrator type="path_sms_ms"><boolean name="biased" value="true"/><integer name="max_trials" value="8"/></integrator>)"));
    EXPECT_EQ(solutions(biased).solutions, MneeSolutions::All);
    EXPECT_EQ(solutions(biased).trials, 8);
    EXPECT_TRUE(has_notice(biased, "solved as one chain"));

    const LoadedScene mnee =
        load_string(scene_with(R"(<integrator type="path_sms_ss"><boolean name="mnee_init" value="true"/>
<boolean name="biased" value="true"/><integer name="max_trials" value="1"/><boolean name="biased_mnee" value="true"/></integrator>)"));
    EXPECT_EQ(solutions(mnee).solutions, MneeSolutions::One);
    EXPECT_TRUE(solutions(mnee).biased);
    EXPECT_EQ(mnee.integrator->name(), "mnee-biased");

    // The teaser integrators prefix the caustic settings: caustics_biased, caustics_max_trials, ...
    const LoadedScene teaser = load_string(scene_with(R"(<integrator type="path_sms_teaser">
<boolean name="caustics_enabled" value="true"/><boolean name="caustics_biased" value="true"/>
<integer name="caustics_max_trials" value="12"/><integer name="caustics_max_iterations" value="20"/>
<boolean name="glints_enabled" value="true"/><integer name="glints_max_trials" value="3"/>
<boolean name="non_sms_paths_enabled" value="true"/></integrator>)"));
    EXPECT_EQ(solutions(teaser).solutions, MneeSolutions::All);
    EXPECT_EQ(solutions(teaser).trials, 12);
    EXPECT_TRUE(has_notice(teaser, "ignored: enabled, glints_enabled, glints_max_trials, non_sms_paths_enabled"));

    // A parameter neither SMS nor snell knows is still an error at its line.
    expect_error(scene_with("<integrator type=\"path_sms_ss\">\n<float name=\"nope\" value=\"1\"/>\n</integrator>"),
                 "test.xml:4: <integrator>", "unused parameter 'nope'");
    // The glint integrator renders as `path` (BSDF and emitter sampling converge to the same
    // image), with a notice naming what it ignores; Mitsuba's particle tracer as `bdpt`.
    const LoadedScene glints =
        load_string(scene_with("<integrator type=\"path_sms_glints\"><integer name=\"max_depth\" value=\"7\"/>"
                               "<integer name=\"glints_max_trials\" value=\"3\"/></integrator>"));
    EXPECT_EQ(glints.integrator->name(), "path");
    EXPECT_TRUE(has_notice(glints, "renders as path"));
    EXPECT_TRUE(has_notice(glints, "ignored: glints_max_trials"));
    const LoadedScene pt = load_string(scene_with("<integrator type=\"ptracer\"/>"));
    EXPECT_EQ(pt.integrator->name(), "bdpt");
    EXPECT_TRUE(has_notice(pt, "renders as bdpt"));
}

// Mitsuba 3 scenes declare films, samplers and area emitters at the top level with an id and use
// them through <ref>: they are instantiated where they are used; one nobody uses is an error.
TEST(SceneLoaderFull, TopLevelDeclarationsUsedByRef) {
    const LoadedScene ls = load_string(R"(<scene version="3.0.0">
<film type="hdrfilm" id="film"><integer name="width" value="20"/><integer name="height" value="10"/></film>
<sampler type="independent" id="spl"><integer name="sample_count" value="7"/></sampler>
<emitter type="area" id="glow"><rgb name="radiance" value="2"/></emitter>
<sensor type="perspective"><ref id="film"/><ref id="spl"/></sensor>
<shape type="sphere"><ref id="glow"/></shape>
<shape type="rectangle"><ref id="glow"/></shape>
</scene>)");
    EXPECT_EQ(ls.film.out_width(), 20);
    EXPECT_EQ(ls.film.out_height(), 10);
    EXPECT_EQ(ls.spp, 7);
    EXPECT_EQ(ls.scene->lights().size(), 2u) << "one area light per shape that uses the emitter";
    expect_error(scene_with("<film type=\"hdrfilm\" id=\"f\"/>"), "test.xml:3: <film>", "none names 'f'");
    expect_error(scene_with("<sampler type=\"independent\"/>"), "test.xml:3: <sampler>", "has no id");
    expect_error(scene_with("<emitter type=\"area\" id=\"e\"/>"), "test.xml:3: <emitter>", "must be nested");
}

// Mitsuba's serialized meshes (tests/data/scenes/full/meshes/two.serialized: a triangle, then a
// quad), chosen by shape_index; a bad index names the file and the element's line.
TEST(SceneLoaderFull, SerializedShapes) {
    const LoadedScene ls = load_string(scene_with(R"(<shape type="serialized">
<string name="filename" value="meshes/two.serialized"/><integer name="shape_index" value="1"/></shape>)"));
    ASSERT_EQ(ls.scene->shapes().size(), 1u);
    EXPECT_NEAR(ls.scene->shapes()[0]->area(), 1.0, 1e-6) << "the quad, not the triangle";
    const std::string msg = load_error(
        scene_with("<shape type=\"serialized\">\n<string name=\"filename\" value=\"meshes/two.serialized\"/>\n<integer "
                   "name=\"shape_index\" value=\"2\"/>\n</shape>"));
    EXPECT_EQ(msg.rfind("test.xml:3: <shape>", 0), 0u) << msg;
    EXPECT_NE(msg.find("two.serialized: shape_index 2 out of range (the file has 2 meshes)"), std::string::npos) << msg;
}

// roughplastic loads with Mitsuba's parameters; an effectively smooth one is the smooth plastic.
TEST(SceneLoaderFull, RoughPlastic) {
    const LoadedScene ls = load_string(scene_with(R"(<shape type="sphere"><bsdf type="roughplastic">
<string name="distribution" value="ggx"/><float name="alpha" value="0.2"/><rgb name="diffuse_reflectance" value="0.2, 0.4, 0.6"/>
<float name="int_ior" value="1.5"/><boolean name="nonlinear" value="true"/></bsdf></shape>
<shape type="sphere"><bsdf type="roughplastic"><float name="alpha" value="0"/></bsdf></shape>)"));
    ASSERT_EQ(ls.scene->shapes().size(), 2u);
    EXPECT_EQ(ls.scene->shapes()[0]->bsdf()->flags(), kReflection | kGlossy | kDiffuse);
    EXPECT_EQ(ls.scene->shapes()[1]->bsdf()->flags(), kReflection | kSpecular | kDiffuse);
    expect_error(scene_with("<bsdf type=\"roughplastic\">\n<string name=\"distribution\" value=\"phong\"/>\n</bsdf>"),
                 "test.xml:4: <bsdf>", "unknown distribution 'phong'");
}

// What snell does not have fails at the element with the feature's name, never silently.
TEST(SceneLoaderFull, UnsupportedFeaturesAreNamed) {
    expect_error(scene_with("<shape type=\"bsplinecurve\"/>"), "test.xml:3: <shape>", "curves are not supported");
    expect_error(scene_with("<shape type=\"sdfgrid\"/>"), "test.xml:3: <shape>", "SDF grids are not supported");
    expect_error(scene_with("<bsdf type=\"polarizer\"/>"), "test.xml:3: <bsdf>", "polarisation is not supported");
    expect_error(scene_with("<integrator type=\"volpath\"/>"), "test.xml:3: <integrator>",
                 "participating media are not supported");
    expect_error(scene_with("<integrator type=\"moment\"><integrator type=\"volpath\"/></integrator>"),
                 "test.xml:3: <integrator>", "participating media");
}

// Mitsuba's sampling-integrator settings: `timeout` becomes the scene's time budget,
// `samples_per_pass` is accepted (snell renders tiles progressively).
TEST(SceneLoaderFull, MitsubaTimeoutAndSamplesPerPass) {
    const LoadedScene ls = load_string(scene_with(R"(<integrator type="path"><float name="timeout" value="12.5"/>
<integer name="samples_per_pass" value="4"/></integrator>)"));
    EXPECT_EQ(ls.time_limit, 12.5);
    const LoadedScene sms = load_string(scene_with(R"(<integrator type="path_sms_ss"><float name="timeout" value="3"/>
<integer name="samples_per_pass" value="4"/></integrator>)"));
    EXPECT_EQ(sms.time_limit, 3.0);
    EXPECT_EQ(load_string(scene_with(R"(<integrator type="path"><float name="timeout" value="-1"/></integrator>)"))
                  .time_limit,
              0.0);
}

// Mitsuba's cylinder: p0, p1, radius, composed with to_world (uniform scale only).
TEST(SceneLoaderFull, Cylinder) {
    const LoadedScene ls = load_string(scene_with(R"(<shape type="cylinder"><float name="radius" value="0.5"/>
<point name="p1" x="0" y="0" z="1.5"/><transform name="to_world"><scale value="2"/></transform></shape>)"));
    ASSERT_EQ(ls.scene->shapes().size(), 1u);
    EXPECT_NEAR(ls.scene->shapes()[0]->area(), 2 * kPi * 1.0 * 3.0, 1e-12);
    // The axis may be scaled on its own (Mitsuba allows it); the cross section must stay round.
    const LoadedScene longer = load_string(scene_with(R"(<shape type="cylinder">
<transform name="to_world"><scale x="0.5" y="0.5" z="4"/></transform></shape>)"));
    EXPECT_NEAR(longer.scene->shapes()[0]->area(), 2 * kPi * 0.5 * 4.0, 1e-12);
    expect_error(scene_with("<shape type=\"cylinder\">\n<transform name=\"to_world\"><scale x=\"1\" y=\"2\" "
                            "z=\"1\"/></transform>\n</shape>"),
                 "test.xml:4: <shape>", "must keep its cross section circular");
}

// Issue 12's loader defects, each a regression test:
//  - integers are read as 64-bit and range-checked before narrowing: sample_count 2147483648 was
//    negative (and rendered forever), 4294967297 one sample, width 4294967312 a 16-pixel film;
//  - crop_offset_x = 2147483647 overflowed the crop check;
//  - nested twosided BSDFs (front and back the same object) cost 2^depth in flags(): depth 50
//    never finished loading; it loads now, as does a blend nesting one BSDF twice per level.
TEST(SceneLoaderFull, IntegersAreRangeCheckedAndNestingIsLinear) {
    auto film = [](const std::string& film_params, const std::string& sampler = "") {
        return std::string(
                   "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>\n"
                   "<film type=\"hdrfilm\">") +
               film_params + "</film>" + sampler + "\n</sensor>\n</scene>";
    };
    expect_error(
        film("", "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"2147483648\"/></sampler>"),
        "test.xml:3: <sampler>", "sample_count must lie in [1, 1073741824] (got 2147483648)");
    expect_error(
        film("", "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"4294967297\"/></sampler>"),
        "test.xml:3: <sampler>", "got 4294967297");
    expect_error(film("<integer name=\"width\" value=\"4294967312\"/>"), "test.xml:3: <film>",
                 "film width must lie in [1, 65536] (got 4294967312)");
    expect_error(film("<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>"
                      "<integer name=\"crop_offset_x\" value=\"2147483647\"/>"),
                 "test.xml:3: <film>", "does not fit the 8x8 film");
    expect_error(film("<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>"
                      "<integer name=\"crop_offset_x\" value=\"4\"/><integer name=\"crop_width\" "
                      "value=\"9223372036854775807\"/>"),
                 "test.xml:3: <film>", "does not fit the 8x8 film");
    std::string nested = R"(<bsdf type="diffuse"/>)";
    for (int i = 0; i < 60; ++i) nested = R"(<bsdf type="twosided">)" + nested + "</bsdf>";
    const LoadedScene deep = load_string(scene_with("<shape type=\"sphere\">" + nested + "</shape>"));
    EXPECT_TRUE(deep.scene->shapes()[0]->bsdf()->flags() & kReflection);
    std::string blend = R"(<bsdf type="diffuse" id="b0"/>)";
    for (int i = 1; i <= 60; ++i)
        blend += "<bsdf type=\"blendbsdf\" id=\"b" + std::to_string(i) + "\"><ref id=\"b" + std::to_string(i - 1) +
                 "\"/><ref id=\"b" + std::to_string(i - 1) + "\"/></bsdf>";
    const LoadedScene wide = load_string(scene_with(blend + "<shape type=\"sphere\"><ref id=\"b60\"/></shape>"));
    EXPECT_TRUE(wide.scene->shapes()[0]->bsdf()->flags() & kDiffuse);
}

// Issue 12: coordinates beyond what Embree represents (it asserts ray origins within 1.8e18 and
// aborted the process) are a load error that says what reaches how far: a sphere of radius 1e25,
// a camera at 1e19. Inside the limit (1e12) a scene loads.
TEST(SceneLoaderFull, ExtremeCoordinatesAreAClearError) {
    const std::string sphere = R"(<shape type="sphere"><float name="radius" value="1e25"/></shape>)";
    expect_error(scene_with(sphere), "test.xml:", "the scene's geometry reaches 1e+25 from the origin");
    const std::string camera = R"(<scene version="3.0.0">
<sensor type="perspective"><transform name="to_world">
<lookat origin="1e19, 0, 0" target="0, 0, 0" up="0, 1, 0"/></transform></sensor>
<shape type="sphere"/>
</scene>)";
    expect_error(camera, "test.xml:", "the sensor's position reaches 1e+19");
    EXPECT_NO_THROW(load_string(scene_with(R"(<shape type="sphere"><float name="radius" value="1e11"/></shape>)")));
}

// Issue 12 (found by the fuzzer): the Metropolis integrators' counts are range-checked before
// use: pssmlt's bootstrap_samples of 2^31 allocated 16 GiB, and its chains were narrowed to int.
TEST(SceneLoaderFull, MetropolisCountsAreRangeChecked) {
    auto with = [](const std::string& type, const std::string& param) {
        return "<scene version=\"3.0.0\">\n<integrator type=\"" + type + "\">" + param +
               "</integrator>\n<sensor type=\"perspective\"/>\n</scene>";
    };
    expect_error(with("pssmlt", "<integer name=\"bootstrap_samples\" value=\"2147483648\"/>"),
                 "test.xml:2: <integrator>", "bootstrap_samples must lie in [1, 16777216]");
    expect_error(with("pssmlt", "<integer name=\"chains\" value=\"4294967297\"/>"), "test.xml:2: <integrator>",
                 "chains must lie in [0, 65536]");
    expect_error(with("pssmlt", "<integer name=\"mutations_per_pixel\" value=\"-1\"/>"), "test.xml:2: <integrator>",
                 "mutations_per_pixel must lie in");
    expect_error(with("erpt", "<integer name=\"bootstrap_samples\" value=\"2147483648\"/>"), "test.xml:2: <integrator>",
                 "bootstrap_samples must lie in [1, 16777216]");
}

// A perspective sensor's frame must be rigid (Mitsuba 3 refuses scale factors too): with a
// scale its clip planes and importance were in mixed units and bdpt's light paths were clipped
// (found by the scale-invariance test). A mirror (Mitsuba 0.5 scenes' scale x="-1") is rigid.
TEST(SceneLoaderFull, ScaledPerspectiveSensorIsAnError) {
    auto sensor = [](const std::string& ops) {
        return "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><transform name=\"to_world\">" + ops +
               "</transform></sensor>\n<shape type=\"sphere\"/>\n</scene>";
    };
    expect_error(sensor("<lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/><scale value=\"10\"/>"),
                 "test.xml:2: <sensor>", "must not scale or shear");
    EXPECT_NO_THROW(
        load_string(sensor("<scale x=\"-1\"/><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>")));
}

// Issue 12: 100,000 nested elements overflowed the stack of the recursive parser. Any document
// nested deeper than 256 levels is refused first, at the element where it crosses the limit;
// 200 levels (far more than any scene needs) still load.
TEST(SceneLoaderFull, DeepNestingIsAClearError) {
    const int n = 100000;
    std::string deep;
    deep.reserve(size_t(n) * 48);
    for (int i = 0; i < n; ++i) deep += "<bsdf type=\"twosided\">";
    deep += "<bsdf type=\"diffuse\"/>";
    for (int i = 0; i < n; ++i) deep += "</bsdf>";
    expect_error(scene_with(deep), "test.xml:3: <bsdf>", "nested deeper than 256 levels");
    std::string ok = R"(<bsdf type="diffuse"/>)";
    for (int i = 0; i < 200; ++i) ok = R"(<bsdf type="twosided">)" + ok + "</bsdf>";
    EXPECT_NO_THROW(load_string(scene_with("<shape type=\"sphere\">" + ok + "</shape>")));
}

// Issue 30: an instance scaled by 1e-20 passed the world-space coordinate check, and Embree
// aborted on its rays (1e20 times longer in the group's space). The composed transform is
// checked where the rays are traced; an instance scaled by 1e-3 still loads.
TEST(SceneLoaderFull, InstanceScaledBeyondTraceableRangeIsAnError) {
    const auto scene = [](const char* scale) {
        return std::string("<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><transform name=\"to_world\">") +
               "<lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform></sensor>\n" +
               "<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"/></shape>\n" +
               "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\"><scale value=\"" + scale +
               "\"/></transform></shape>\n</scene>";
    };
    expect_error(scene("1e-20"), "test.xml:4: <shape>", "carries the scene (and its rays)");
    EXPECT_NO_THROW(load_scene_string(scene("1e-3"), "test.xml", kDataDir));
}

// Issue 30: emission textures went through the reflectance upsampling, which clamps to [0, 1]:
// an area light textured 1, 2, 10 or 100 rendered the same image. The emitted spectrum now
// scales with the texture's value up to 1e4 at every wavelength, grey and coloured, and a grey
// texture of v emits v at every wavelength.
TEST(SceneLoaderFull, EmissionTexturesAreUnbounded) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("snell_emission_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const auto le_of = [&](const RGB& rgb, const char* type) {
        Image img;
        img.width = img.height = 2;
        for (int i = 0; i < 4; ++i) img.rgb.insert(img.rgb.end(), {float(rgb.r), float(rgb.g), float(rgb.b)});
        const fs::path f = dir / "emission.exr";
        write_exr(f.string(), img);
        const std::string radiance =
            std::string(type) == "bitmap"
                ? "<texture type=\"bitmap\" name=\"radiance\"><string name=\"filename\" value=\"" + f.string() +
                      "\"/></texture>"
                : "<rgb name=\"radiance\" value=\"" + std::to_string(rgb.r) + ", " + std::to_string(rgb.g) + ", " +
                      std::to_string(rgb.b) + "\"/>";
        const LoadedScene ls = load_scene_string(
            scene_with("<shape type=\"rectangle\"><emitter type=\"area\">" + radiance + "</emitter></shape>"),
            "test.xml", kDataDir);
        const Light& light = *ls.scene->lights().at(0);
        const SampledWavelengths wl = SampledWavelengths::sample_visible({0.3, 0.7}, kSpectrumSamples);
        return std::make_pair(light.le(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec2(0.5, 0.5), Vec3(0, 0, 1), wl), wl);
    };
    for (const RGB& base : {RGB(1, 1, 1), RGB(0.9, 0.4, 0.1)}) {
        const auto [one, wl] = le_of(base, "bitmap");
        for (double v : {2.0, 10.0, 100.0, 1e4}) {
            const auto [scaled, wl2] = le_of(RGB(base.r * v, base.g * v, base.b * v), "bitmap");
            for (int k = 0; k < kSpectrumSamples; ++k)
                EXPECT_NEAR(scaled[k] / one[k], v, 1e-4 * v) << v << " at " << wl[k];
        }
    }
    const auto [grey, wl] = le_of(RGB(37, 37, 37), "bitmap");
    for (int k = 0; k < kSpectrumSamples; ++k) EXPECT_NEAR(grey[k], 37.0, 1e-6) << wl[k];
    fs::remove_all(dir);
}
