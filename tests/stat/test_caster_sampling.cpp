// Caster sampling (scene/caster_sampling.h, issue 26): the mixture of BSDF sampling and the
// casters' cones draws directions by the density pdf() claims (chi-square), its samples carry
// f |cos| / pdf, and it applies only where it should: reflecting non-delta vertices, casters
// outside the point and above its surface.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bsdf/bsdf.h"
#include "geometry/shape.h"
#include "scene/caster_sampling.h"
#include "scene/scene.h"
#include "stat/chi2.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// A floor with `floor_bsdf` and four glass spheres seen from the floor's origin: two above it
// (their cones apply), one below its plane and one holding the origin (theirs do not).
// `emitter`: the scene's light (an environment by default, which lights every point through
// every caster, so the shadow test passes everywhere).
std::string casters_scene(
    const std::string& floor_bsdf,
    const std::string& emitter = R"(<emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>)") {
    const std::string glass =
        R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf>)";
    const auto sphere = [&](const char* c, const char* r) {
        return std::string(R"(<shape type="sphere"><point name="center" )") + c + R"(/><float name="radius" value=")" +
               r + R"("/>)" + glass + "</shape>\n";
    };
    return R"(<scene version="3.0.0">
  <integrator type="nee"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 4, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="4"/></transform>
    )" + floor_bsdf +
           R"(</shape>
)" + sphere(R"(x="0.8" y="1.5" z="0")", "0.5") +
           sphere(R"(x="-1" y="0.9" z="0.5")", "0.3") + sphere(R"(x="0" y="-2" z="0")", "0.5") +
           sphere(R"(x="0" y="0.1" z="0")", "0.5") + emitter + "\n</scene>";
}

// The floor's point at the origin, reached from straight above (inside the fourth sphere).
SurfaceInteraction floor_point(const Scene& scene) {
    Ray ray(Vec3(0, 0.05, 0), Vec3(0, -1, 0));
    SurfaceInteraction si;
    EXPECT_TRUE(scene.intersect(ray, &si));
    EXPECT_NEAR(si.p.y, 0.0, 1e-9);
    return si;
}

struct Floor {
    const char* name;
    const char* bsdf;
};

class CasterSamplingChi2 : public ::testing::TestWithParam<Floor> {};

}  // namespace

TEST_P(CasterSamplingChi2, SamplesFollowTheMixturesPdf) {
    const Floor& fl = GetParam();
    const LoadedScene ls = load_xml(casters_scene(fl.bsdf));
    const Scene& scene = *ls.scene;
    ASSERT_EQ(scene.refractive_casters().size(), 4u);
    const SurfaceInteraction si = floor_point(scene);
    const BSDF& bsdf = *si.bsdf();
    const CasterSampling mix(scene, 0.6);
    ASSERT_TRUE(mix.applies(si, bsdf));
    BSDFContext ctx;
    ctx = ctx.at(si);
    const Vec3 wo = si.to_local(si.wo);

    Chi2Options opt;
    opt.theta_res = 24;
    opt.phi_res = 48;
    opt.test_count = 2;
    size_t bad = 0, cone = 0, checked = 0;
    std::string first_bad;
    const Chi2Result r = chi2_sphere_test(
        [&](PCG32& rng) -> std::optional<Vec3> {
            const double uc = rng.next_double();
            const Vec2 u(rng.next_double(), rng.next_double());
            const auto s = mix.sample(si, bsdf, ctx, uc, u);
            if (!s) return std::nullopt;
            ++checked;
            if (uc < 0.6) ++cone;
            const double p = mix.pdf(si, bsdf, ctx, wo, s->wi);
            const SampledSpectrum f = bsdf.eval(ctx, wo, s->wi) * (std::abs(s->wi.z) / p);
            bool ok = std::abs(s->pdf - p) <= 1e-9 * p && !s->is_delta() && !(s->lobe & kTransmission);
            for (int i = 0; i < kSpectrumSamples; ++i) ok = ok && std::abs(s->weight[i] - f[i]) <= 1e-9 * f[i] + 1e-14;
            if (!ok && !bad++) first_bad = "pdf " + std::to_string(s->pdf) + " vs " + std::to_string(p);
            return s->wi;
        },
        [&](const Vec3& wi) { return mix.pdf(si, bsdf, ctx, wo, wi); }, opt);
    EXPECT_TRUE(r.passed) << fl.name << ": " << r.message;
    // Both cones lie above the floor, so no direction is lost: the density integrates to one.
    EXPECT_NEAR(r.pdf_integral, 1.0, 2e-3) << fl.name;
    EXPECT_GT(cone, opt.samples / 2) << fl.name;
    EXPECT_EQ(bad, 0u) << fl.name << " (" << checked << " checked) " << first_bad;
}

