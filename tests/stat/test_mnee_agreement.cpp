// MNEE is unbiased: on scenes where NEE converges (a large light), `mnee` and `nee` agree per
// pixel block within their confidence intervals, for smooth and rough droplets; without
// refractive objects `mnee` is `nee` sample for sample; the biased variant only removes energy.
#include <array>
#include <cmath>
#include <iostream>

#include "integrators/path/technique_stats.h"
#include "manifold/walk_counters.h"
#include "stat/droplet_scene.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

std::string scene_with(const std::string& droplet_bsdf, const std::string& extra = "", const std::string& light = "") {
    std::string s = droplet_scene(droplet_bsdf, extra);
    if (!light.empty()) {
        const size_t a =
            s.find("  <shape type=\"rectangle\">\n    <transform name=\"to_world\"><scale value=\"1.5\"/>");
        const size_t b = s.find("</shape>", a) + 8;
        s.replace(a, b - a, light);
    }
    return s;
}

std::string smooth_water() {
    return R"(<bsdf type="dielectric"><float name="int_ior" value="1.33"/><float name="ext_ior" value="1"/></bsdf>)";
}
std::string rough_water(double alpha, const char* distribution = "beckmann") {
    return std::string(R"(<bsdf type="roughdielectric"><string name="distribution" value=")") + distribution +
           R"("/><float name="alpha" value=")" + std::to_string(alpha) +
           R"("/><float name="int_ior" value="1.33"/><float name="ext_ior" value="1"/></bsdf>)";
}

// The scene's mnee with every region walking (allocation=fixed): these tests are of the
// estimators themselves, whose share of the light a learned allocation would vary per region
// (test_connection_allocation.cpp tests that).
std::string walked_everywhere(std::string xml) {
    const std::string at = R"(<integer name="max_depth" value="8"/>)";
    if (xml.find("\"allocation\"") == std::string::npos && xml.find(at) != std::string::npos)
        xml.insert(xml.find(at) + at.size(), R"(<string name="allocation" value="fixed"/>)");
    return xml;
}

// `replicas` of mnee's render give each block's standard error; heavy-tailed estimators (the
// 1 / p counts of solutions=unbiased) need more of them for an honest one.
void expect_mnee_matches_nee(const std::string& xml, int nee_spp, int mnee_spp, const char* what,
                             const std::string& nee_xml = "", int replicas = 8) {
    LoadedScene nee = load_xml(nee_xml.empty() ? xml : nee_xml, {{"integrator", "nee"}});
    LoadedScene mnee = load_xml(walked_everywhere(xml), {{"integrator", "mnee"}});
    const auto a = block_estimates(nee, *nee.integrator, nee_spp, 8, 6, 100);
    const auto b = block_estimates(mnee, *mnee.integrator, mnee_spp, replicas, 6, 200);
    expect_agreement(a, b, 0.01, what);
}

}  // namespace

TEST(MneeAgreement, SmoothDropletMatchesNee) {
    expect_mnee_matches_nee(scene_with(smooth_water()), 256, 64, "smooth droplet");
}

class MneeRough : public ::testing::TestWithParam<double> {};
TEST_P(MneeRough, RoughDropletMatchesNee) {
    expect_mnee_matches_nee(scene_with(rough_water(GetParam())), 256, 64, "rough droplet");
}
INSTANTIATE_TEST_SUITE_P(Alphas, MneeRough, ::testing::Values(0.02, 0.1, 0.5));

// Roughness from a texture (issue 11): a checkerboard of alpha 0.05 and 0.3 over the droplet,
// 8 x 8 cells around it. The walk re-reads each vertex's target half vector with the roughness
// where the vertex lies, and D(h) is the converged vertex's, so the estimator stays unbiased.
TEST(MneeAgreement, TexturedRoughnessDropletMatchesNee) {
    const std::string bsdf = R"(<bsdf type="roughdielectric">
      <texture type="checkerboard" name="alpha"><float name="color0" value="0.05"/><float name="color1" value="0.3"/>
        <transform name="to_uv"><scale x="4" y="4"/></transform></texture>
      <float name="int_ior" value="1.33"/><float name="ext_ior" value="1"/></bsdf>)";
    expect_mnee_matches_nee(scene_with(bsdf), 256, 64, "checkerboard roughness droplet");
}

