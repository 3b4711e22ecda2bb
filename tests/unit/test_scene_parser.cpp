// Stage 1 of scene loading (loader/xml_scene.h), independent of the plugin factories: substitution,
// includes, refs, value tags, transform composition and error messages with file:line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "loader/xml_scene.h"

using namespace snell;

namespace {

const std::string kDataDir = std::string(SNELL_SOURCE_DIR) + "/tests/data/scenes/parser";

std::shared_ptr<XmlObject> parse(const std::string& body, const std::map<std::string, std::string>& defines = {}) {
    return parse_scene_xml_string(body, "test.xml", kDataDir, defines);
}

/// Message of the SceneError thrown by parsing `xml` ("" if it parses).
std::string parse_error(const std::string& xml, const std::map<std::string, std::string>& defines = {}) {
    try {
        parse(xml, defines);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

std::string file_error(const std::string& path) {
    try {
        parse_scene_xml_file(path);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

/// Expects the error to start with "test.xml:<line>: <tag>:" and to contain `what`.
void expect_error(const std::string& xml, int line, const std::string& tag, const std::string& what,
                  const std::map<std::string, std::string>& defines = {}) {
    const std::string msg = parse_error(xml, defines);
    const std::string head = "test.xml:" + std::to_string(line) + ": <" + tag + ">:";
    EXPECT_EQ(msg.rfind(head, 0), 0u) << "expected prefix '" << head << "' in: " << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
}

template <typename T>
const T& value_of(const XmlObject& o, const std::string& name) {
    const XmlParam* p = o.param(name);
    EXPECT_NE(p, nullptr) << name;
    return std::get<T>(p->value);
}

void expect_matrix_near(const Transform& a, const Transform& b) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            EXPECT_NEAR(a.matrix()[i][j], b.matrix()[i][j], 1e-12) << i << "," << j;
            EXPECT_NEAR(a.inverse_matrix()[i][j], b.inverse_matrix()[i][j], 1e-12) << i << "," << j;
        }
}

}  // namespace

TEST(SceneParser, ObjectsValuesAndLines) {
    const auto s = parse(R"(<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="8"/>
        <boolean name="hide_emitters" value="True"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <string name="fov_axis" value="x"/>
        <film type="hdrfilm">
            <integer name="width" value="64"/>
        </film>
    </sensor>
    <shape type="sphere">
        <point name="center" x="1" z="3"/>
        <vector name="v" value="1, 2 3"/>
        <rgb name="c" value="0.1, 0.2, 0.3"/>
        <rgb name="g" value="0.5"/>
        <spectrum name="s1" value="0.25"/>
        <spectrum name="s2" value="400:0.1, 500:0.2,600:0.3"/>
    </shape>
</scene>)");
    EXPECT_EQ(s->tag, "scene");
    EXPECT_EQ(s->loc.line, 1);
    ASSERT_EQ(s->children.size(), 3u);
    const XmlObject& integ = *s->children[0].obj;
    EXPECT_EQ(integ.tag, "integrator");
    EXPECT_EQ(integ.type, "path");
    EXPECT_EQ(integ.loc.line, 2);
    EXPECT_EQ(integ.loc.file, "test.xml");
    EXPECT_EQ(value_of<int64_t>(integ, "max_depth"), 8);
    EXPECT_EQ(integ.param("max_depth")->loc.line, 3);
    EXPECT_TRUE(value_of<bool>(integ, "hide_emitters"));
    const XmlObject& sensor = *s->children[1].obj;
    EXPECT_DOUBLE_EQ(value_of<double>(sensor, "fov"), 45.0);
    ASSERT_EQ(sensor.children.size(), 1u);
    EXPECT_EQ(sensor.children[0].obj->tag, "film");
    EXPECT_EQ(sensor.children[0].loc.line, 9);
    EXPECT_EQ(value_of<int64_t>(*sensor.children[0].obj, "width"), 64);
    const XmlObject& shape = *s->children[2].obj;
    const Vec3 c = value_of<Vec3>(shape, "center");
    EXPECT_EQ(c.x, 1);
    EXPECT_EQ(c.y, 0);
    EXPECT_EQ(c.z, 3);
    EXPECT_EQ(value_of<Vec3>(shape, "v").y, 2);
    EXPECT_EQ(value_of<RGB>(shape, "c").b, 0.3);
    EXPECT_EQ(value_of<RGB>(shape, "g").g, 0.5);
    const auto& s1 = value_of<SpectrumData>(shape, "s1");
    EXPECT_TRUE(s1.lambda.empty());
    ASSERT_EQ(s1.values.size(), 1u);
    EXPECT_EQ(s1.values[0], 0.25);
    const auto& s2 = value_of<SpectrumData>(shape, "s2");
    ASSERT_EQ(s2.lambda.size(), 3u);
    EXPECT_EQ(s2.lambda[2], 600);
    EXPECT_EQ(s2.values[1], 0.2);
}

TEST(SceneParser, DefaultsSubstitutionAndDefines) {
    const std::string xml = R"(<scene version="3.0.0">
    <default name="spp" value="16"/>
    <default name="name" value="mesh"/>
    <sensor type="perspective">
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <string name="file" value="meshes/$name.obj"/>
    </sensor>
</scene>)";
    auto spp_of = [](const std::shared_ptr<XmlObject>& s) {
        return value_of<int64_t>(*s->children[0].obj->children[0].obj, "sample_count");
    };
    const auto a = parse(xml);
    EXPECT_EQ(spp_of(a), 16);
    EXPECT_EQ(value_of<std::string>(*a->children[0].obj, "file"), "meshes/mesh.obj");
    const auto b = parse(xml, {{"spp", "1024"}});  // -D overrides the <default>
    EXPECT_EQ(spp_of(b), 1024);
    // A define the scene never declares is most likely a typo.
    const std::string msg = parse_error(xml, {{"sppp", "4"}});
    EXPECT_NE(msg.find("sppp"), std::string::npos) << msg;
    // A define may stand in for a <default> the scene lacks.
    const auto c = parse(R"(<scene version="3.0.0"><sensor type="$t"/></scene>)", {{"t", "perspective"}});
    EXPECT_EQ(c->children[0].obj->type, "perspective");
}

TEST(SceneParser, UnknownParamNamesFileAndLine) {
    expect_error(R"(<scene version="3.0.0">
    <default name="spp" value="16"/>
    <sensor type="perspective">

        <float name="fov" value="$fovv"/>
    </sensor>
</scene>)",
                 5, "float", "unknown parameter $fovv");
    // Defaults apply only after their declaration.
    expect_error(R"(<scene version="3.0.0">
    <bsdf type="$t"/>
    <default name="t" value="diffuse"/>
</scene>)",
                 2, "bsdf", "unknown parameter $t");
    // Mitsuba keeps the first <default> of a name.
    const auto first = parse(R"(<scene version="3.0.0">
    <default name="t" value="diffuse"/>
    <default name="t" value="conductor"/>
    <bsdf type="$t"/>
</scene>)");
    EXPECT_EQ(first->children[0].obj->type, "diffuse");
}