INSTANTIATE_TEST_SUITE_P(
    Floors, CasterSamplingChi2,
    ::testing::Values(Floor{"diffuse", R"(<bsdf type="diffuse"/>)"},
                      Floor{"rough_conductor",
                            R"(<bsdf type="roughconductor"><float name="alpha" value="0.3"/></bsdf>)"}),
    [](const auto& info) { return std::string(info.param.name); });

// The mixture applies at reflecting vertices alone, and there averages the cones of the casters
// outside the point and reaching above its side of the surface: from above the floor's origin
// the two spheres above it (not the one below, not the one holding it); from below another
// point the one below and the one that reaches through the floor, not the two above. Where it does not apply it is BSDF
// sampling, draw for draw.
TEST(CasterSampling, AveragesTheConesOfTheCastersInView) {
    const LoadedScene ls = load_xml(casters_scene(R"(<bsdf type="diffuse"/>)"));
    const Scene& scene = *ls.scene;
    const double c = 0.6;
    const CasterSampling mix(scene, c);
    // 1 / the solid angle of the sphere (centre, r) seen from p.
    const auto cone_density = [](const Vec3& p, const Vec3& centre, double r) {
        const double sin2 = r * r / length_squared(centre - p);
        return 1.0 / (2 * kPi * (1 - std::sqrt(1 - sin2)));
    };
    const auto expect_mixture = [&](const SurfaceInteraction& si, const Vec3& centre, double r, int cones) {
        BSDFContext ctx;
        ctx = ctx.at(si);
        const Vec3 wo = si.to_local(si.wo), wi = si.to_local(normalize(centre - si.p));
        const double p_bsdf = si.bsdf()->pdf(ctx, wo, wi);
        EXPECT_NEAR(mix.pdf(si, *si.bsdf(), ctx, wo, wi), (1 - c) * p_bsdf + c * cone_density(si.p, centre, r) / cones,
                    1e-9);
    };
    const SurfaceInteraction top = floor_point(scene);
    ASSERT_TRUE(mix.applies(top, *top.bsdf()));
    EXPECT_FALSE(CasterSampling(scene, 0.0).applies(top, *top.bsdf()));
    expect_mixture(top, Vec3(0.8, 1.5, 0), 0.5, 2);
    expect_mixture(top, Vec3(-1, 0.9, 0.5), 0.3, 2);

    SurfaceInteraction under;
    ASSERT_TRUE(scene.intersect(Ray(Vec3(1.5, -0.05, 1.5), Vec3(0, 1, 0)), &under));
    ASSERT_TRUE(mix.applies(under, *under.bsdf()));
    expect_mixture(under, Vec3(0, -2, 0), 0.5, 2);

    SurfaceInteraction glass;  // the top of the first sphere, from above
    ASSERT_TRUE(scene.intersect(Ray(Vec3(0.8, 3, 0), Vec3(0, -1, 0)), &glass));
    ASSERT_TRUE(glass.bsdf()->is_transmissive());
    ASSERT_FALSE(mix.applies(glass, *glass.bsdf()));
    BSDFContext ctx;
    ctx = ctx.at(glass);
    const Vec3 wo = glass.to_local(glass.wo);
    for (const double uc : {0.1, 0.5, 0.9}) {
        const auto a = mix.sample(glass, *glass.bsdf(), ctx, uc, Vec2(0.2, 0.7));
        const auto b = glass.bsdf()->sample(ctx, wo, uc, Vec2(0.2, 0.7));
        ASSERT_EQ(a.has_value(), b.has_value());
        if (a) {
            EXPECT_EQ(a->wi, b->wi);
            EXPECT_EQ(a->pdf, b->pdf);
        }
    }
}