TEST(MneeAgreement, GgxDropletMatchesNee) {
    expect_mnee_matches_nee(scene_with(rough_water(0.05, "ggx")), 256, 64, "ggx droplet");
}

TEST(MneeAgreement, WithoutRefractionMneeIsNeeSampleForSample) {
    // Same seed, same random numbers: MNEE degenerates to NEE exactly (paper Sec. 3.1).
    const std::string xml = scene_with(R"(<bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf>)");
    LoadedScene nee = load_xml(xml, {{"integrator", "nee"}});
    LoadedScene mnee = load_xml(xml, {{"integrator", "mnee"}});
    RenderOptions opt;
    opt.spp = 4;
    opt.progress = false;
    const auto a = render(*nee.scene, *nee.integrator, nee.film, opt).film.to_linear_srgb();
    const auto b = render(*mnee.scene, *mnee.integrator, mnee.film, opt).film.to_linear_srgb();
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "component " << i;
}

TEST(MneeAgreement, BiasedVariantOnlyRemovesEnergy) {
    // Sec. 3.5: outlier removal zeroes transmissive-suffix paths MNEE cannot find (past caustic
    // folds): never brighter than the unbiased estimate, and strictly darker.
    const std::string xml = scene_with(smooth_water(), R"(<boolean name="biased" value="$biased"/>)");
    LoadedScene unbiased = load_xml(xml, {{"integrator", "mnee"}, {"biased", "false"}});
    LoadedScene biased = load_xml(xml, {{"integrator", "mnee"}, {"biased", "true"}});
    const auto u = block_estimates(unbiased, *unbiased.integrator, 64, 8, 6, 300);
    const auto b = block_estimates(biased, *biased.integrator, 64, 8, 6, 400);
    double su = 0, sb = 0;
    for (size_t i = 0; i < u.size(); ++i) {
        // One-sided: the biased mean may not exceed the unbiased one beyond noise.
        const double se = std::sqrt(u[i].stderr_ * u[i].stderr_ + b[i].stderr_ * b[i].stderr_);
        EXPECT_LT(b[i].mean, u[i].mean + 4.5 * se + 1e-9) << "block " << i;
        su += u[i].mean;
        sb += b[i].mean;
    }
    EXPECT_LT(sb, su);
}

// With the unbiased estimator the biased mode weighs the reflected connection by MIS, as the
// unbiased mode does: the outlier rule no longer drops BSDF sampling's copies of its paths, so a
// weight of 1 would count them twice (its light 5 % high: caught). BSDF sampling's light after a
// reflection is kept (most of it here is that class; the rule's reach itself is checked with the
// paper's estimator below, where both modes draw the same samples), MNEE's light is there, and
// the biased mode keeps at least 95 % of the image and adds none.
TEST(MneeAgreement, BiasedModeWeighsTheReflectedConnectionByMis) {
    const std::string unbiased =
        R"(<string name="solutions" value="unbiased"/><string name="seeding" value="straight+surface"/>)";
    struct ByTechnique {
        Moments reflected;
        double mnee, connected_reflection;
        Moments image;
    };
    const auto by_technique = [&](bool biased) {
        LoadedScene ls =
            load_xml(scene_with(smooth_water(), unbiased + (biased ? R"(<boolean name="biased" value="true"/>)" : "")),
                     {{"integrator", "mnee"}});
        RenderOptions opt;
        opt.spp = 16;
        opt.progress = false;
        const RenderResult r = render(*ls.scene, *ls.integrator, ls.film, opt);
        const auto mean = [&](const char* name) { return r.counters.moments(*find_stat(name)).mean(); };
        return ByTechnique{r.counters.moments(*find_stat("path.technique.bsdf_reflected")),
                           mean("path.technique.mnee_surface") + mean("path.technique.mnee_straight"),
                           mean("path.technique.mnee_reflected"), r.counters.moments(*find_stat("path.sample"))};
    };
    const ByTechnique u = by_technique(false), b = by_technique(true);
    const auto se = [](const Moments& m) { return m.mean() * std::sqrt(m.relative_variance() / double(m.count)); };
    std::cout << "[biased] BSDF sampling's reflected light " << u.reflected.mean() << " +- " << se(u.reflected)
              << " -> " << b.reflected.mean() << " +- " << se(b.reflected) << ", MNEE " << u.mnee << " -> " << b.mnee
              << ", reflected connection " << u.connected_reflection << " -> " << b.connected_reflection << ", image "
              << u.image.mean() << " -> " << b.image.mean() << "\n";
    EXPECT_GT(u.reflected.mean(), 0.0);
    EXPECT_GT(b.reflected.mean(), 0.0);
    EXPECT_GT(b.mnee, 0.0);
    EXPECT_GT(b.connected_reflection, 0.0);
    EXPECT_LT(std::abs(b.connected_reflection - u.connected_reflection), 0.02 * u.connected_reflection);
    EXPECT_GT(b.image.mean(), 0.95 * u.image.mean());
    EXPECT_LT(b.image.mean(), u.image.mean() + 4 * std::hypot(se(u.image), se(b.image)));
}

