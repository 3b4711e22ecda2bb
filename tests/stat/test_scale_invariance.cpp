// Issue 12: ray offsets come from each point's own rounding error, not from the scene's size.
// The same scene scaled by 1e-4 and by 1e4, and the original with a giant sphere far below the
// floor (which made the scene radius, and with it the old offset, 1e5 times larger), render the
// same image within noise: replicas agree per block and for the whole image (replica_stats.h).
// Before the fix the giant sphere made `nee` lose the glass sphere and `path` go black, and the
// 1e4 scale shifted `path` by about 15 %.
#include <cstdio>
#include <string>

#include "stat/replica_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// A glass sphere resting on a diffuse floor beside a diffuse block, under a rectangle light.
// Every shape's transform ends in a uniform scale by $s about the origin; the camera (whose frame
// must stay rigid, as in Mitsuba) moves to the scaled position and its clip planes scale too,
// so the scaled scenes show exactly the same picture. (No environment
// light: its power, and so its share of light samples, grows with the scene's radius, which
// the giant sphere changes; that changes the noise, not the image.)
std::string scene(bool giant) {
    std::string xml = R"(<scene version="3.0.0">
  <integrator type="$integrator"><integer name="max_depth" value="8"/></integrator>
  <sensor type="perspective"><float name="fov" value="40"/>
    <float name="near_clip" value="$near"/><float name="far_clip" value="$far"/>
    <transform name="to_world"><lookat origin="$origin" target="$target" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="8"/><rotate x="1" angle="-90"/><scale value="$s"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf></shape>
  <shape type="sphere"><transform name="to_world"><scale value="0.8"/><translate x="-0.4" y="0.8"/><scale value="$s"/></transform>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>
  <shape type="cube"><transform name="to_world"><scale value="0.35"/><translate x="1.1" y="0.35" z="0.3"/><scale value="$s"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.3, 0.2"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="0.8"/><rotate x="1" angle="90"/><translate x="-0.6" y="3.5" z="0.5"/><scale value="$s"/></transform>
    <emitter type="area"><rgb name="radiance" value="12, 12, 12"/></emitter></shape>
)";
    // Radius 1e4, its top 9e4 below the floor: out of the picture, but the scene is now 1e5 wide.
    if (giant)
        xml +=
            R"(  <shape type="sphere"><transform name="to_world"><scale value="1e4"/><translate y="-1e5"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.5, 0.5"/></bsdf></shape>
)";
    return xml + "</scene>";
}

/// The scene's parameters at scale `s` (a string, as written in the defines).
Defines at_scale(const std::string& integrator, const char* s) {
    const double k = std::stod(s);
    auto num = [](double v) {
        char b[64];
        std::snprintf(b, sizeof b, "%.17g", v);
        return std::string(b);
    };
    return {{"integrator", integrator},
            {"s", s},
            {"origin", "0, " + num(2.5 * k) + ", " + num(5 * k)},
            {"target", "0, " + num(0.7 * k) + ", 0"},
            {"near", num(0.01 * k)},
            {"far", num(1e4 * k)}};
}

constexpr int kBlock = 4;
constexpr int kReplicas = kAgreementReplicas;

void expect_same_image(const std::string& integrator, int spp) {
    const ReplicaStats original =
        replica_stats(load_xml(scene(false), at_scale(integrator, "1")), spp, kBlock, 100, kReplicas);
    EXPECT_GT(original.image.mean, 0.01) << integrator << ": the test scene must be lit";
    const struct {
        const char* what;
        bool giant;
        const char* s;
    } variants[] = {
        {"scaled by 1e-4", false, "1e-4"}, {"scaled by 1e4", false, "1e4"}, {"far giant sphere", true, "1"}};
    uint64_t seed = 1000;
    for (const auto& v : variants) {
        const LoadedScene ls = load_xml(scene(v.giant), at_scale(integrator, v.s));
        const ReplicaStats other = replica_stats(ls, spp, kBlock, seed += 1000, kReplicas);
        expect_replicas_agree(original, other, (integrator + ", " + v.what).c_str());
    }
}

}  // namespace

TEST(ScaleInvariance, PathTracerSameImageAtAnyScale) { expect_same_image("path", 16); }
TEST(ScaleInvariance, MneeSameImageAtAnyScale) { expect_same_image("mnee", 32); }
TEST(ScaleInvariance, BdptSameImageAtAnyScale) { expect_same_image("bdpt", 4); }
