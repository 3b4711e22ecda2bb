// Stage 2 of scene loading: the parsed XML instantiated through every factory (BSDFs, shapes,
// emitters, integrators), and the errors that only instantiation can find, with file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "bsdf/bsdf.h"
#include "integrators/integrator.h"
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
    EXPECT_NEAR(s.scene->camera()->tan_half_x(), std::tan(20.0 * kPi / 180.0), 1e-12);
    const Vec3 eye = s.scene->camera()->position();
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

TEST(SceneLoaderFull, SensorFilmSamplerErrors) {
    expect_error("<scene version=\"3.0.0\">\n<shape type=\"sphere\"/>\n</scene>", "test.xml:1: <scene>", "no <sensor");
    expect_error("<scene version=\"3.0.0\">\n<sensor type=\"orthographic\"/>\n</scene>", "test.xml:2: <sensor>",
                 "orthographic");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n"
        "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"crop_width\" "
        "value=\"9\"/></film>\n"
        "</sensor>\n</scene>",
        "test.xml:4: <film>", "does not fit");
    expect_error(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n"
        "<sampler type=\"orthogonal\"/>\n</sensor>\n</scene>",
        "test.xml:4: <sampler>", "unknown sampler type 'orthogonal' (supported: independent, stratified");
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