// The rule's other half, with the paper's estimator (one solution, the straight seed's): BSDF
// sampling's refracted light where Alg. 2's walk does not reach the path (past the droplet's fold)
// is dropped; its light after a reflection stays. The two modes draw the same samples and weigh
// them alike, so the difference is what the rule drops, not noise (22 % of the refracted light).
TEST(MneeAgreement, BiasedModeDropsWhatThePapersWalkCannotReach) {
    const auto run = [&](bool biased) {
        LoadedScene ls =
            load_xml(scene_with(smooth_water(), std::string(R"(<string name="solutions" value="one"/>)") +
                                                    (biased ? R"(<boolean name="biased" value="true"/>)" : "")),
                     {{"integrator", "mnee"}});
        RenderOptions opt;
        opt.spp = 16;
        opt.progress = false;
        return render(*ls.scene, *ls.integrator, ls.film, opt).counters;
    };
    const StatTotals u = run(false), b = run(true);
    const Moments ur = u.moments(*find_stat("path.technique.bsdf_refracted")),
                  br = b.moments(*find_stat("path.technique.bsdf_refracted"));
    const double se = ur.mean() * std::sqrt(ur.relative_variance() / double(ur.count));
    const double reflected_u = u.moments(*find_stat("path.technique.bsdf_reflected")).mean(),
                 reflected_b = b.moments(*find_stat("path.technique.bsdf_reflected")).mean();
    std::cout << "[biased, paper's estimator] BSDF sampling's refracted light " << ur.mean() << " +- " << se << " -> "
              << br.mean() << ", reflected " << reflected_u << " -> " << reflected_b << "\n";
    EXPECT_LT(br.mean(), 0.9 * ur.mean());
    EXPECT_GT(reflected_b, 0.0);
    EXPECT_EQ(reflected_b, reflected_u);
}

