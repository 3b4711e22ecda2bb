// MNEE as an estimator on its own (Alg. 1) and its density (Alg. 2), at single shading points
// under a water droplet: unbiased against BSDF sampling, MIS weights that sum to one, lights
// without area.
#include <cmath>
#include <optional>

#include "bsdf/fresnel.h"
#include "integrators/mis.h"
#include "manifold/manifold_technique.h"
#include "manifold/mnee.h"
#include "manifold/seed_path.h"
#include "manifold/walk_counters.h"
#include "sampler/independent.h"
#include "stat/droplet_points.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

const char* kScene = R"(<scene version="3.0.0"><integrator type="mnee"/>
  <sensor type="perspective"><transform name="to_world"><lookat origin="0,3,3" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="4"/></transform></shape>
  <shape type="sphere"><point name="center" x="0" y="0.35" z="0"/><float name="radius" value="0.8"/>
    <bsdf type="dielectric"><float name="int_ior" value="1.33"/><float name="ext_ior" value="1"/></bsdf></shape>
  $light
</scene>)";

const char* kAreaLight =
    R"(<shape type="rectangle"><transform name="to_world"><scale value="1.5"/><rotate x="1" angle="90"/>
    <translate x="-0.8" y="3" z="-0.5"/></transform><emitter type="area"><rgb name="radiance" value="3, 3, 3"/></emitter></shape>)";

LoadedScene droplet(const std::string& light) {
    std::string s = kScene;
    s.replace(s.find("$light"), 6, light);
    return load_xml(s);
}

const BSDFContext kCtx{SampledWavelengths::single(550), TransportMode::Radiance};

// One connection of Alg. 1 from x_b through the straight seed to a light sample (chosen with
// probability pmf), where the seed refracts and the walk succeeds.
struct StraightConnection {
    LightSample ls;
    std::vector<ManifoldVertex> chain;
    MneeConnection c;
};
std::optional<StraightConnection> connect_straight(const Scene& scene, const MneeSettings& st,
                                                   const SurfaceInteraction& xb, const Light& light, double pmf,
                                                   Sampler& smp) {
    auto s = light.sample_li({xb.p, xb.n}, smp.next_2d(), SampledWavelengths::single(550));
    if (!s) return std::nullopt;
    StraightConnection out;
    out.ls = *s;
    if (trace_seed_path(scene, xb, s->p, 550, st, &out.chain) != SeedStatus::Refractive) return std::nullopt;
    out.c = mnee_connect(scene, st, xb, *xb.bsdf(), kCtx, MediumStack(), light, pmf,
                         light_point(scene, light, *s, xb.p), out.chain, smp);
    if (out.c.outcome != MneeOutcome::Success) return std::nullopt;
    return out;
}

// MNEE's value at receivers under the droplet for light `a` (a single sample: the light has no
// area, so MNEE is deterministic there) against the mean of MNEE samples for the area light
// `b` that converges to it; O(size) bias allowed plus 5 standard errors.
void expect_light_limit(const LoadedScene& a, const LoadedScene& b, std::initializer_list<double> xs) {
    const MneeSettings st;
    for (double x : xs) {
        double va = 0;
        Mean vb;
        for (int which = 0; which < 2; ++which) {
            const Scene& scene = which ? *b.scene : *a.scene;
            const Light& light = *scene.lights()[0];
            const SurfaceInteraction xb = droplet_receiver(scene, x, 0.05, 2);
            IndependentSampler smp(11);
            smp.start_pixel_sample(which, 0, 0);
            for (int n = 0; n < (which ? 4000 : 1); ++n) {
                double v = 0;
                if (auto s = light.sample_li({xb.p, xb.n}, smp.next_2d(), SampledWavelengths::single(550))) {
                    const LightPoint lp = light_point(scene, light, *s, xb.p);
                    std::vector<ManifoldVertex> chain;
                    if (trace_seed_path(scene, xb, lp.p, 550, st, &chain) == SeedStatus::Refractive) {
                        const MneeConnection c =
                            mnee_connect(scene, st, xb, *xb.bsdf(), kCtx, MediumStack(), light, 1.0, lp, chain, smp);
                        if (c.outcome == MneeOutcome::Success) v = c.value[0];
                    }
                }
                if (which)
                    vb.add(v);
                else
                    va = v;
            }
        }
        EXPECT_GT(va, 0.0) << "x = " << x;
        EXPECT_NEAR(va, vb.mean(), 5 * vb.stderr_() + 0.02 * va) << "x = " << x;
    }
}

}  // namespace

