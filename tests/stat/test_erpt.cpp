// `erpt` (Cline et al. 2005's energy redistribution driving `nee`) estimates the same image as
// `nee`. Chains carry energy across pixels, so pixels and blocks of one ERPT image are
// correlated; replicas with different seeds are independent, so Welch's t-test over replicas
// (replica_stats.h) is valid, per block and for the whole image.
#include <cmath>
#include <cstdio>
#include <string>

#include "core/props.h"
#include "core/spectrum.h"
#include "integrators/erpt/energy_redistribution.h"
#include "integrators/erpt/erpt.h"
#include "integrators/erpt/recording_sampler.h"
#include "integrators/pssmlt/path_sample.h"
#include "integrators/pssmlt/primary_sample_sampler.h"
#include "manifold/walk_counters.h"
#include "sampler/independent.h"
#include "stat/box_scene.h"
#include "stat/replica_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

constexpr int kBlock = 4;  // 4 x 4 blocks of 4 x 4 pixels on a 16 x 16 image
constexpr int kReplicas = 64;
constexpr int kSpp = 16;
constexpr int kNeeSpp = 64;

/// The box with `extra` parameters in its integrator and the rough glass sphere named "glass".
std::string box_xml(const std::string& extra) {
    std::string xml = kCornellBox;
    const std::string depth = R"(<integer name="max_depth" value="6"/>)";
    xml.replace(xml.find(depth), depth.size(), depth + extra);
    const std::string glass = R"(<shape type="sphere"><point name="center" x="0.45")";
    xml.replace(xml.find(glass), glass.size(), R"(<shape type="sphere" id="glass"><point name="center" x="0.45")");
    return xml;
}

/// Short chains and more of them than the default, so that a small test image has many
/// chains and every seed's energy travels: cost per pixel sample ~ 1 + 0.5 * 32 = 17 paths.
const std::string kTestChains = R"(<integer name="mutations" value="32"/>)"
                                R"(<float name="chains_per_sample" value="0.5"/>)"
                                R"(<integer name="bootstrap_samples" value="4096"/>)";

LoadedScene load_erpt(const std::string& extra = "") {
    return load_xml(box_xml(kTestChains + extra), {{"integrator", "erpt"}, {"res", "16"}});
}

RenderResult render_once(const LoadedScene& ls, uint64_t seed, int threads = 0, int spp = kSpp) {
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed;
    opt.progress = false;
    opt.threads = threads;
    opt.tile_size = 8;
    return render(*ls.scene, *ls.integrator, ls.film, opt);
}

const ErptIntegrator& erpt_of(const LoadedScene& ls) { return dynamic_cast<const ErptIntegrator&>(*ls.integrator); }

/// The tracer a render with `seed` uses (E_d and the bootstrap's mean depend on the seed only).
std::unique_ptr<ErptTracer> prepared(const LoadedScene& ls, uint64_t seed) {
    RenderOptions opt;
    opt.seed = seed;
    return erpt_of(ls).prepare_erpt(*ls.scene, ls.film, opt);
}

/// Replica statistics of `erpt` renders at kSpp over independent seeds.
ReplicaStats erpt_replica_stats(const LoadedScene& ls, uint64_t seed_base) {
    return replica_stats_of(ls, kBlock, seed_base, kReplicas, [&](uint64_t s) { return render_once(ls, s); });
}

}  // namespace

// A state set from outside is read back exactly, a proposal small-steps it within Kelemen's
// range, dimensions beyond it are fresh, and rejecting restores it.
TEST(PrimarySampleSampler, SetStateStartsAChainThere) {
    PrimarySampleSampler s(7, 1, 0.0);
    const std::vector<double> state = {0.1, 0.5, 0.999, 0.0, 0.25};
    s.set_state(state);
    for (double v : state) ASSERT_EQ(s.next_1d(), v);
    for (int it = 0; it < 100; ++it) {
        s.start_iteration();
        for (double v : state) {
            double d = std::abs(s.next_1d() - v);
            d = std::min(d, 1 - d);
            ASSERT_GE(d, 1.0 / 1024 * (1 - 1e-9));
            ASSERT_LE(d, 1.0 / 64 * (1 + 1e-9));
        }
        const double extra = s.next_1d();
        ASSERT_TRUE(extra >= 0 && extra < 1);
        s.reject();
        s.start_pixel_sample(0, 0, 0);
        for (double v : state) ASSERT_EQ(s.next_1d(), v);
    }
}