// The biased mode's outlier clamp (max_sample_share 0.5 by default): no pixel is dominated by one
// sample, the clamp takes little of the image and its spread (clamp_spread 8 by default) puts
// nearly all of that back on neighbouring pixels, and without it (max_sample_share=0) the same
// render has dominated pixels (MNEE's own samples at the droplet caustic's fold). The renders
// share their samples (fixed seeds), so the images' sums differ by exactly the light the clamp
// drops: with the spread, what no disc hid; with clamp_spread=0, all it takes.
TEST(MneeAgreement, BiasedModeLetsNoSampleDominateAPixel) {
    const auto run = [](const std::string& extra) {
        LoadedScene ls = load_xml(scene_with(smooth_water(), R"(<boolean name="biased" value="true"/>)" + extra),
                                  {{"integrator", "mnee"}});
        RenderOptions opt;
        opt.spp = 32;
        opt.progress = false;
        return render(*ls.scene, *ls.integrator, ls.film, opt);
    };
    const RenderResult clamped = run(""), raw = run(R"(<float name="max_sample_share" value="0"/>)");
    std::cout << "[biased] dominated pixels " << raw.dominance.dominated << " -> " << clamped.dominance.dominated
              << ", clamped " << clamped.dominance.clamped << " taking " << clamped.dominance.clamped_share
              << " of the luminance, " << clamped.dominance.spread_share << " spread back\n";
    EXPECT_GT(raw.dominance.dominated, 0u);
    EXPECT_EQ(raw.dominance.clamped, 0u);
    // Every dominated pixel names the technique of its largest sample.
    ASSERT_EQ(raw.technique_names.size(), size_t(kTechniqueCount));
    uint64_t attributed = 0;
    std::cout << "[biased] dominated pixels by technique without the clamp:";
    for (size_t t = 0; t < raw.dominance.dominated_by_technique.size(); ++t) {
        attributed += raw.dominance.dominated_by_technique[t];
        std::cout << " " << raw.technique_names[t] << " " << raw.dominance.dominated_by_technique[t];
    }
    std::cout << "\n";
    EXPECT_EQ(attributed, raw.dominance.dominated);
    EXPECT_EQ(clamped.dominance.dominated, 0u);
    EXPECT_GT(clamped.dominance.clamped, 0u);
    EXPECT_LT(clamped.dominance.clamped_share, 0.05);
    EXPECT_GT(clamped.dominance.spread_share, 0.9 * clamped.dominance.clamped_share);
    const RenderResult dropped = run(R"(<integer name="clamp_spread" value="0"/>)");
    EXPECT_EQ(dropped.dominance.dominated, 0u);
    EXPECT_EQ(dropped.dominance.spread_share, 0.0);
    const auto image_y = [](const Film& f) {
        double s = 0;
        for (int y = 0; y < f.height(); ++y)
            for (int x = 0; x < f.width(); ++x) s += f.xyz(x, y).y;
        return s;
    };
    const double lost = clamped.dominance.clamped_share - clamped.dominance.spread_share;
    EXPECT_NEAR(image_y(clamped.film) / image_y(raw.film), 1 - lost, 1e-9);
    EXPECT_NEAR(image_y(dropped.film) / image_y(raw.film), 1 - dropped.dominance.clamped_share, 1e-9);
    EXPECT_THROW(
        load_xml(scene_with(smooth_water(), R"(<float name="max_sample_share" value="1"/>)"), {{"integrator", "mnee"}}),
        SceneError);
}

// Lights at infinity: MNEE connects to a far point in the sampled direction (light_point.h).
TEST(MneeAgreement, EnvironmentThroughDropletMatchesNee) {
    const std::string env = R"(<emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>)";
    expect_mnee_matches_nee(scene_with(smooth_water(), "", env), 128, 32, "constant environment, smooth");
    expect_mnee_matches_nee(scene_with(rough_water(0.1), "", env), 128, 32, "constant environment, rough");
}

// The same droplet scene scaled by 1000 (camera, shapes, light) renders the same image:
// every tolerance is relative to the scene's size.
TEST(MneeAgreement, SceneScaledBy1000RendersTheSame) {
    const std::string xml = scene_with(rough_water(0.05));
    std::string scaled = xml;
    // Wrap the whole scene in a scale: camera origin/target, sphere centre/radius, transforms.
    const auto replace_all = [&](const std::string& a, const std::string& b) {
        for (size_t i = scaled.find(a); i != std::string::npos; i = scaled.find(a, i + b.size()))
            scaled.replace(i, a.size(), b);
    };
    replace_all(R"(origin="0, 3.2, 3.2" target="0, 0.2, 0")", R"(origin="0, 3200, 3200" target="0, 200, 0")");
    replace_all(R"(<point name="center" x="0" y="0.35" z="0"/><float name="radius" value="0.8"/>)",
                R"(<point name="center" x="0" y="350" z="0"/><float name="radius" value="800"/>)");
    replace_all(R"(<scale value="4"/>)", R"(<scale value="4000"/>)");
    replace_all(R"(<scale value="1.5"/><rotate x="1" angle="90"/><translate x="-0.8" y="3" z="-0.5"/>)",
                R"(<scale value="1500"/><rotate x="1" angle="90"/><translate x="-800" y="3000" z="-500"/>)");
    ASSERT_NE(scaled, xml);
    LoadedScene a = load_xml(xml, {{"integrator", "mnee"}});
    LoadedScene b = load_xml(scaled, {{"integrator", "mnee"}});
    // Radiance is scale-free, so the images agree statistically block by block.
    const auto ea = block_estimates(a, *a.integrator, 32, 8, 6, 500);
    const auto eb = block_estimates(b, *b.integrator, 32, 8, 6, 600);
    expect_agreement(ea, eb, 0.01, "scaled by 1000");
}