// Alg. 1 estimates the light arriving through the droplet exactly as BSDF sampling restricted
// to refraction-only paths that Alg. 2 attributes to MNEE (the rest are caustic folds, Fig. 7).
TEST(MneeEstimator, MatchesBsdfSamplingOfTheSamePaths) {
    LoadedScene ls = droplet(kAreaLight);
    const Scene& scene = *ls.scene;
    const Light& light = *scene.lights()[0];
    const MneeSettings st;
    for (double x : {0.1, -0.3, 0.45}) {
        const SurfaceInteraction xb = droplet_receiver(scene, x, 0.05, 2);
        IndependentSampler smp(7);
        smp.start_pixel_sample(int(x * 100), 0, 0);
        Mean mnee, bsdf;
        for (int n = 0; n < 40000; ++n) {
            double v = 0;
            if (auto s = light.sample_li({xb.p, xb.n}, smp.next_2d(), SampledWavelengths::single(550))) {
                std::vector<ManifoldVertex> chain;
                if (trace_seed_path(scene, xb, s->p, 550, st, &chain) == SeedStatus::Refractive) {
                    const MneeConnection c = mnee_connect(scene, st, xb, *xb.bsdf(), kCtx, MediumStack(), light, 1.0,
                                                          light_point(scene, light, *s, xb.p), chain, smp);
                    if (c.outcome == MneeOutcome::Success) v = c.value[0];
                }
            }
            mnee.add(v);
        }
        for (int n = 0; n < 200000; ++n) {
            // Diffuse sampling at x_b, then refractions only, until the light.
            const double v = refracted_light_sample(
                scene, xb, kCtx, smp, [&](const std::vector<SurfaceInteraction>& chain, const SurfaceInteraction& h) {
                    return !chain.empty() && mnee_pdf(scene, st, xb, *xb.bsdf(), chain.data(), int(chain.size()), light,
                                                      1.0, h.p, h.n, 550) > 0;
                });
            bsdf.add(v);
        }
        const double se = std::sqrt(sqr(mnee.stderr_()) + sqr(bsdf.stderr_()));
        EXPECT_GT(mnee.mean(), 0.1) << "x = " << x;
        EXPECT_NEAR(mnee.mean(), bsdf.mean(), 4.5 * se) << "x = " << x;
    }
}

// For paths produced by MNEE, Alg. 2 returns the density Alg. 1 used, and the BSDF-sampling
// density it reports equals one computed here independently (Walter et al.'s refraction
// Jacobian, Fresnel lobe probability): so the power-heuristic weights of the two techniques
// for the same path sum to one.
TEST(MneeMis, WeightsOfAllTechniquesSumToOne) {
    LoadedScene ls = droplet(kAreaLight);
    const Scene& scene = *ls.scene;
    const Light& light = *scene.lights()[0];
    const MneeSettings st;
    const SurfaceInteraction xb = droplet_receiver(scene, -0.2, 0.1, 2);
    IndependentSampler smp(3);
    smp.start_pixel_sample(0, 0, 0);
    int checked = 0;
    for (int n = 0; n < 400 && checked < 50; ++n) {
        const double pmf = 0.7;
        const auto found = connect_straight(scene, st, xb, light, pmf, smp);
        if (!found) continue;
        const LightSample* s = &found->ls;
        const std::vector<ManifoldVertex>& chain = found->chain;
        const MneeConnection& c = found->c;
        ASSERT_EQ(chain.size(), 1u);
        const SurfaceInteraction& v = chain[0].si;
        // Alg. 2 on the produced path.
        const double alg2 = mnee_pdf(scene, st, xb, *xb.bsdf(), &v, 1, light, pmf, s->p, s->n, 550);
        EXPECT_NEAR(alg2, c.pdf_mnee, 1e-6 * c.pdf_mnee);
        // BSDF sampling, independently: cosine lobe at x_b, then refraction chosen with
        // probability 1 - F and its delta rewritten in half-vector measure.
        const Vec3 o_b = normalize(v.p - xb.p), o_1 = normalize(s->p - v.p);
        const double cos_b = std::abs(dot(xb.n, o_b));
        double p = (cos_b / kPi) * std::abs(dot(v.ng, o_b)) / length_squared(v.p - xb.p);
        const double eta = 1.33;  // inside -> outside: the camera side is water
        const double F = fresnel_dielectric(dot(-o_b, v.n), eta).R;
        const double jac =
            sqr(eta * dot(-o_b, v.n) + 1.0 * dot(o_1, v.n)) / std::abs(dot(o_1, v.n));  // |do/dh| at h = n
        p *= (1 - F) / jac * std::abs(dot(s->n, o_1)) / length_squared(s->p - v.p);
        EXPECT_NEAR(c.pdf_bsdf, p, 1e-5 * p);
        const double w_mnee = power_heuristic(c.pdf_mnee, c.pdf_bsdf), w_bsdf = power_heuristic(p, alg2);
        EXPECT_NEAR(w_mnee + w_bsdf, 1.0, 1e-5);
        ++checked;
    }
    EXPECT_GE(checked, 20);
}