// Mitsuba's file resolution: <path value="..."/> adds a folder to search, and a relative file
// name in an included file is also looked up in the main scene's folder. Names resolve to the
// absolute path of the file found.
TEST(SceneParser, SearchPathsAndMitsubaFileResolution) {
    const std::string dir = kDataDir + "/mitsuba_paths";
    const auto s = parse_scene_xml_file(dir + "/scene.xml");
    ASSERT_EQ(s->children.size(), 2u);
    const auto file_of = [](const XmlObject& o) { return std::get<std::string>(o.param("filename")->value); };
    const std::filesystem::path quad = file_of(*s->children[0].obj), tri = file_of(*s->children[1].obj);
    EXPECT_TRUE(quad.is_absolute()) << quad;
    EXPECT_EQ(std::filesystem::canonical(quad), std::filesystem::canonical(dir + "/meshes/quad.obj"));
    EXPECT_EQ(std::filesystem::canonical(tri), std::filesystem::canonical(dir + "/assets/tri.obj"));
    const std::string bad = file_error(dir + "/bad_path.xml");
    EXPECT_NE(bad.find("bad_path.xml:2: <path>"), std::string::npos) << bad;
    EXPECT_NE(bad.find("no_such_folder"), std::string::npos) << bad;
    // A folder given again is searched once, at the front (issue 30: 20,000 <path value="."/>
    // took 80 s, each <path> rebuilding every candidate of the search): thousands of repeats and
    // spellings of the same folders still find tri.obj in assets/, given last.
    std::string repeated = "<scene version=\"3.0.0\">\n";
    for (int i = 0; i < 20000; ++i) repeated += i % 2 ? "<path value=\"./meshes/..\"/>" : "<path value=\"meshes\"/>";
    repeated +=
        "<path value=\"assets\"/>\n<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/></shape>\n</scene>";
    const auto r = parse_scene_xml_string(repeated, "repeated.xml", dir, {});
    EXPECT_EQ(std::filesystem::canonical(file_of(*r->children[0].obj)),
              std::filesystem::canonical(dir + "/assets/tri.obj"));
    // Only directly inside <scene>.
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere"><path value="."/></shape>
</scene>)",
                 2, "path", "only allowed directly inside <scene>");
}