// The ray-cast projection (the alternative to closest-point search, Sec. 3.4) and the
// over-relaxed walk (Table 1, variant B) change only efficiency, never the expectation.
TEST(MneeAgreement, RayCastProjectionAndVariantBAreUnbiased) {
    expect_mnee_matches_nee(scene_with(smooth_water(), R"(<string name="projection" value="raycast"/>)"), 256, 64,
                            "raycast projection", scene_with(smooth_water()));
    expect_mnee_matches_nee(scene_with(smooth_water(), R"(<boolean name="allow_error_increase" value="true"/>)"), 256,
                            64, "variant B", scene_with(smooth_water()));
}

// Rough absorbing glass: the light reached by refracting at a rough vertex lies across the
// interface, so NEE there must attenuate with the other side's medium. `path` (BSDF sampling
// only) is the independent reference for both `nee` and `mnee`.
TEST(MneeAgreement, AbsorbingRoughGlassMatchesPathTracing) {
    const std::string glass =
        R"(<bsdf type="roughdielectric"><float name="alpha" value="0.3"/><float name="int_ior" value="1.5"/>
        <float name="ext_ior" value="1"/><rgb name="sigma_a" value="0.5, 0.2, 0.8"/></bsdf>)";
    const std::string xml = scene_with(glass);
    LoadedScene path = load_xml(xml, {{"integrator", "pt"}});
    const auto ref = block_estimates(path, *path.integrator, 512, 8, 6, 700);
    for (const char* integ : {"nee", "mnee"}) {
        LoadedScene ls = load_xml(xml, {{"integrator", integ}});
        expect_agreement(ref, block_estimates(ls, *ls.integrator, 96, 8, 6, 800), 0.01, integ);
    }
}

// A glowing glass sphere: BSDF-sampled hits of an emitter that is itself a refractive
// interface end the path there; they must not be treated as a chain vertex. Paths through it
// are the straight seed's alone (surface seeds neither start on nor cross an emitter): MIS must
// weigh them by Alg. 2 with SMS's weighting too (surface_weight 1; the solution density's 0 made
// the image 40 % too bright), and with surface seeds alone only BSDF sampling produces them.
TEST(MneeAgreement, EmissiveDielectricMatchesPathTracing) {
    const std::string glowing = R"(<bsdf type="dielectric"><float name="int_ior" value="1.33"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="0.5, 0.5, 0.5"/></emitter>)";
    const std::string xml = scene_with(glowing);
    LoadedScene path = load_xml(xml, {{"integrator", "pt"}});
    const auto reference = block_estimates(path, *path.integrator, 256, 8, 6, 900);
    LoadedScene mnee = load_xml(xml, {{"integrator", "mnee"}});
    expect_agreement(reference, block_estimates(mnee, *mnee.integrator, 64, 8, 6, 1000), 0.01, "emissive dielectric");
    LoadedScene sms =
        load_xml(scene_with(glowing, R"(<float name="surface_weight" value="1"/>)"), {{"integrator", "mnee"}});
    expect_agreement(reference, block_estimates(sms, *sms.integrator, 64, 8, 6, 1200), 0.01,
                     "emissive dielectric, SMS's weighting");
    LoadedScene surface = load_xml(
        scene_with(glowing, R"(<string name="solutions" value="unbiased"/><string name="seeding" value="surface"/>)"),
        {{"integrator", "mnee"}});
    expect_agreement(reference, block_estimates(surface, *surface.integrator, 64, 8, 6, 1100), 0.01,
                     "emissive dielectric, surface seeds alone");
}

