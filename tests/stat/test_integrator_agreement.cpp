// `path` and `nee` are independent estimators of the same image: per pixel block their means
// must agree within the standard errors measured from independent replicas.
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// A Cornell-box-like scene with a large light, a diffuse sphere, a glass sphere and a rough
// conductor: both estimators converge here, and every BSDF family is on some path.
const char* kScene = R"(<scene version="3.0.0">
  <default name="integrator" value="nee"/>
  <integrator type="$integrator"><integer name="max_depth" value="6"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 1, 3.4" target="0, 1, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film>
    <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
  </sensor>
  <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.7, 0.7, 0.7"/></bsdf>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/><translate y="1"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="90"/><translate x="-1" y="1"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.1, 0.1"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="-90"/><translate x="1" y="1"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.1, 0.6, 0.1"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><translate y="2"/></transform><ref id="white"/></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="1.99"/></transform>
    <emitter type="area"><rgb name="radiance" value="6, 6, 6"/></emitter>
  </shape>
  <shape type="sphere"><point name="center" x="-0.45" y="0.35" z="-0.2"/><float name="radius" value="0.35"/>
    <bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0.45" y="0.35" z="0.2"/><float name="radius" value="0.35"/>
    <bsdf type="roughdielectric"><float name="alpha" value="0.3"/><float name="int_ior" value="1.5"/></bsdf></shape>
</scene>)";

}  // namespace

TEST(IntegratorAgreement, PathAndNeeAgreePerBlock) {
    LoadedScene path = load_xml(kScene, {{"integrator", "path"}});
    LoadedScene nee = load_xml(kScene, {{"integrator", "nee"}});
    const auto a = block_estimates(path, *path.scene->integrator(), 64, 8, 6, 1000);
    const auto b = block_estimates(nee, *nee.scene->integrator(), 16, 8, 6, 2000);
    expect_agreement(a, b, 0.01, "path vs nee");
}

// Sensitivity check: the test above must be able to fail. A scene where one light is twice
// as bright must be detected as different.
TEST(IntegratorAgreement, DetectsABrighterLight) {
    std::string brighter = kScene;
    brighter.replace(brighter.find("6, 6, 6"), 7, "7, 7, 7");
    LoadedScene a_scene = load_xml(kScene, {{"integrator", "nee"}});
    LoadedScene b_scene = load_xml(brighter, {{"integrator", "nee"}});
    const auto a = block_estimates(a_scene, *a_scene.scene->integrator(), 16, 8, 6, 3000);
    const auto b = block_estimates(b_scene, *b_scene.scene->integrator(), 16, 8, 6, 4000);
    const int differing = count_disagreements(a, b, 0.01);
    EXPECT_GT(differing, int(a.size()) / 2);
}