TEST(SceneParser, IncludeSplicesRelativeToIncludingFile) {
    const auto s = parse_scene_xml_file(kDataDir + "/main.xml", {{"radius", "3"}});
    ASSERT_EQ(s->children.size(), 3u);
    const XmlObject& white = *s->children[0].obj;
    const XmlObject& mesh = *s->children[1].obj;  // from sub/shapes.xml
    const XmlObject& sphere = *s->children[2].obj;
    EXPECT_EQ(mesh.type, "obj");
    EXPECT_EQ(mesh.loc.line, 4);
    EXPECT_NE(mesh.loc.file.find("sub/shapes.xml"), std::string::npos) << mesh.loc.file;
    EXPECT_EQ(std::filesystem::path(mesh.base_dir).filename(), "sub");
    EXPECT_EQ(std::filesystem::path(sphere.base_dir), std::filesystem::path(kDataDir));
    EXPECT_EQ(value_of<double>(sphere, "radius"), 3.0);  // -D radius=3 beat <default> 2
    // Both refs resolve to the one <bsdf id="white"> (a shared instance).
    ASSERT_EQ(mesh.children.size(), 1u);
    ASSERT_EQ(sphere.children.size(), 1u);
    EXPECT_EQ(mesh.children[0].obj.get(), &white);
    EXPECT_EQ(sphere.children[0].obj.get(), &white);
    EXPECT_EQ(sphere.children[0].loc.line, 9);
}

TEST(SceneParser, IncludeErrors) {
    const std::string missing = file_error(kDataDir + "/missing_include.xml");
    EXPECT_NE(missing.find("missing_include.xml:3: <include>"), std::string::npos) << missing;
    EXPECT_NE(missing.find("does_not_exist.xml"), std::string::npos) << missing;
    const std::string cycle = file_error(kDataDir + "/cycle_a.xml");
    EXPECT_NE(cycle.find("cycle_b.xml:3: <include>"), std::string::npos) << cycle;
    EXPECT_NE(cycle.find("include cycle"), std::string::npos) << cycle;
    // An error inside an included file names that file and line.
    const std::string inner = file_error(kDataDir + "/bad_in_include.xml");
    EXPECT_NE(inner.find("sub/broken.xml:4:"), std::string::npos) << inner;
    EXPECT_NE(inner.find("malformed XML"), std::string::npos) << inner;
    const std::string nofile = file_error(kDataDir + "/nope.xml");
    EXPECT_NE(nofile.find("nope.xml"), std::string::npos) << nofile;
}

// Issue 30: the nesting limit is one budget across <include>s. A chain of files each nesting
// 200 levels (every one within the limit alone) overflowed the stack, and so did a long chain of
// files that only include the next; both are refused where the budget runs out.
TEST(SceneParser, NestingBudgetIsSharedAcrossIncludes) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("snell_include_chain_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const auto chain = [&](const std::string& stem, int files, int levels) {
        for (int i = 0; i < files; ++i) {
            std::string open, close;
            for (int l = 0; l < levels; ++l) open += "<bsdf type=\"twosided\">", close += "</bsdf>";
            const std::string inner = i + 1 < files ? "<include filename=\"" + stem + std::to_string(i + 1) + ".xml\"/>"
                                                    : "<bsdf type=\"diffuse\"/>";
            std::ofstream(dir / (stem + std::to_string(i) + ".xml")) << "<scene version=\"3.0.0\">\n"
                                                                     << open << inner << close << "\n</scene>\n";
        }
        std::ofstream(dir / (stem + ".xml")) << "<scene version=\"3.0.0\">\n<shape type=\"sphere\"><include filename=\""
                                             << stem << "0.xml\"/></shape>\n</scene>\n";
        return file_error((dir / (stem + ".xml")).string());
    };
    const std::string deep = chain("deep", 600, 200);
    EXPECT_NE(deep.find("deep1.xml:2: <bsdf>"), std::string::npos) << deep;
    EXPECT_NE(deep.find("nested deeper than 256 levels (counting the <include> elements"), std::string::npos) << deep;
    const std::string longer = chain("long", 3000, 0);
    EXPECT_NE(longer.find("nested deeper than 256 levels"), std::string::npos) << longer;
    // Within the budget a chain still loads.
    EXPECT_EQ(chain("ok", 20, 5), "");
    fs::remove_all(dir);
}