// An air bubble (interior less dense than the outside, eta < 1): the walk must converge
// there too (the half vector's orientation depends on which side is denser).
TEST(MneeAgreement, BubbleWithEtaBelowOneConvergesAndMatchesNee) {
    const std::string bubble =
        R"(<bsdf type="dielectric"><float name="int_ior" value="1.0"/><float name="ext_ior" value="1.33"/></bsdf>)";
    const std::string xml = scene_with(bubble);
    LoadedScene mnee = load_xml(xml, {{"integrator", "mnee"}});
    RenderOptions opt;
    opt.spp = 8;
    opt.progress = false;
    const RenderResult r = render(*mnee.scene, *mnee.integrator, mnee.film, opt);
    ASSERT_GT(r.counters[walk_counters::walks_started], 100u);
    EXPECT_GT(double(r.counters[walk_counters::walks_converged]),
              0.2 * double(r.counters[walk_counters::walks_started]));
    // Every walk ends in exactly one WalkEnd bin, for Alg. 1 and for Alg. 2.
    uint64_t alg1 = 0, alg2 = 0;
    for (uint64_t n : r.counters.bins(walk_counters::walk_end_alg1)) alg1 += n;
    for (uint64_t n : r.counters.bins(walk_counters::walk_end_alg2)) alg2 += n;
    EXPECT_EQ(alg1, r.counters[walk_counters::walks_started]);
    EXPECT_EQ(alg2, r.counters[walk_counters::pdf_walks]);
    EXPECT_GT(alg2, 0u);
    expect_mnee_matches_nee(xml, 256, 64, "bubble");
}

// Every solution per shading point (solutions=all or unbiased, surface seeds): the density is
// then the solution density, the same for the paths it finds and for the BSDF-sampled copies of
// any solution, so MIS stays a partition of unity; smooth and rough droplets agree with nee.
// (Finite trials can miss a solution, biasing low; 16 trials per caster find both branches here.)
TEST(MneeAgreement, EverySolutionEstimatorsAgreeWithNee) {
    const std::string all =
        R"(<string name="solutions" value="all"/><string name="seeding" value="straight+surface"/>)";
    expect_mnee_matches_nee(scene_with(smooth_water(), all), 256, 32, "all solutions, smooth",
                            scene_with(smooth_water()));
    expect_mnee_matches_nee(scene_with(rough_water(0.1), all), 256, 32, "all solutions, rough 0.1",
                            scene_with(rough_water(0.1)));
    const std::string unbiased =
        R"(<string name="solutions" value="unbiased"/><string name="seeding" value="straight+surface"/>)";
    expect_mnee_matches_nee(scene_with(smooth_water(), unbiased), 256, 32, "unbiased, smooth",
                            scene_with(smooth_water()));
    // Rough: the issue's roughnesses 0.02 and 0.2, and 0.1.
    // (32 replicas of 16 spp: with 8 of 32, one heavy 1 / p count in a block of the α 0.02 droplet
    // gave a standard error too small, and a false alarm, with one seed as with the other; with 16
    // of 16 caster sampling's new stream did the same, block 4 at 4.3 standard errors, while
    // renders of 1,024 spp put that block at 0.4142 and 0.4187 against nee's 0.4149, with or
    // without the mixture alike; docs/experiments.md, fourteenth measurement.)
    for (const double alpha : {0.02, 0.1, 0.2})
        expect_mnee_matches_nee(scene_with(rough_water(alpha), unbiased), 256, 16,
                                ("unbiased, rough " + std::to_string(alpha)).c_str(), scene_with(rough_water(alpha)),
                                32);
}

namespace {

// The droplet with an opaque diffuse ball inside it (the glass sphere scene's cube): every
// straight seed that crosses the ball is blocked.
std::string with_ball(std::string xml) {
    const std::string ball = R"(<shape type="sphere"><point name="center" x="0" y="0.45" z="0"/>
    <float name="radius" value="0.3"/><bsdf type="diffuse"/></shape>)";
    xml.insert(xml.rfind("</scene>"), ball);
    return xml;
}

// The share of the refracted light (paths x_b, refractions, light) that MNEE delivers, from the
// per-technique statistics of one render; the rest comes from BSDF sampling hitting the light.
double mnee_share(const std::string& xml) {
    LoadedScene ls = load_xml(walked_everywhere(xml), {{"integrator", "mnee"}});
    RenderOptions opt;
    opt.spp = 16;
    opt.progress = false;
    const RenderResult r = render(*ls.scene, *ls.integrator, ls.film, opt);
    const auto mean = [&](const char* name) { return r.counters.moments(*find_stat(name)).mean(); };
    const double mnee = mean("path.technique.mnee_straight") + mean("path.technique.mnee_surface");
    // The techniques partition each sample's radiance.
    double sum = 0;
    for (const char* t : {"emitted", "bsdf_hit", "bsdf_refracted", "bsdf_reflected", "nee", "mnee_straight",
                          "mnee_surface", "mnee_reflected"})
        sum += mean((std::string("path.technique.") + t).c_str());
    EXPECT_NEAR(sum, mean("path.sample"), 1e-9 * mean("path.sample"));
    return mnee / (mnee + mean("path.technique.bsdf_refracted"));
}

}  // namespace