// The shadow test: with a light behind the first sphere as seen from the floor's origin, only
// that sphere's cone applies there, and at a floor point that sees no caster in front of the
// light the mixture does not apply at all. The same for a sphere light (beside a dim
// environment), a point light and a directional light along that line; a bright environment
// turns the test off.
TEST(CasterSampling, AimsOnlyAtCastersInFrontOfALight) {
    const char* lights[] = {
        // with a dim environment beside it, which the test leaves out
        R"(<shape type="sphere"><point name="center" x="2.4" y="4.5" z="0"/><float name="radius" value="0.2"/>
             <emitter type="area"><rgb name="radiance" value="10, 10, 10"/></emitter></shape>
           <emitter type="constant"><rgb name="radiance" value="0.001, 0.001, 0.001"/></emitter>)",
        R"(<emitter type="point"><point name="position" x="2.4" y="4.5" z="0"/></emitter>)",
        R"(<emitter type="directional"><vector name="direction" x="-0.8" y="-1.5" z="0"/></emitter>)",
    };
    const double c = 0.6;
    for (const char* light : lights) {
        const LoadedScene ls = load_xml(casters_scene(R"(<bsdf type="diffuse"/>)", light));
        const Scene& scene = *ls.scene;
        ASSERT_EQ(scene.bounded_lights().size(), 1u) << light;
        const CasterSampling mix(scene, c);
        const SurfaceInteraction top = floor_point(scene);
        ASSERT_TRUE(mix.applies(top, *top.bsdf())) << light;
        BSDFContext ctx;
        ctx = ctx.at(top);
        const Vec3 centre(0.8, 1.5, 0), wo = top.to_local(top.wo), wi = top.to_local(normalize(centre - top.p));
        const double sin2 = 0.25 / length_squared(centre - top.p);
        const double cone = 1.0 / (2 * kPi * (1 - std::sqrt(1 - sin2)));  // the first sphere's alone
        EXPECT_NEAR(mix.pdf(top, *top.bsdf(), ctx, wo, wi), (1 - c) * top.bsdf()->pdf(ctx, wo, wi) + c * cone, 1e-9)
            << light;
        // The second sphere's direction is BSDF sampling's alone.
        const Vec3 wi2 = top.to_local(normalize(Vec3(-1, 0.9, 0.5) - top.p));
        EXPECT_NEAR(mix.pdf(top, *top.bsdf(), ctx, wo, wi2), (1 - c) * top.bsdf()->pdf(ctx, wo, wi2), 1e-12) << light;

        SurfaceInteraction lit;  // a floor point no caster shadows
        ASSERT_TRUE(scene.intersect(Ray(Vec3(3, 1, -3), Vec3(0, -1, 0)), &lit));
        EXPECT_FALSE(mix.applies(lit, *lit.bsdf())) << light;
    }
    // An environment brighter than the sphere light lights every point through every caster.
    const LoadedScene ls = load_xml(casters_scene(R"(<bsdf type="diffuse"/>)", R"(
        <shape type="sphere"><point name="center" x="2.4" y="4.5" z="0"/><float name="radius" value="0.2"/>
          <emitter type="area"><rgb name="radiance" value="10, 10, 10"/></emitter></shape>
        <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>)"));
    EXPECT_TRUE(ls.scene->bounded_lights().empty());
    SurfaceInteraction lit;
    ASSERT_TRUE(ls.scene->intersect(Ray(Vec3(3, 1, -3), Vec3(0, -1, 0)), &lit));
    EXPECT_TRUE(CasterSampling(*ls.scene, c).applies(lit, *lit.bsdf()));
}

// Scene::manifold_casters (the shapes whose surface trials MNEE runs at every trial connection)
// holds the glass alone, in shapes()' order: not the diffuse floor, not an emitter with a glass
// BSDF, not a rough conductor; a rough dielectric is one. Built once at build(), so a scene of
// thousands of opaque shapes no longer costs each connection a scan of them all.
TEST(CasterSampling, ManifoldCastersAreTheSceneGlassAlone) {
    const LoadedScene ls = load_xml(casters_scene(R"(<bsdf type="diffuse"/>)", R"(
  <shape type="sphere"><point name="center" x="3" y="3" z="0"/><float name="radius" value="0.2"/>
    <bsdf type="roughdielectric"><float name="alpha" value="0.1"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="-3" y="3" z="0"/><float name="radius" value="0.2"/>
    <bsdf type="roughconductor"><float name="alpha" value="0.1"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0" y="3" z="-3"/><float name="radius" value="0.2"/>
    <bsdf type="dielectric"/><emitter type="area"><rgb name="radiance" value="1, 1, 1"/></emitter></shape>)"));
    const Scene& scene = *ls.scene;
    std::vector<const Shape*> glass;
    for (const auto& s : scene.shapes())
        if (!s->emitter() && s->bsdf() && s->bsdf()->is_refractive_interface(550.0)) glass.push_back(s.get());
    ASSERT_EQ(glass.size(), 5u);  // the four spheres and the rough one
    EXPECT_EQ(scene.manifold_casters(), glass);
    EXPECT_EQ(scene.refractive_casters().size(), glass.size());
}
