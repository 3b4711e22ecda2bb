// `pssmlt` (Kelemen PSSMLT driving `nee`) estimates the same image as `nee`. Replicas with
// different seeds are independent, so Welch's t-test over replicas is valid even though the
// noise within one MLT image is correlated between pixels; coarse blocks keep each block's
// estimate close to normal.
#include <cmath>
#include <cstdio>
#include <string>

#include "integrators/pssmlt/primary_sample_sampler.h"
#include "integrators/pssmlt/pssmlt.h"
#include "manifold/walk_counters.h"
#include "sampler/independent.h"
#include "stat/box_scene.h"
#include "stat/replica_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

constexpr int kMutationsPerPixel = 256;
constexpr int kBlock = 4;  // 4 x 4 blocks of 4 x 4 pixels
constexpr int kReplicas = 20;

PssmltSettings test_settings(const LoadedScene& ls, int chains = 8) {
    PssmltSettings s = dynamic_cast<const PssmltIntegrator&>(*ls.integrator).settings();
    s.mutations_per_pixel = kMutationsPerPixel;
    s.bootstrap_samples = 65536;
    s.chains = chains;
    return s;
}

RenderResult render_once(const LoadedScene& ls, uint64_t seed, int threads = 0, int chains = 8) {
    RenderOptions opt;
    opt.seed = seed;
    opt.progress = false;
    opt.threads = threads;
    return render_pssmlt(*ls.scene, test_settings(ls, chains), kSpectrumSamples, ls.film, opt);
}

/// Replica statistics of render_pssmlt over independent seeds.
ReplicaStats pssmlt_replica_stats(const LoadedScene& ls, uint64_t seed_base) {
    return replica_stats_of(ls, kBlock, seed_base, kReplicas, [&](uint64_t seed) { return render_once(ls, seed); });
}

}  // namespace

// A rejected proposal restores the state bit for bit, including dimensions that the proposal
// added, and an accepted one is kept.
TEST(PrimarySampleSampler, RejectRestoresAndAcceptKeeps) {
    PrimarySampleSampler s(1, 2, 0.3);
    std::vector<double> state;
    for (int i = 0; i < 5; ++i) state.push_back(s.next_1d());
    s.accept();
    for (int it = 0; it < 200; ++it) {
        s.start_iteration();
        std::vector<double> proposal;
        for (int i = 0; i < 5 + it % 3; ++i) proposal.push_back(s.next_1d());
        for (double u : proposal) ASSERT_TRUE(u >= 0 && u < 1);
        if (it % 2) {
            s.accept();
            state.assign(proposal.begin(), proposal.begin() + 5);
        } else {
            s.reject();
        }
        // Reading the state again (a dimension-counter restart, no iteration) must give it back.
        s.start_pixel_sample(0, 0, 0);
        for (int i = 0; i < 5; ++i) ASSERT_EQ(s.next_1d(), state[size_t(i)]) << "iteration " << it;
    }
}

// Small steps move each coordinate by a wrapped distance in [s1, s2]; large steps anywhere.
TEST(PrimarySampleSampler, SmallStepsStayWithinKelemenRange) {
    PrimarySampleSampler s(3, 4, 0.0);
    double x = s.next_1d();
    s.accept();
    for (int it = 0; it < 1000; ++it) {
        s.start_iteration();
        const double y = s.next_1d();
        double d = std::abs(y - x);
        d = std::min(d, 1 - d);
        ASSERT_GE(d, 1.0 / 1024 * (1 - 1e-9));
        ASSERT_LE(d, 1.0 / 64 * (1 + 1e-9));
        s.accept();
        x = y;
    }
}

// The image is a pure function of the seed for a fixed number of chains, whatever the thread
// count, and different seeds give different images.
TEST(Pssmlt, DeterministicForASeed) {
    LoadedScene ls = load_xml(kCornellBox, {{"integrator", "pssmlt"}, {"res", "16"}});
    const Film a = render_once(ls, 5, 1, 4).film, b = render_once(ls, 5, 2, 4).film, c = render_once(ls, 6, 2, 4).film;
    bool differs = false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            ASSERT_EQ(a.xyz(x, y).y, b.xyz(x, y).y);
            differs |= a.xyz(x, y).y != c.xyz(x, y).y;
        }
    EXPECT_TRUE(differs);
}

// Issue 12: with the default chains = 0 the chain count came from the thread count, so one
// seed gave different images at 1 and 2 threads. Now it is fixed (64 chains, run in batches
// of `threads`); 3 threads leaves a short last batch.
TEST(Pssmlt, DefaultChainsIndependentOfThreads) {
    LoadedScene ls = load_xml(kCornellBox, {{"integrator", "pssmlt"}, {"res", "16"}});
    const Film a = render_once(ls, 5, 1, 0).film, b = render_once(ls, 5, 2, 0).film, c = render_once(ls, 5, 3, 0).film;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            ASSERT_EQ(a.xyz(x, y).y, b.xyz(x, y).y) << x << "," << y;
            ASSERT_EQ(a.xyz(x, y).y, c.xyz(x, y).y) << x << "," << y;
        }
}