// The recorded seed vector is the seed's primary sample in evaluate()'s layout: replaying it
// through a PrimarySampleSampler gives the seed's own contribution (up to the rounding of the
// film position, which can move a ray across a silhouette in rare cases).
TEST(Erpt, RecordedSeedReplaysThroughEvaluate) {
    const LoadedScene ls = load_erpt();
    const auto inner = std::make_shared<PathTracer>(PathSettings{6, 5, false}, true);
    const Camera& camera = *ls.scene->camera();
    const int w = ls.film.out_width(), h = ls.film.out_height();
    IndependentSampler sampler(3);
    int lit = 0, matched = 0;
    for (int i = 0; i < 2000; ++i) {
        const int px = i % w, py = (i / w) % h;
        sampler.start_pixel_sample(px, py, uint64_t(i));
        const Vec2 jitter = sampler.next_2d();
        const Vec2 raster(px + jitter.x, py + jitter.y);
        const Vec2 u_lambda = sampler.next_2d();
        const SampledWavelengths wl = SampledWavelengths::sample_visible(u_lambda);
        const Vec2 o = ls.film.sample_origin(), e = ls.film.sample_extent();
        std::vector<double> state = {(raster.x - o.x) / e.x, (raster.y - o.y) / e.y, u_lambda.x, u_lambda.y};
        RecordingSampler rec(sampler, state);
        const SampledSpectrum L = inner->li(camera.generate_ray(raster, Vec2(0.5, 0.5)), *ls.scene, rec, wl);
        PrimarySampleSampler replay(1, 2, 0.0);
        replay.set_state(state);
        const PathSample p = evaluate(*ls.scene, camera, *inner, kSpectrumSamples, ls.film, replay);
        ASSERT_EQ(p.x, px);
        ASSERT_EQ(p.y, py);
        if (L.is_zero()) continue;
        ++lit;
        const double y = wl.to_xyz(L).y;
        matched += std::abs(p.target() - y) <= 1e-9 * y;
    }
    EXPECT_GT(lit, 1000);
    EXPECT_GE(matched, lit - lit / 100);
}