TEST(SceneParser, RefsAndIds) {
    const auto s = parse(R"(<scene version="3.0.0">
    <bsdf type="dielectric" id="glass"/>
    <bsdf type="twosided" id="two"><ref id="glass" name="inner"/></bsdf>
    <shape type="sphere"><ref id="two"/></shape>
</scene>)");
    EXPECT_EQ(s->children[1].obj->children[0].obj, s->children[0].obj);
    EXPECT_EQ(s->children[1].obj->children[0].name, "inner");
    EXPECT_EQ(s->children[2].obj->children[0].obj, s->children[1].obj);
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere">
        <ref id="nothere"/>
    </shape>
</scene>)",
                 3, "ref", "unknown id 'nothere'");
    expect_error(R"(<scene version="3.0.0">
    <bsdf type="diffuse" id="a"/>
    <bsdf type="diffuse" id="a"/>
</scene>)",
                 3, "bsdf", "duplicate id 'a'");
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere" id="s"/>
    <bsdf type="twosided"><ref id="s"/></bsdf>
</scene>)",
                 3, "ref", "cannot be used inside <bsdf>");
    expect_error(R"(<scene version="3.0.0">
    <bsdf type="twosided" id="loop">
        <ref id="loop"/>
    </bsdf>
</scene>)",
                 3, "ref", "cycle");
}

TEST(SceneParser, TransformCompositionMatchesTransformMath) {
    const auto s = parse(R"(<scene version="3.0.0">
    <shape type="sphere">
        <transform name="to_world">
            <translate x="1" y="-2" z="3"/>
            <rotate y="1" angle="30"/>
            <scale value="2"/>
            <rotate value="1, 1, 0" angle="-45"/>
            <scale x="1" y="3" z="0.5"/>
            <translate value="0.5 0 0"/>
        </transform>
        <transform name="m">
            <matrix value="1 0 0 4  0 0 -1 5  0 1 0 6  0 0 0 1"/>
        </transform>
        <transform name="cam">
            <lookat origin="0, 1, -5" target="0 0 0" up="0 1 0"/>
            <translate z="2"/>
        </transform>
        <transform name="id"/>
        <transform name="ax"><rotate axis="0 0 1" angle="90"/></transform>
    </shape>
</scene>)");
    const XmlObject& shape = *s->children[0].obj;
    // File order: each operation is applied after the previous ones (left-multiplied).
    const Transform expected = Transform::translate(Vec3(0.5, 0, 0)) * Transform::scale(Vec3(1, 3, 0.5)) *
                               Transform::rotate(Vec3(1, 1, 0), -45) * Transform::scale(Vec3(2)) *
                               Transform::rotate(Vec3(0, 1, 0), 30) * Transform::translate(Vec3(1, -2, 3));
    expect_matrix_near(value_of<Transform>(shape, "to_world"), expected);
    const Transform m = value_of<Transform>(shape, "m");
    const Vec3 p = m.point(Vec3(1, 2, 3));  // row-major: (1+4, -3+5, 2+6)
    EXPECT_NEAR(p.x, 5, 1e-12);
    EXPECT_NEAR(p.y, 2, 1e-12);
    EXPECT_NEAR(p.z, 8, 1e-12);
    expect_matrix_near(
        value_of<Transform>(shape, "cam"),
        Transform::translate(Vec3(0, 0, 2)) * Transform::look_at(Vec3(0, 1, -5), Vec3(0, 0, 0), Vec3(0, 1, 0)));
    EXPECT_TRUE(value_of<Transform>(shape, "id").is_identity());
    const Vec3 r = value_of<Transform>(shape, "ax").vector(Vec3(1, 0, 0));  // right-handed about +z
    EXPECT_NEAR(r.x, 0, 1e-12);
    EXPECT_NEAR(r.y, 1, 1e-12);
}