// solution_density_bound (mis_cutoff's bound, issue 26 point 5) is a function of the path alone,
// and for every path Alg. 1 finds it is the density Alg. 1 reports (Eq. 7 with Eq. 8), which
// Alg. 2 reproduces: so the cutoff's test reads the same on the solution's side and on BSDF
// sampling's side of the path, and bounds Alg. 2's density. A ball above the floor (k = 2),
// smooth and rough (there line 3's half-vector density enters).
TEST(MneeMis, SolutionDensityBoundIsTheDensityOfTheSolutionsFound) {
    for (
        const char* bsdf :
        {R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>)",
         R"(<bsdf type="roughdielectric"><float name="alpha" value="0.1"/><float name="int_ior" value="1.5"/></bsdf>)"}) {
        std::string xml = kScene;
        xml.replace(xml.find("$light"), 6, kAreaLight);
        xml.replace(xml.find(R"(<float name="radius" value="0.8"/>)"), 34, R"(<float name="radius" value="0.3"/>)");
        xml.replace(xml.find(R"(y="0.35")"), 8, R"(y="1.2")");
        const size_t a = xml.find(R"(<bsdf type="dielectric">)");
        xml.replace(a, xml.find("</bsdf>", a) + 7 - a, bsdf);
        LoadedScene ls = load_xml(xml);
        const Scene& scene = *ls.scene;
        const Light& light = *scene.lights()[0];
        const MneeSettings st;
        IndependentSampler smp(5);
        smp.start_pixel_sample(0, 0, 0);
        int checked = 0;
        for (double x : {-0.25, -0.1, 0.05}) {
            const SurfaceInteraction xb = droplet_receiver(scene, x, 0.1, 0.5);
            for (int n = 0; n < 400; ++n) {
                const double pmf = 0.6;
                const auto found = connect_straight(scene, st, xb, light, pmf, smp);
                if (!found) continue;
                const LightSample* s = &found->ls;
                const MneeConnection& c = found->c;
                ASSERT_EQ(found->chain.size(), 2u);
                const SurfaceInteraction path[2] = {found->chain[0].si, found->chain[1].si};
                const double bound =
                    solution_density_bound(scene, st, xb, *xb.bsdf(), path, 2, light, pmf, s->p, s->n, 550);
                EXPECT_NEAR(bound, c.pdf_mnee, 1e-5 * c.pdf_mnee) << bsdf;
                const double alg2 = mnee_pdf(scene, st, xb, *xb.bsdf(), path, 2, light, pmf, s->p, s->n, 550);
                EXPECT_LE(alg2, bound * (1 + 1e-6)) << bsdf;
                ++checked;
            }
        }
        EXPECT_GE(checked, 100) << bsdf;
    }
}

// A point light of intensity I is the limit of small spherical lights of radiance
// I / (pi r^2): MNEE must give the same caustic for both (no area: a virtual tangent plane).
TEST(MneeEstimator, PointLightIsTheLimitOfSmallSphereLights) {
    const char* point = R"(<emitter type="point"><point name="position" x="-0.6" y="3" z="-0.4"/>
        <rgb name="intensity" value="4, 4, 4"/></emitter>)";
    const double r = 0.01;
    const std::string sphere =
        std::string(
            R"(<shape type="sphere"><point name="center" x="-0.6" y="3" z="-0.4"/><float name="radius" value=")") +
        std::to_string(r) + R"("/><emitter type="area"><rgb name="radiance" value=")" +
        std::to_string(4 / (kPi * r * r)) + R"("/></emitter></shape>)";
    expect_light_limit(droplet(point), droplet(sphere), {0.1, -0.25});
}