// Cline et al.'s invariant on an analytic target whose image is known exactly: seeds uniform
// over the unit square of film positions carry energy f / N, their chains run through
// redistribute_energy(), and the deposits binned on an 8 x 8 grid must estimate the integral
// of f over each cell. The target uses a third number only for x >= 0.5 (dimensions come and
// go, as with Russian roulette) and is zero on one row of cells, which chains may not enter.
// Replicas are independent; per cell a t-test against the exact value, Bonferroni-corrected at
// level 0.01. Power (measured by injecting bugs): an acceptance of (Y_p / Y_c)^0.5 fails 7 and
// 2 cells of the two tests below; dropping the current state's (1 - a) share fails 25 and 38.
namespace {

constexpr int kGrid = 8;
constexpr int kBand = 4;  // f = 0 on row 4: y in [0.5, 0.625)

// A square wave in w (contrast 19, mean 1) makes many proposals fall to a dark state, so the
// current state's (1 - a) share of each deposit matters; v has mean 1 too.
double f_analytic(double x, double y, double w, double v) {
    if (int(y * kGrid) == kBand) return 0;
    const double wave = w * 16 - std::floor(w * 16) < 0.5 ? 1.9 : 0.1;
    return (0.2 + x) * (1 + 3 * y * y) * wave * (0.5 + v);
}

PathSample evaluate_analytic(Sampler& s) {
    const Vec2 u = s.next_2d();
    const double w = s.next_1d();
    const double v = u.x >= 0.5 ? s.next_1d() : 0.5;
    PathSample p;
    p.x = std::min(kGrid - 1, int(u.x * kGrid));
    p.y = std::min(kGrid - 1, int(u.y * kGrid));
    const double f = f_analytic(u.x, u.y, w, v);
    p.xyz = Vec3(0.3 * f, f, 0);
    return p;
}

/// Exact integral of f over cell (cx, cy): separable, and the w and v factors have mean 1.
double cell_integral(int cx, int cy) {
    if (cy == kBand) return 0;
    const double x0 = double(cx) / kGrid, x1 = double(cx + 1) / kGrid, y0 = double(cy) / kGrid,
                 y1 = double(cy + 1) / kGrid;
    return (0.2 * (x1 - x0) + 0.5 * (x1 * x1 - x0 * x0)) * ((y1 - y0) + (y1 * y1 * y1 - y0 * y0 * y0));
}

/// Deposited luminance per cell over `seeds` seeds of one replica.
std::vector<double> redistribute_analytic(uint64_t replica, int seeds, int mutations, double chains_per_sample,
                                          int max_chains) {
    double mean_f = 0;  // the exact E[f], as a bootstrap would estimate it
    for (int cx = 0; cx < kGrid; ++cx)
        for (int cy = 0; cy < kGrid; ++cy) mean_f += cell_integral(cx, cy);
    const double deposition = mean_f / double(seeds) / (double(mutations) * chains_per_sample);
    std::vector<double> cells(kGrid * kGrid, 0.0);
    IndependentSampler sampler(replica);
    for (int i = 0; i < seeds; ++i) {
        sampler.start_pixel_sample(0, 0, uint64_t(i));
        std::vector<double> start;
        RecordingSampler recorder(sampler, start);
        PathSample seed = evaluate_analytic(recorder);
        seed.xyz = seed.xyz / double(seeds);
        if (!(seed.target() > 0)) continue;
        const ChainPlan plan = plan_chains(seed.target(), mutations, deposition, max_chains, sampler.next_1d());
        const uint64_t bits = uint64_t(sampler.next_1d() * 0x1p53);
        redistribute_energy(
            start, seed, plan, mutations, bits, 1.0 / 1024, 1.0 / 64,
            [&](PrimarySampleSampler& s) {
                PathSample p = evaluate_analytic(s);
                p.xyz = p.xyz / double(seeds);
                return p;
            },
            [&](const PathSample& p, const Vec3& xyz) {
                EXPECT_NEAR(xyz.x, 0.3 * xyz.y, 1e-12 * xyz.y);  // XYZ keeps its chromaticity
                cells[size_t(p.y * kGrid + p.x)] += xyz.y;
            });
    }
    return cells;
}

void expect_cells_match_target(int mutations, double chains_per_sample, int max_chains) {
    constexpr int kCellReplicas = 30, kSeeds = 2000;
    std::vector<std::vector<double>> per_cell(kGrid * kGrid);
    for (int r = 0; r < kCellReplicas; ++r) {
        const std::vector<double> c =
            redistribute_analytic(uint64_t(100 + r), kSeeds, mutations, chains_per_sample, max_chains);
        for (size_t i = 0; i < c.size(); ++i) per_cell[i].push_back(c[i]);
    }
    const double threshold = 0.01 / double(kGrid * (kGrid - 1));
    int failures = 0;
    for (int cy = 0; cy < kGrid; ++cy)
        for (int cx = 0; cx < kGrid; ++cx) {
            const Estimate est = estimate_of(per_cell[size_t(cy * kGrid + cx)]);
            const double exact = cell_integral(cx, cy);
            if (cy == kBand) {
                EXPECT_EQ(est.mean, 0.0) << "a chain entered the zero row at cell " << cx;
                continue;
            }
            const double p = student_t_two_sided_p(std::abs(est.mean - exact) / est.stderr_, kCellReplicas - 1);
            if (p < threshold && ++failures <= 5)
                ADD_FAILURE() << "cell (" << cx << ", " << cy << "): " << est.mean << " +- " << est.stderr_
                              << " vs exact " << exact << " (p = " << p << ")";
        }
    EXPECT_EQ(failures, 0);
}

}  // namespace