TEST(SceneParser, MalformedXmlReportsLine) {
    expect_error(
        "<scene version=\"3.0.0\">\n  <bsdf type=\"diffuse\">\n    <float name=\"a\" value=\"1\">\n  </bsdf>\n</scene>",
        4, "xml", "malformed XML");
    expect_error("<scene version=\"3.0.0\">\n\n  <bsdf type=\"diffuse\" <float/>\n</scene>", 3, "xml", "malformed XML");
    expect_error("", 1, "xml", "malformed XML");
    expect_error("<!-- only a comment -->", 1, "xml", "malformed XML");
}

TEST(SceneParser, UnknownTagsAndAttributes) {
    expect_error(R"(<scene version="3.0.0">
    <bsdf type="diffuse">
        <colour name="reflectance" value="0.5"/>
    </bsdf>
</scene>)",
                 3, "colour", "unknown tag inside <bsdf>");
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere">

        <float name="radius" value="1" units="m"/>
    </shape>
</scene>)",
                 4, "float", "unknown attribute 'units'");
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere" colour="red"/>
</scene>)",
                 2, "shape", "unknown attribute 'colour'");
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere">
        <transform name="to_world"><shear value="1"/></transform>
    </shape>
</scene>)",
                 3, "shear", "unknown tag inside <transform>");
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere">
        <film type="hdrfilm"/>
    </shape>
</scene>)",
                 3, "film", "cannot be nested inside <shape>");
    expect_error(R"(<scene version="3.0.0">
    <float name="x" value="1"/>
</scene>)",
                 2, "float", "not directly in <scene>");
    expect_error(R"(<scene version="3.0.0">
    <bsdf type="diffuse">
        <float name="x" value="1">2</float>
    </bsdf>
</scene>)",
                 3, "float", "unexpected text");
}

TEST(SceneParser, DuplicateParameterNamesBothLines) {
    expect_error(R"(<scene version="3.0.0">
    <bsdf type="diffuse">
        <float name="reflectance" value="0.5"/>
        <rgb name="reflectance" value="0.5"/>
    </bsdf>
</scene>)",
                 4, "rgb", "duplicate parameter 'reflectance' (first given at test.xml:3)");
}

TEST(SceneParser, BadValues) {
    auto in_shape = [](const std::string& tag) {
        return "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n" + tag + "\n</shape>\n</scene>";
    };
    expect_error(in_shape(R"(<float name="r" value="1.5x"/>)"), 3, "float", "not a number");
    expect_error(in_shape(R"(<integer name="n" value="2.5"/>)"), 3, "integer", "not an integer");
    expect_error(in_shape(R"(<boolean name="b" value="yes"/>)"), 3, "boolean", "not true or false");
    expect_error(in_shape(R"(<rgb name="c" value="1 2"/>)"), 3, "rgb", "1 or 3 values");
    expect_error(in_shape(R"(<spectrum name="s" value="500:1, 400:2"/>)"), 3, "spectrum", "must increase");
    expect_error(in_shape(R"(<spectrum name="s" value="500:1:2"/>)"), 3, "spectrum", "not a wavelength:value pair");
    expect_error(in_shape(R"(<point name="p" value="1" x="2"/>)"), 3, "point", "not both");
    expect_error(in_shape(R"(<float value="1"/>)"), 3, "float", "missing attribute 'name'");
    expect_error(in_shape(R"(<transform name="t"><rotate x="1"/></transform>)"), 3, "rotate",
                 "missing attribute 'angle'");
    expect_error(in_shape(R"(<transform name="t"><matrix value="1 2 3"/></transform>)"), 3, "matrix", "16");
    expect_error(in_shape(R"(<transform name="t"><matrix value="0 0 0 0 0 0 0 0 0"/></transform>)"), 3, "matrix",
                 "singular");
    expect_error(in_shape(R"(<transform name="t"><lookat origin="0 0 0" target="0 1 0" up="0 1 0"/></transform>)"), 3,
                 "lookat", "parallel");
    expect_error(in_shape(R"(<bsdf id="x"/>)"), 3, "bsdf", "missing attribute 'type'");
}