// A directional light is the limit of a distant small sphere light with the same irradiance
// E = L pi r^2 / d^2 (MNEE puts it on a far sphere, light_point.h).
TEST(MneeEstimator, DirectionalLightIsTheLimitOfADistantSphereLight) {
    const Vec3 dir = normalize(Vec3(0.3, -1, 0.2));  // direction of travel of the light
    const double d = 200, r = 0.2, E = 2;
    const Vec3 c = dir * -d;
    const std::string directional = R"(<emitter type="directional"><vector name="direction" x=")" +
                                    std::to_string(dir.x) + R"(" y=")" + std::to_string(dir.y) + R"(" z=")" +
                                    std::to_string(dir.z) + R"("/><rgb name="irradiance" value=")" + std::to_string(E) +
                                    R"("/></emitter>)";
    const std::string sphere = R"(<shape type="sphere"><point name="center" x=")" + std::to_string(c.x) + R"(" y=")" +
                               std::to_string(c.y) + R"(" z=")" + std::to_string(c.z) +
                               R"("/><float name="radius" value=")" + std::to_string(r) +
                               R"("/><emitter type="area"><rgb name="radiance" value=")" +
                               std::to_string(E * d * d / (kPi * r * r)) + R"("/></emitter></shape>)";
    expect_light_limit(droplet(directional), droplet(sphere), {0.05, -0.2});
}

// max_geometry: off by default; a threshold t scales a connection whose focusing ratio r exceeds
// it by exactly t / r and leaves the others alone. r is the generalised geometry term over the
// free-space one, so near the droplet's axis (a gentle lens) it stays of order one.
TEST(MneeEstimator, MaxGeometryOffByDefaultAndClampsAboveThreshold) {
    const LoadedScene ls = droplet(R"(<emitter type="point"><point name="position" x="-0.6" y="3" z="-0.4"/>
        <rgb name="intensity" value="4, 4, 4"/></emitter>)");
    const Scene& scene = *ls.scene;
    const Light& light = *scene.lights()[0];
    EXPECT_EQ(MneeSettings().max_geometry, 0.0);
    for (double x : {0.1, -0.25}) {
        const SurfaceInteraction xb = droplet_receiver(scene, x, 0.05, 2);
        const auto connect = [&](double max_geometry) {
            MneeSettings st;
            st.max_geometry = max_geometry;
            IndependentSampler smp(3);
            smp.start_pixel_sample(0, 0, 0);
            const auto s = light.sample_li({xb.p, xb.n}, smp.next_2d(), SampledWavelengths::single(550));
            EXPECT_TRUE(s.has_value());
            const LightPoint lp = light_point(scene, light, *s, xb.p);
            std::vector<ManifoldVertex> chain;
            EXPECT_EQ(trace_seed_path(scene, xb, lp.p, 550, st, &chain), SeedStatus::Refractive);
            return mnee_connect(scene, st, xb, *xb.bsdf(), kCtx, MediumStack(), light, 1.0, lp, chain, smp);
        };
        const MneeConnection off = connect(0);
        ASSERT_EQ(off.outcome, MneeOutcome::Success) << "x = " << x;
        EXPECT_GT(off.focusing, 0.05) << "x = " << x;
        EXPECT_LT(off.focusing, 20.0) << "x = " << x;
        const MneeConnection above = connect(2 * off.focusing), clamped = connect(0.5 * off.focusing);
        EXPECT_EQ(above.value[0], off.value[0]);
        EXPECT_NEAR(clamped.value[0], 0.5 * off.value[0], 1e-12 * off.value[0]);
        EXPECT_EQ(clamped.pdf_mnee, off.pdf_mnee);  // densities, hence MIS weights, are untouched
    }
}