// Glass around an opaque object: a straight seed through the object is blocked, but refracted
// paths pass beside it. The paper's MNEE gives those up to BSDF sampling; the multi-solution
// estimators still run their surface seeds there (SeedStatus::Blocked) and deliver
// most of that light (0.86 against the paper's 0.69 here), and stay unbiased: they agree with nee. (Before surface
// seeds ran for blocked straight seeds, the glass sphere scene's floor caustic got 0.1 % of its light from MNEE;
// docs/experiments.md.)
TEST(MneeAgreement, GlassAroundAnOpaqueBallAgreesAndMneeFindsThePathsAroundIt) {
    const std::string unbiased =
        R"(<string name="solutions" value="unbiased"/><string name="seeding" value="straight+surface"/>)";
    const std::string fallback = R"(<string name="solutions" value="fallback"/>)";
    const double one = mnee_share(with_ball(scene_with(smooth_water(), R"(<string name="solutions" value="one"/>)")));
    const double multi = mnee_share(with_ball(scene_with(smooth_water(), unbiased)));
    const double fell_back = mnee_share(with_ball(scene_with(smooth_water(), fallback)));
    std::cout << "[ball] share of the refracted light from MNEE: paper " << one << ", unbiased " << multi
              << ", fallback (the biased mode's default) " << fell_back << "\n";
    EXPECT_GT(multi, 0.8);
    EXPECT_GT(multi, one + 0.1);
    EXPECT_GT(fell_back, one + 0.1);
    expect_mnee_matches_nee(with_ball(scene_with(smooth_water(), unbiased)), 256, 32,
                            "unbiased, glass around an opaque ball", with_ball(scene_with(smooth_water())));
    // fallback: Alg. 2 where the straight seed is clear, the solution density where the ball
    // blocks it; smooth and rough.
    expect_mnee_matches_nee(with_ball(scene_with(smooth_water(), fallback)), 256, 32,
                            "fallback, glass around an opaque ball", with_ball(scene_with(smooth_water())));
    expect_mnee_matches_nee(with_ball(scene_with(rough_water(0.2), fallback)), 256, 32,
                            "fallback, rough 0.2 glass around an opaque ball", with_ball(scene_with(rough_water(0.2))));
}

// The paper's estimator (solutions=one: the straight seed's solution, MIS by Alg. 2), no longer
// the default, still agrees with nee.
TEST(MneeAgreement, PaperEstimatorMatchesNee) {
    const std::string one = R"(<string name="solutions" value="one"/>)";
    expect_mnee_matches_nee(scene_with(smooth_water(), one), 256, 64, "one, smooth", scene_with(smooth_water()));
    expect_mnee_matches_nee(scene_with(rough_water(0.1), one), 256, 64, "one, rough 0.1", scene_with(rough_water(0.1)));
}

// connect_probability (issue 26): MNEE connects a refracting light sample with probability q,
// counts it 1 / q, and MIS weighs its density as q p_mnee, here q = 0.3 under the droplet's large
// light. Dropping the 1 / q darkens the caustic, and so does leaving q out of the BSDF-sampled
// paths' weights (the weights then sum to less than one): both fail this test (docs/testing.md).
TEST(MneeAgreement, ConnectProbabilityIsCountedAndWeighed) {
    const std::string q = R"(<float name="connect_probability" value="0.3"/>)";
    expect_mnee_matches_nee(scene_with(smooth_water(), q), 256, 64, "q 0.3, smooth", scene_with(smooth_water()));
    expect_mnee_matches_nee(scene_with(rough_water(0.1), q), 256, 64, "q 0.3, rough 0.1", scene_with(rough_water(0.1)));
}