TEST(SceneParser, VersionsAndMitsuba06) {
    EXPECT_NO_THROW(parse(R"(<scene version="2.0.0"><bsdf type="diffuse"/></scene>)"));
    EXPECT_NO_THROW(parse(R"(<scene version="3.5.2"><bsdf type="diffuse"/></scene>)"));
    // Mitsuba 0.6 files are upgraded in memory: camelCase names, <lookAt>, <srgb>.
    const auto old = parse(R"(<scene version="0.6.0">
    <sensor type="perspective">
        <float name="fov" value="30"/><string name="fovAxis" value="smaller"/>
        <transform name="toWorld"><lookAt origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sampleCount" value="8"/></sampler>
    </sensor>
    <bsdf type="dielectric"><float name="intIOR" value="1.5"/><srgb name="specularReflectance" value="1, 1, 1"/></bsdf>
</scene>)");
    const XmlObject& sensor = *old->children[0].obj;
    EXPECT_NE(sensor.param("fov_axis"), nullptr);
    EXPECT_NE(sensor.param("to_world"), nullptr);
    EXPECT_NE(sensor.children[0].obj->param("sample_count"), nullptr);
    EXPECT_NE(old->children[1].obj->param("int_ior"), nullptr);
    EXPECT_NE(old->children[1].obj->param("specular_reflectance"), nullptr);
    expect_error(R"(<scene version="1.0.0"/>)", 1, "scene", "not supported (0.x, 2.x and 3.x are)");
    // Mitsuba 2's texture-valued spectra are textures by another name.
    auto m2 = parse_scene_xml_string(R"(<scene version="2.0.0">
    <bsdf type="diffuse"><spectrum name="reflectance" type="bitmap"><string name="filename" value="a.png"/></spectrum></bsdf>
</scene>)",
                                     "test.xml", ".");
    const XmlObject::Child& tex = m2->children[0].obj->children[0];
    EXPECT_EQ(tex.name, "reflectance");
    EXPECT_EQ(tex.obj->tag, "texture");
    EXPECT_EQ(tex.obj->type, "bitmap");
    expect_error(R"(<scene version="2.0.0">
    <shape type="sphere"><spectrum name="reflectance" type="bitmap"/></shape>
</scene>)",
                 2, "spectrum", "a texture cannot be nested inside <shape>");
    expect_error(R"(<scene/>)", 1, "scene", "missing attribute 'version'");
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere">
        <transform name="toWorld"/>
    </shape>
</scene>)",
                 3, "transform", "'to_world'");
    expect_error(R"(<mitsuba version="3.0.0"/>)", 1, "mitsuba", "root element must be <scene");
}

TEST(SceneParser, UnsupportedFeaturesAreClearErrors) {
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere">
        <medium type="homogeneous" name="interior"/>
    </shape>
</scene>)",
                 3, "medium", "sigma_a");
    expect_error(R"(<scene version="3.0.0">
    <shape type="sphere">
        <texture type="bitmap" name="reflectance"/>
    </shape>
</scene>)",
                 3, "texture", "cannot be nested inside <shape>");
}

TEST(SceneParser, DamagedInputIsAlwaysASceneError) {
    // Truncations and single-character corruptions of a valid scene must either parse or throw
    // SceneError: never crash, hang or leak another exception type.
    const std::string good = R"(<scene version="3.0.0">
    <default name="r" value="0.5"/>
    <bsdf type="diffuse" id="b"><rgb name="reflectance" value="0.2, 0.3, 0.4"/></bsdf>
    <shape type="sphere">
        <float name="radius" value="$r"/>
        <transform name="to_world"><rotate y="1" angle="30"/><translate value="1 2 3"/></transform>
        <spectrum name="s" value="400:1, 500:2"/>
        <ref id="b"/>
    </shape>
</scene>)";
    ASSERT_NO_THROW(parse(good));
    auto survives = [](const std::string& xml) {
        try {
            parse(xml);
        } catch (const SceneError&) {
        } catch (const std::exception& e) {
            ADD_FAILURE() << "non-scene exception '" << e.what() << "' for:\n" << xml;
        }
    };
    for (size_t n = 0; n < good.size(); ++n) survives(good.substr(0, n));
    const std::string alphabet = "<>/=\"$:, x0.-e";
    uint64_t state = 12345;  // fixed-seed LCG: the same corruptions on every run
    auto next = [&] { return (state = state * 6364136223846793005ull + 1442695040888963407ull) >> 33; };
    for (int k = 0; k < 3000; ++k) {
        std::string bad = good;
        bad[next() % bad.size()] = alphabet[next() % alphabet.size()];
        survives(bad);
    }
}