TEST(EnergyRedistribution, DepositsEstimateTheTarget) { expect_cells_match_target(256, 0.25, 64); }

// With max_chains = 1 most seeds are capped and deposit e through a larger quantum instead.
TEST(EnergyRedistribution, CappedChainsStillDepositTheSeedEnergy) {
    expect_cells_match_target(64, 1.0, 1);
    const ChainPlan capped = plan_chains(10.0, 64, 0.01, 2, 0.5);
    EXPECT_EQ(capped.chains, 2);
    EXPECT_DOUBLE_EQ(capped.chains * 64 * capped.quantum, 10.0);
    const ChainPlan plain = plan_chains(1.0, 10, 0.04, 64, 0.3);  // floor(0.3 + 2.5)
    EXPECT_EQ(plain.chains, 2);
    EXPECT_EQ(plain.quantum, 0.04);
}

// (a) Agreement with `nee`: Welch per 4x4 block and for the whole image, Bonferroni-corrected
// at family-wise level 0.01.
TEST(Erpt, AgreesWithNeeInABox) {
    const LoadedScene erpt = load_erpt();
    const LoadedScene nee = load_xml(kCornellBox, {{"integrator", "nee"}, {"res", "16"}});
    const ReplicaStats a = erpt_replica_stats(erpt, 1000);
    // The chains ran: E_d came from a bootstrap that saw light.
    EXPECT_GT(prepared(erpt, 1000)->deposition_energy(), 0);
    expect_replicas_agree(a, replica_stats(nee, kNeeSpp, kBlock, 2000, kReplicas), "erpt vs nee");
}

// (b) The same with redistribution restricted to paths that touch the glass sphere: those
// chains stay among such paths, everything else is plain `nee`.
TEST(Erpt, AgreesWithNeeWhenRestrictedToAShape) {
    const LoadedScene erpt = load_erpt(R"(<string name="shapes" value="glass"/>)");
    const LoadedScene nee = load_xml(kCornellBox, {{"integrator", "nee"}, {"res", "16"}});
    const ReplicaStats a = erpt_replica_stats(erpt, 3000);
    // Some but not all light reaches the camera through paths touching the sphere.
    const auto tracer = prepared(erpt, 3000);
    EXPECT_GT(tracer->deposition_energy(), 0);
    const LoadedScene all = load_erpt();
    EXPECT_LT(tracer->mean_eligible_energy(), 0.5 * prepared(all, 1000)->mean_eligible_energy());
    expect_replicas_agree(a, replica_stats(nee, kNeeSpp, kBlock, 4000, kReplicas), "erpt(shapes=glass) vs nee");
}

// Long restricted chains travel far from their seeds: a chain that started among paths touching
// the glass must stay among them (a proposal outside the set has target 0), or energy the image
// already holds as plain `nee` would be deposited twice. 4096 mutations at 0.005 chains per
// sample cost about as much as the short chains above.
TEST(Erpt, LongRestrictedChainsAgreeWithNee) {
    const LoadedScene erpt = load_xml(box_xml(R"(<integer name="mutations" value="4096"/>)"
                                              R"(<float name="chains_per_sample" value="0.005"/>)"
                                              R"(<integer name="bootstrap_samples" value="4096"/>)"
                                              R"(<string name="shapes" value="glass"/>)"),
                                      {{"integrator", "erpt"}, {"res", "16"}});
    const LoadedScene nee = load_xml(kCornellBox, {{"integrator", "nee"}, {"res", "16"}});
    expect_replicas_agree(erpt_replica_stats(erpt, 5000), replica_stats(nee, kNeeSpp, kBlock, 6000, kReplicas),
                          "erpt(shapes=glass, 4096 mutations) vs nee");
}