// mis_cutoff (issue 26, point 5): MNEE has no MIS share of a path where the other techniques'
// density exceeds K q times solution_density_bound, on both sides of the path. At K = 0.5 that
// takes most of the droplet's caustic from MNEE (the default 10 cuts where its weight is under
// 1 %). Cutting on one side only (MNEE's solutions dropped while BSDF sampling still weighs them,
// or the reverse) darkens or brightens the caustic, and fails here (docs/testing.md).
TEST(MneeAgreement, MisCutoffCutsBothSidesAlike) {
    const std::string k = R"(<float name="mis_cutoff" value="0.5"/>)";
    expect_mnee_matches_nee(scene_with(smooth_water(), k), 256, 64, "cutoff 0.5, smooth", scene_with(smooth_water()));
    expect_mnee_matches_nee(scene_with(rough_water(0.1), k), 256, 64, "cutoff 0.5, rough 0.1",
                            scene_with(rough_water(0.1)));
}

// With reflections, surface seeds also reflect (Fresnel's probability), so the multi-solution
// estimators find paths with an internal reflection too and MIS shares that light with BSDF
// sampling: the image still agrees with nee, so the density and MIS changes leave the rest of
// the light intact. It cannot see errors in the reflection paths' own value: they carry too
// little light here (a reflection factor doubled passes; see docs/testing.md). That the seeds
// reach such paths is ManifoldSolutions.ReflectionsFindPathsWithAnInternalReflection.
// SMS's weighting (surface_weight 1), under which reflecting paths beside a clear straight seed
// are the technique's; and the default weighting, under which they are BSDF sampling's there.
TEST(MneeAgreement, UnbiasedWithReflectionsAgreesWithNee) {
    const std::string with =
        R"(<string name="solutions" value="unbiased"/><string name="seeding" value="straight+surface"/>
      <boolean name="reflections" value="true"/>)";
    const std::string sms = with + R"(<float name="surface_weight" value="1"/>)";
    expect_mnee_matches_nee(scene_with(smooth_water(), sms), 256, 32, "unbiased with reflections, smooth",
                            scene_with(smooth_water()));
    expect_mnee_matches_nee(scene_with(rough_water(0.1), sms), 256, 32, "unbiased with reflections, rough 0.1",
                            scene_with(rough_water(0.1)));
    expect_mnee_matches_nee(scene_with(rough_water(0.1), with), 256, 32,
                            "reflections with the default surface_weight, rough 0.1", scene_with(rough_water(0.1)));
}

// A glass rod (an open cylinder, IOR 1.5) lying above the floor under a large light: MNEE walks
// its chains on the cylinder's mantle (its closest point and shape operator) and agrees with nee.
// It cannot see a 20 % error in the mantle's curvature (MNEE carries 12 % of this image, BSDF
// sampling much of the rest); GeometryCylinder.DifferentialGeometryMatchesFiniteDifferences does.
TEST(MneeAgreement, GlassCylinderMatchesNee) {
    const std::string rod = R"(<scene version="3.0.0">
  <integrator type="$integrator"><integer name="max_depth" value="8"/></integrator>
  <sensor type="perspective"><float name="fov" value="35"/>
    <transform name="to_world"><lookat origin="0, 3, 3" target="0, 0.2, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="18"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.7, 0.7"/></bsdf></shape>
  <shape type="cylinder"><point name="p0" x="-1.2" y="0.5" z="0"/><point name="p1" x="1.2" y="0.5" z="0.1"/>
    <float name="radius" value="0.3"/>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="1.5"/><rotate x="1" angle="90"/><translate x="-0.3" y="3" z="-0.5"/></transform>
    <emitter type="area"><rgb name="radiance" value="3, 3, 3"/></emitter></shape>
</scene>)";
    // 32 replicas of `mnee` and `nee` at 1,024 spp: with caster_probability 0.75 the rod's
    // loose sphere (its box's) gives `mnee` a heavy tail, and 8 replicas at 64 spp read block 3
    // 1.9 % high at 4.7 of their standard errors, while 8 x 2,048 spp agree with `nee` at
    // 65,536 spp in every block (issue 26, fifteenth measurement).
    expect_mnee_matches_nee(rod, 1024, 64, "glass cylinder", "", 32);
}
