// Shape groups and instances in renders: a scene built from two instances of a group renders as
// the same scene written out shape by shape (replicas agree per block), `mnee` finds the caustic
// of an instanced glass sphere as `nee` does, and the loader names what is not allowed.
#include "stat/replica_stats.h"
#include "unit/loader_errors.h"

using namespace snell;
using namespace snell::test;

namespace {

// A glass sphere on a diffuse block, twice: once as a group placed by two instances, once written
// out. Instance transforms: uniform scales, rotations, translations (a sphere written out takes
// only those).
std::string scene(bool instanced, const std::string& integrator = "path") {
    const std::string head = R"(<scene version="3.0.0">
  <integrator type=")" + integrator +
                             R"("><integer name="max_depth" value="8"/></integrator>
  <sensor type="perspective"><float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 4, 7" target="0, 0.5, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="24"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="6"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="1.5"/><rotate x="1" angle="90"/><translate y="5"/></transform>
    <emitter type="area"><rgb name="radiance" value="6, 6, 6"/></emitter></shape>
)";
    const std::string glass = R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>)";
    const std::string block = R"(<bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.3, 0.2"/></bsdf>)";
    // Group space: a sphere of radius 0.5 at (0, 0.8, 0) on a cube [-0.4, 0.4] x [0, 0.3] x [-0.4, 0.4].
    const char* placements[2] = {R"(<scale value="1.2"/><rotate y="1" angle="30"/><translate x="-1.3"/>)",
                                 R"(<scale value="0.8"/><rotate y="1" angle="-70"/><translate x="1.4" z="0.5"/>)"};
    std::string body;
    if (instanced) {
        body = R"(<shape type="shapegroup" id="g">
    <shape type="sphere"><point name="center" x="0" y="0.8" z="0"/><float name="radius" value="0.5"/>)" +
               glass + R"(</shape>
    <shape type="cube"><transform name="to_world"><scale x="0.4" y="0.15" z="0.4"/><translate y="0.15"/></transform>)" +
               block + R"(</shape>
  </shape>
)";
        for (const char* p : placements)
            body += std::string(R"(  <shape type="instance"><ref id="g"/><transform name="to_world">)") + p +
                    "</transform></shape>\n";
    } else {
        for (const char* p : placements) {
            body +=
                std::string(
                    R"(  <shape type="sphere"><transform name="to_world"><scale value="0.5"/><translate y="0.8"/>)") +
                p + "</transform>" + glass + "</shape>\n";
            body +=
                std::string(
                    R"(  <shape type="cube"><transform name="to_world"><scale x="0.4" y="0.15" z="0.4"/><translate y="0.15"/>)") +
                p + "</transform>" + block + "</shape>\n";
        }
    }
    return head + body + "</scene>";
}

}  // namespace

TEST(Instancing, RendersAsTheSameSceneWrittenOut) {
    expect_replicas_agree(replica_stats(load_xml(scene(true)), 16, 4, 10, 8),
                          replica_stats(load_xml(scene(false)), 16, 4, 20, 8), "instanced vs written out");
}

// The caustics under both instanced glass spheres: `mnee` walks on the placed spheres (their
// projection and differential geometry are the group sphere's, carried by the transform).
TEST(Instancing, MneeThroughInstancedGlassAgreesWithNee) {
    expect_replicas_agree(replica_stats(load_xml(scene(true, "nee")), 64, 4, 30, 8),
                          replica_stats(load_xml(scene(true, "mnee")), 16, 4, 40, 8), "nee vs mnee, instanced");
}

TEST(Instancing, LoaderErrors) {
    auto with = [](const std::string& body) {
        return "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n" + body + "\n</scene>";
    };
    expect_load_error(with(R"(<shape type="shapegroup" id="g"><shape type="sphere">
<emitter type="area"/></shape></shape>)"),
                      ".", "test.xml:4: <emitter>", "a shape in a shapegroup cannot emit");
    expect_load_error(with(R"(<shape type="instance"/>)"), ".", "test.xml:3: <shape>",
                      "an instance needs a <ref id=\"...\"/> to a shapegroup");
    expect_load_error(with(R"(<shape type="sphere" id="s"/>
<shape type="instance"><ref id="s"/></shape>)"),
                      ".", "test.xml:4: <shape>", "an instance takes exactly one <ref> to a shapegroup");
    expect_load_error(with(R"(<shape type="sphere"><shape type="sphere"/></shape>)"), ".", "test.xml:3: <shape>",
                      "only a <shape type=\"shapegroup\"> contains shapes");
    expect_load_error(with(R"(<shape type="shapegroup"/>)"), ".", "test.xml:3: <shape>", "an empty shapegroup");
}