// Sensitivity: the comparison must be able to fail. ERPT of a box whose light is 3% brighter
// must be told apart from `nee` of the original box.
TEST(Erpt, DetectsALightThreePercentBrighter) {
    const LoadedScene erpt =
        load_xml(box_xml(kTestChains), {{"integrator", "erpt"}, {"res", "16"}, {"radiance", "6.18"}});
    const LoadedScene nee = load_xml(kCornellBox, {{"integrator", "nee"}, {"res", "16"}});
    const ReplicaStats a = erpt_replica_stats(erpt, 5000);
    const ReplicaStats b = replica_stats(nee, kNeeSpp, kBlock, 6000, kReplicas);
    std::printf("brighter erpt %.5f +- %.5f vs nee %.5f +- %.5f\n", a.image.mean, a.image.stderr_, b.image.mean,
                b.image.stderr_);
    EXPECT_GT(disagreements(a, b, 0.01, false), 0);
}

// (c) The image is a pure function of the seed, whatever the thread count; other seeds differ.
TEST(Erpt, DeterministicForASeed) {
    const LoadedScene ls = load_erpt(R"(<string name="shapes" value="glass"/>)");
    const Film a = render_once(ls, 5, 1, 2).film, b = render_once(ls, 5, 2, 2).film, c = render_once(ls, 6, 2, 2).film;
    bool differs = false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const Vec3 va = a.xyz(x, y), vb = b.xyz(x, y);
            ASSERT_EQ(va.x, vb.x);
            ASSERT_EQ(va.y, vb.y);
            ASSERT_EQ(va.z, vb.z);
            differs |= va.y != c.xyz(x, y).y;
        }
    EXPECT_TRUE(differs);
}

// `sampler=mnee` drives MNEE (its walks run) and gives a finite, non-black image.
TEST(Erpt, MneeSamplerRuns) {
    const LoadedScene ls = load_erpt(R"(<string name="sampler" value="mnee"/>)");
    const RenderResult r = render_once(ls, 9, 0, 1);
    EXPECT_GT(r.counters[walk_counters::walks_started], 0u);
    expect_finite_and_lit(r.film);
}

// (d) Bad settings are scene errors that name the problem.
TEST(Erpt, BadSettingsAreSceneErrors) {
    const auto load_error = [](const std::string& extra) -> std::string {
        try {
            load_erpt(extra);
        } catch (const SceneError& e) {
            return e.what();
        }
        return "";
    };
    const auto expect_error = [&](const std::string& extra, const std::string& names) {
        EXPECT_NE(load_error(extra).find(names), std::string::npos) << extra << " gave: " << load_error(extra);
    };
    expect_error(R"(<integer name="mutations" value="0"/>)", "mutations");
    expect_error(R"(<float name="chains_per_sample" value="0"/>)", "chains_per_sample");
    expect_error(R"(<float name="deposition_energy" value="-1"/>)", "deposition_energy");
    expect_error(R"(<integer name="bootstrap_samples" value="0"/>)", "bootstrap_samples");
    expect_error(R"(<integer name="max_chains" value="0"/>)", "max_chains");
    expect_error(R"(<string name="sampler" value="bdpt"/>)", "sampler");
    expect_error(R"(<string name="shapes" value="glass,,"/>)", "shapes");

    // Shape ids are resolved against the scene when rendering starts.
    const LoadedScene ls = load_erpt(R"(<string name="shapes" value="glass, teapot"/>)");
    try {
        render_once(ls, 1, 0, 1);
        ADD_FAILURE() << "an unknown shape id rendered";
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("unknown shape id 'teapot'"), std::string::npos) << what;
        EXPECT_NE(what.find("glass"), std::string::npos) << what;  // lists the ids that exist
    }
}