// ManifoldTechnique::connect is Alg. 1 whole: the light sample, the seed and the solutions are
// those of the pieces run by hand from the same sampler state; where nothing refracts it is NEE's
// sample (Kind::Direct); with q = 0 it never walks, and with q = 1/2 it walks for half of the
// refracting seeds (binomial, 5 standard deviations).
TEST(MneeConnect, IsAlgorithmOneWhole) {
    LoadedScene ls = droplet(kAreaLight);
    const Scene& scene = *ls.scene;
    const MneeSettings st;  // the paper's estimator: one solution, from the straight seed
    const ManifoldTechnique technique(scene, st);
    const SurfaceInteraction under = droplet_receiver(scene, 0.1, 0.05, 2);
    const SurfaceInteraction aside = droplet_receiver(scene, 2.5, 0.05, 2);  // the light in plain sight
    const auto query = [&](const SurfaceInteraction& xb, double q) {
        ManifoldQuery mq{&xb, xb.bsdf(), kCtx, MediumStack(), false};
        mq.connect_probability = q;
        return mq;
    };
    IndependentSampler smp(11), by_hand(11);
    int manifold = 0, solutions = 0;
    for (int n = 0; n < 300; ++n) {
        smp.start_pixel_sample(n, 0, 0);
        by_hand.start_pixel_sample(n, 0, 0);
        const ManifoldConnection c = technique.connect(query(under, 1.0), smp);
        // Line 1, line 2, then solve() from the same numbers.
        double pmf = 0;
        const Light* light = scene.light_sampler().sample(by_hand.next_1d(), &pmf);
        const auto s = light->sample_li({under.p, under.n}, by_hand.next_2d(), kCtx.wl);
        if (!s) {
            EXPECT_EQ(c.kind, ManifoldConnection::Kind::None);
            continue;
        }
        const LightPoint lp = light_point(scene, *light, *s, under.p);
        std::vector<ManifoldVertex> seed;
        if (trace_seed_path(scene, under, lp.p, 550, st, &seed) != SeedStatus::Refractive) continue;
        ASSERT_EQ(c.kind, ManifoldConnection::Kind::Manifold);
        EXPECT_EQ(c.light, light);
        EXPECT_EQ(c.q, 1.0);
        ManifoldQuery mq = query(under, 1.0);
        const SolutionSet set = technique.solve(mq, *light, pmf, lp, seed, by_hand);
        ASSERT_EQ(c.set.solutions.size(), set.solutions.size());
        for (size_t i = 0; i < set.solutions.size(); ++i) {
            EXPECT_EQ(c.set.solutions[i].value[0], set.solutions[i].value[0]);
            EXPECT_EQ(c.set.solutions[i].density, set.solutions[i].density);
        }
        ++manifold;
        solutions += int(set.solutions.size());
    }
    EXPECT_GT(manifold, 200);
    EXPECT_GT(solutions, 100);

    // In plain sight: NEE's sample, with or without walks allowed.
    for (double q : {1.0, 0.0}) {
        int direct = 0;
        for (int n = 0; n < 100; ++n) {
            smp.start_pixel_sample(n, 1, 0);
            const ManifoldConnection c = technique.connect(query(aside, q), smp);
            EXPECT_NE(c.kind, ManifoldConnection::Kind::Manifold);
            direct += c.kind == ManifoldConnection::Kind::Direct;
        }
        EXPECT_GT(direct, 90) << "q = " << q;
    }

    // q = 0 under the droplet: no walk, and the glass blocks NEE's shadow ray.
    const uint64_t walks_before = walk_counters::walks_started.this_thread();
    for (int n = 0; n < 200; ++n) {
        smp.start_pixel_sample(n, 2, 0);
        EXPECT_EQ(technique.connect(query(under, 0.0), smp).kind, ManifoldConnection::Kind::None);
    }
    EXPECT_EQ(walk_counters::walks_started.this_thread(), walks_before);

    // q = 1/2: half of the refracting seeds are walked.
    int walked = 0;
    const int n_half = 4000;
    for (int n = 0; n < n_half; ++n) {
        smp.start_pixel_sample(n, 3, 0);
        const ManifoldConnection c = technique.connect(query(under, 0.5), smp);
        if (c.kind == ManifoldConnection::Kind::Manifold) {
            EXPECT_EQ(c.q, 0.5);
            ++walked;
        }
    }
    EXPECT_NEAR(double(walked), 0.5 * n_half, 5 * std::sqrt(0.25 * n_half));
}