// Agreement with `nee`: Welch per 4x4 block and for the whole image, Bonferroni-corrected at
// family-wise level 0.01 (replica_stats.h). Without Kelemen's weights the whole-image mean of
// a PSSMLT render is its bootstrap estimate b (every mutation splats total weight 1), so the
// blocks are what test the chains. Power (measured by injecting bugs): a Metropolis target of Y^0.97 instead of Y
// fails two blocks, Y^0.9 fails most of them; block standard errors are ~2% (pssmlt).
TEST(Pssmlt, AgreesWithNeeInABox) {
    LoadedScene mlt = load_xml(kCornellBox, {{"integrator", "pssmlt"}, {"res", "16"}});
    LoadedScene nee = load_xml(kCornellBox, {{"integrator", "nee"}, {"res", "16"}});
    expect_replicas_agree(pssmlt_replica_stats(mlt, 1000), replica_stats(nee, 256, kBlock, 2000, kReplicas),
                          "pssmlt(nee) vs nee");
}

// The plain expected-value estimator (kelemen_weights=false) converges to the same image.
TEST(Pssmlt, AgreesWithNeeWithoutKelemenWeights) {
    std::string xml = kCornellBox;
    const std::string depth = R"(<integer name="max_depth" value="6"/>)";
    xml.replace(xml.find(depth), depth.size(),
                std::string(depth) + R"(<boolean name="kelemen_weights" value="false"/>)");
    LoadedScene mlt = load_xml(xml, {{"integrator", "pssmlt"}, {"res", "16"}});
    ASSERT_FALSE(dynamic_cast<const PssmltIntegrator&>(*mlt.integrator).settings().kelemen_weights);
    LoadedScene nee = load_xml(kCornellBox, {{"integrator", "nee"}, {"res", "16"}});
    expect_replicas_agree(pssmlt_replica_stats(mlt, 5000), replica_stats(nee, 256, kBlock, 6000, kReplicas),
                          "pssmlt(nee), plain weights, vs nee");
}

// Sensitivity: the comparison above must be able to fail. PSSMLT of a box whose light is 3%
// brighter must be told apart from `nee` of the original box.
TEST(Pssmlt, DetectsALightThreePercentBrighter) {
    LoadedScene mlt = load_xml(kCornellBox, {{"integrator", "pssmlt"}, {"radiance", "6.18"}, {"res", "16"}});
    LoadedScene nee = load_xml(kCornellBox, {{"integrator", "nee"}, {"res", "16"}});
    const ReplicaStats a = pssmlt_replica_stats(mlt, 3000);
    const ReplicaStats b = replica_stats(nee, 256, kBlock, 4000, kReplicas);
    std::printf("brighter pssmlt %.5f +- %.5f vs nee %.5f +- %.5f\n", a.image.mean, a.image.stderr_, b.image.mean,
                b.image.stderr_);
    EXPECT_GT(disagreements(a, b, 0.01, false), 0);
}

// `sampler=mnee` builds MNEE as the inner estimator (its manifold walks run) and gives a
// finite image; an unknown sampler is a scene error.
TEST(Pssmlt, MneeSamplerRunsAndUnknownSamplerIsRejected) {
    const std::string depth = R"(<integer name="max_depth" value="6"/>)";
    std::string xml = kCornellBox;
    xml.replace(xml.find(depth), depth.size(), depth + R"(<string name="sampler" value="mnee"/>)");
    LoadedScene ls = load_xml(xml, {{"integrator", "pssmlt"}, {"res", "16"}});
    const auto& integ = dynamic_cast<const PssmltIntegrator&>(*ls.integrator);
    EXPECT_EQ(integ.settings().sampler, "mnee");
    PssmltSettings s = integ.settings();
    s.mutations_per_pixel = 16;
    s.bootstrap_samples = 4096;
    s.chains = 2;
    RenderOptions opt;
    opt.progress = false;
    const RenderResult r = render_pssmlt(*ls.scene, s, kSpectrumSamples, ls.film, opt);
    EXPECT_GT(r.counters[walk_counters::walks_started], 0u);
    expect_finite_and_lit(r.film);

    std::string bad = kCornellBox;
    bad.replace(bad.find(depth), depth.size(), depth + R"(<string name="sampler" value="bdpt"/>)");
    EXPECT_ANY_THROW(load_xml(bad, {{"integrator", "pssmlt"}, {"res", "16"}}));
}
