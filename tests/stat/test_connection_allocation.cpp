// MNEE's learned connect probability (integrators/mnee/connection_allocation.h, issue 26): the
// pilot's second moments are those of the estimator at every candidate q, each region takes the
// q of least variance x work, the choice is a crop's as the full film's, and `mnee` with the
// learned allocation stays unbiased (agreement with nee and bdpt per pixel block, with the power
// to see a 3 % error in the light).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <random>
#include <string>

#include <unistd.h>

#include "integrators/mnee/connection_allocation.h"
#include "manifold/walk_counters.h"
#include "stat/droplet_scene.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::test;

namespace {

// A one-dimensional path space [0, 1] with f(x) = x^2 + 0.05 and two techniques: "MNEE", made
// with probability q, draws x with density p_s = 2x, finds it with probability `find` and then
// counts it N times (N geometric with mean 1 / find, as the 1 / p estimate of the surface
// trials: E[N 1{found}] = 1), and weighs it in MIS by the density c p_s (c = surface_weight);
// "BSDF" draws x with density 1. Under the power heuristic each technique's share of the
// second moment is the integral of its weighted contribution squared over its draws:
// MNEE's find E[N^2 | found] w_m^2 f^2 / (q p_s), BSDF's w_b^2 f^2 (Veach's estimator, one
// sample of each).
struct Toy {
    double c, find;
};
double f_toy(double x) { return x * x + 0.05; }
double second_moment(const Toy& t, double q) {
    const int n = 200000;
    const double n2 = (2 - t.find) / (t.find * t.find);  // E[N^2 | found]
    double s = 0;
    for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) / n, p_s = 2 * x, a = q * t.c * p_s, sum = a * a + 1;
        if (q > 0) s += t.find * n2 * sqr(a * a / sum) * sqr(f_toy(x)) / (q * p_s);
        s += sqr(1 / sum) * sqr(f_toy(x));
    }
    return s / n;
}

}  // namespace

// The pilot at q = 1/2 records, from its own samples, the second moment the estimator has at
// every other q: the mean of what PilotSample adds agrees with the integral within its error;
// with MNEE's density weighed apart in MIS (c < 1) and its paths counted N times too, so that
// the 1 / p estimate's noise is judged, and BSDF sampling's share where c makes it large is
// judged from MNEE's frequent draws (each counted N times, its mean).
TEST(ConnectionAllocation, PilotSecondMomentsMatchTheirIntegrals) {
    for (const Toy toy : {Toy{1.0, 1.0}, Toy{0.25, 0.6}}) {
        const double q_pilot = 0.5;
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> u(0, 1);
        const int n = 400000;
        std::array<double, kCandidateCount> sum{}, sum2{};
        for (int i = 0; i < n; ++i) {
            PilotSample s;
            if (u(rng) < q_pilot && u(rng) < toy.find) {  // the connection is made and finds x
                const double x = std::sqrt(u(rng));
                double count = 1;
                while (!(u(rng) < toy.find)) ++count;
                s.add_connection(count * f_toy(x) / (2 * x), count, toy.c * 2 * x, toy.c, 1.0, q_pilot);
            }
            const double y = u(rng);
            s.add_other(f_toy(y), 1.0, toy.c * 2 * y, toy.c, 1.0, q_pilot);
            for (int j = 0; j < kCandidateCount; ++j) {
                sum[size_t(j)] += s.m2[size_t(j)];
                sum2[size_t(j)] += sqr(s.m2[size_t(j)]);
            }
        }
        // q = 0 included: BSDF sampling alone, int f^2 / p_b.
        for (int j = 0; j < kCandidateCount; ++j) {
            const double q = kConnectCandidates[size_t(j)];
            const double mean = sum[size_t(j)] / n;
            const double se = std::sqrt((sum2[size_t(j)] / n - mean * mean) / n);
            EXPECT_NEAR(mean, second_moment(toy, q), 4 * se + 1e-9) << "q = " << q << ", c = " << toy.c;
        }
    }
}

// Paths no candidate gives to MNEE (its straight walk fails beside them, so the trials do not
// run and density() gives 0) are BSDF sampling's under every q; the pilot's probes find them
// anyway (draws of density p_s = 2x, found with probability 0.6, counted N times, not counted in
// the image) and judge BSDF sampling's second moment there, int f^2 / p_b, together with BSDF
// sampling's own hits, whose weighted contributions leave the pilot's realized second moment.
TEST(ConnectionAllocation, ProbesJudgeBsdfSamplingWhereTheStraightWalkFails) {
    const double q_pilot = 0.5, find = 0.6;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    const int n = 400000;
    double sum = 0, sum2 = 0, realized = 0;
    std::array<double, kCandidateCount> fw_sum{}, fw_sum2{};
    for (int i = 0; i < n; ++i) {
        PilotSample s;
        if (u(rng) < q_pilot && u(rng) < find) {
            const double x = std::sqrt(u(rng));
            double count = 1;
            while (!(u(rng) < find)) ++count;
            s.add_probe(count * f_toy(x) / (2 * x), count, 2 * x, 1.0, q_pilot);
        }
        const double y = u(rng);
        s.add_probe_other(f_toy(y), 1.0, 2 * y, 1.0, q_pilot);
        for (int j = 0; j < kCandidateCount; ++j) {
            fw_sum[size_t(j)] += s.m2_failed_walk[size_t(j)];
            fw_sum2[size_t(j)] += sqr(s.m2_failed_walk[size_t(j)]);
        }
        for (int j = 1; j < kCandidateCount; ++j) ASSERT_EQ(s.m2[size_t(j)], s.m2[0]);
        for (int j = 0; j < kCandidateCount; ++j) ASSERT_EQ(s.m2_no_trials[size_t(j)], s.m2[0]);
        sum += s.m2[0];
        sum2 += sqr(s.m2[0]);
        realized += s.m2_pilot - sqr(f_toy(y));
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, second_moment(Toy{1.0, 1.0}, 0.0), 4 * se);
    EXPECT_EQ(realized, 0.0);  // a BSDF hit at MNEE density 0 has weight 1; a probe's find is not counted
    // The third kind (the trials beside failed walks too, weighed 1) gives those paths to MNEE at
    // density q p_s: the same probes judge its second moment at every q.
    for (int j = 0; j < kCandidateCount; ++j) {
        const double q = kConnectCandidates[size_t(j)];
        const double m = fw_sum[size_t(j)] / n, e = std::sqrt((fw_sum2[size_t(j)] / n - m * m) / n);
        EXPECT_NEAR(m, second_moment(Toy{1.0, find}, q), 4 * e + 1e-9) << "q = " << q;
    }
}

namespace {

// n pilot samples (q_pilot = 1) of pixel (x, y) on a path space with f = 1: each makes one MNEE
// connection (p_m = 1, value 1) and BSDF sampling finds the path with density p_other, in
// expectation: every 1 / p_other-th sample (counted by `clock`) with value 1 / p_other. The
// samples' values alternate 0 and 2 (variance from elsewhere in the pixel). `seed_work`: the work
// of tracing the connection's seed beyond the shadow ray a sample makes without it.
void feed(ConnectionAllocation& a, int x, int y, int n, double p_other, bool only_mnee, double work_connect, int& clock,
          double seed_work = 0) {
    const int every = std::max(1, int(std::lround(1 / p_other)));
    for (int i = 0; i < n; ++i) {
        PilotSample s;
        s.add_connection(1.0, 1.0, 1.0, 1.0, only_mnee ? 0.0 : p_other, 1.0);
        if (!only_mnee && clock++ % every == 0) s.add_other(1.0 / p_other, p_other, 1.0, 1.0, p_other, 1.0);
        s.work_connect = work_connect;
        s.work_seed = seed_work;
        a.add(x, y, s, 2.0 * (i % 2), work_connect + seed_work + 2.0);
    }
}

}  // namespace

// Where BSDF sampling hardly finds the paths (p_other << p_m) the walks pay whatever they cost;
// where it finds them as often as MNEE, expensive walks do not, and the region takes q = 0,
// unless the pilot saw light that only MNEE produces.
TEST(ConnectionAllocation, RegionsChooseTheLeastVarianceTimesWork) {
    ConnectionAllocation a(48, 16, 0, 0, 16, 1.0);
    int clock = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            feed(a, x, y, 4, 1e-3, false, 20, clock);                 // a small light behind glass
            feed(a, x + 16, y, 4, 1.0, false, 20, clock);             // a magnified light
            feed(a, x + 32, y, 4, 1.0, x == 3 && y == 5, 20, clock);  // ... one path only MNEE's
        }
    EXPECT_TRUE(a.learning());
    a.fit();
    EXPECT_FALSE(a.learning());
    // Variance 1 / (q + 10^-3) plus 0.83 from elsewhere, work 2 + 20 q: the optimum is q = 1/2.
    EXPECT_EQ(a.q(5, 5), 0.5);
    EXPECT_EQ(a.q(20, 5), 0.0);
    EXPECT_GT(a.q(40, 5), 0.0);
    const auto h = a.histogram();
    EXPECT_EQ(h[0], 1u);
}

// A connection's seed is traced only when the connection is made (ManifoldTechnique::connect
// draws the coin first), so its work scales with q like the walks'. With a seed 10 times as
// dear as the walks (work 2 + 220 q against variance about 1 / q + 0.83) the region takes
// q = 1/8. Charged to every sample at any q > 0 (as before the coin came first), or at every q
// alike, the seed made small q look dear and the region took 1.
TEST(ConnectionAllocation, SeedWorkScalesWithQ) {
    ConnectionAllocation a(16, 16, 0, 0, 16, 1.0);
    int clock = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) feed(a, x, y, 4, 1e-3, false, 20, clock, 200);
    a.fit();
    EXPECT_EQ(a.q(5, 5), 0.125);
}

// One pilot firefly in a region must not decide its q. Every pixel of the region sees light
// only MNEE finds well (p_other = 10^-3: the walks pay, q = 1 is best), and one pixel also
// draws one sample of 10^6 from elsewhere (a BSDF hit on a small light). Summed absolutely,
// that pixel's variance made every candidate's alike and the region took the cheapest q: 0
// here, 1/64 where the pilot saw light only MNEE produces (the pool's square blocks of speckle,
// issue 26). Counted as a pixel 10 times the region's median, it leaves the region walking (1/2
// or 1); the region without it takes 1, and the image's scale does not change the choice.
TEST(ConnectionAllocation, OneFireflyDoesNotDecideARegion) {
    for (double scale : {1.0, 1e-4, 1e4}) {
        ConnectionAllocation a(32, 16, 0, 0, 16, 1.0);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 32; ++x)
                for (int i = 0; i < 4; ++i) {
                    PilotSample s;
                    s.add_connection(scale, 1.0, 1.0, 1.0, 1e-3, 1.0);
                    s.work_connect = 2.0;
                    const bool firefly = x == 3 && y == 5 && i == 2;
                    a.add(x, y, s, firefly ? 1e6 * scale : scale * (1.0 + 0.5 * (i % 2)), s.work_connect + 1.0);
                }
        a.fit();
        EXPECT_GE(a.q(3, 5), 0.5) << "the region with the firefly, scale " << scale;
        EXPECT_EQ(a.q(20, 5), 1.0) << "the region without, scale " << scale;
    }
}

namespace {

// n pilot samples (q_pilot = 1) of pixel (x, y) whose connections walk the straight seed (a
// path BSDF sampling hardly finds, p_m = 1, p_other = 10^-3: the walks pay) and run surface trials of work
// `trial_work`, which find, when `p_surface` > 0 (or `only_trials`), a second path of value 1
// that BSDF sampling finds with density p_surface (0 with only_trials).
void feed_trials(ConnectionAllocation& a, int x, int y, int n, double p_surface, bool only_trials, double trial_work) {
    for (int i = 0; i < n; ++i) {
        PilotSample s;
        s.add_connection(1.0, 1.0, 1.0, 1.0, 1e-3, 1.0);
        if (p_surface > 0 || only_trials)
            s.add_connection(1.0, 1.0, 1.0, 1.0, only_trials ? 0.0 : p_surface, 1.0, /*surface=*/true);
        s.work_connect = 1.0 + trial_work;
        s.work_trials = trial_work;
        a.add(x, y, s, 1.0 + 0.5 * (i % 2), s.work_connect + 1.0);
    }
}

}  // namespace

// The surface trials run where their paths would otherwise be BSDF sampling's rare finds, and
// not where they find nothing the straight seed misses (a height field); never where the pilot
// saw light only they produce. Without the choice every region runs them.
TEST(ConnectionAllocation, RegionsRunSurfaceTrialsWhereTheyPay) {
    for (bool choose : {true, false}) {
        ConnectionAllocation a(48, 16, 0, 0, 16, 1.0, choose ? TrialAllocation::Learned : TrialAllocation::Always);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                feed_trials(a, x, y, 4, 0.0, false, 20);                  // trials find nothing
                feed_trials(a, x + 16, y, 4, 1e-3, false, 20);            // a post-fold path
                feed_trials(a, x + 32, y, 4, 0.0, x == 3 && y == 5, 20);  // ... one only theirs
            }
        a.fit();
        EXPECT_GT(a.q(5, 5), 0.0);
        EXPECT_EQ(a.surface_trials(5, 5), !choose) << "choose " << choose;
        EXPECT_TRUE(a.surface_trials(20, 5));
        EXPECT_TRUE(a.surface_trials(40, 5));
        EXPECT_EQ(a.regions_without_trials(), choose ? 1u : 0u);
    }
    // trial_allocation=never: no region runs them, whatever the pilot saw.
    ConnectionAllocation never(16, 16, 0, 0, 16, 1.0, TrialAllocation::Never);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) feed_trials(never, x, y, 4, 1e-3, false, 20);
    never.fit();
    EXPECT_FALSE(never.surface_trials(5, 5));
}

namespace {
// n pilot samples (q_pilot = 1) of pixel (x, y) with one straight connection (p_m = 1, BSDF
// sampling's p_other 1e-3) and, beside a failed straight walk, a path the probes find (p_s = 1,
// work `probe_work`) that BSDF sampling finds with density p_fail.
void feed_probes(ConnectionAllocation& a, int x, int y, int n, double p_fail, double probe_work) {
    for (int i = 0; i < n; ++i) {
        PilotSample s;
        s.add_connection(1.0, 1.0, 1.0, 1.0, 1e-3, 1.0);
        s.add_probe(1.0, 1.0, 1.0, p_fail, 1.0);
        s.work_connect = 1.0;
        s.work_probe = probe_work;
        a.add(x, y, s, 1.0 + 0.5 * (i % 2), 2.0 + probe_work);
    }
}
}  // namespace

// With the third kind allowed, a region runs the trials beside failed straight walks too where
// BSDF sampling hardly finds what they find and they cost little, and not where it finds those
// paths as often or they cost far more; never without the choice.
TEST(ConnectionAllocation, RegionsRunTrialsBesideFailedWalksWhereTheyPay) {
    for (bool allowed : {true, false}) {
        ConnectionAllocation a(48, 16, 0, 0, 16, 1.0, TrialAllocation::Learned, WorkPrice::Region, allowed);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                feed_probes(a, x, y, 4, 1e-3, 1.0);       // rare for BSDF sampling, cheap trials
                feed_probes(a, x + 16, y, 4, 1.0, 1.0);   // BSDF sampling finds them as often
                feed_probes(a, x + 32, y, 4, 1e-3, 1e5);  // trials far too costly
            }
        a.fit();
        EXPECT_EQ(a.failed_walk_trials(5, 5), allowed);
        EXPECT_TRUE(a.surface_trials(5, 5));
        EXPECT_FALSE(a.failed_walk_trials(20, 5));
        EXPECT_FALSE(a.failed_walk_trials(40, 5));
        EXPECT_EQ(a.regions_with_failed_walk_trials(), allowed ? 1u : 0u);
    }
    // Only a learned trial allocation offers it.
    ConnectionAllocation always(16, 16, 0, 0, 16, 1.0, TrialAllocation::Always, WorkPrice::Region, true);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) feed_probes(always, x, y, 4, 1e-3, 1.0);
    always.fit();
    EXPECT_FALSE(always.failed_walk_trials(5, 5));
}

// Regions are squares of the full film: a crop chooses as the full film does in every region
// it holds whole, from the same samples.
TEST(ConnectionAllocation, ACropChoosesAsTheFullFilm) {
    ConnectionAllocation full(64, 64, 0, 0, 16, 1.0), crop(40, 40, 8, 8, 16, 1.0);
    int clock_full = 0, clock_crop = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            // The walks' work varies over the film, so the regions choose differently.
            const double work = std::pow(10.0, -2.0 + 3.0 * (x + 2 * y) / 192.0);
            feed(full, x, y, 4, 1.0, false, work, clock_full);
            feed(crop, x, y, 4, 1.0, false, work, clock_crop);  // outside the window: ignored
        }
    full.fit();
    crop.fit();
    int distinct = 0;
    for (int ry = 1; ry < 3; ++ry)
        for (int rx = 1; rx < 3; ++rx) {
            EXPECT_EQ(crop.choice(16 * rx, 16 * ry), full.choice(16 * rx, 16 * ry)) << rx << "," << ry;
            distinct += full.choice(16 * rx, 16 * ry) != full.choice(16, 16);
        }
    EXPECT_GT(distinct, 0) << "the regions should not all choose alike";
}

// At equal time every pixel pays for every region's walks. One region whose walks pay by its own
// variance x work (q = 1/2, as in RegionsChooseTheLeastVarianceTimesWork) beside three whose
// relative variance is four times its own per unit of work, and which cannot walk: priced by the
// image, its walks are dearer (the price lambda = sum of relative variances over sum of work is
// about 1.3, not its own 0.24) and it takes q = 1/4; priced by itself it keeps 1/2. Beside quiet
// regions (a constant value) the image's price is lower and it keeps walking.
TEST(ConnectionAllocation, ThePriceOfWorkIsTheImages) {
    for (bool noisy : {true, false})
        for (WorkPrice price : {WorkPrice::Image, WorkPrice::Region}) {
            ConnectionAllocation a(64, 16, 0, 0, 16, 1.0, TrialAllocation::Always, price);
            int clock = 0;
            for (int y = 0; y < 16; ++y)
                for (int x = 0; x < 16; ++x) {
                    feed(a, x, y, 4, 1e-3, false, 20, clock);
                    for (int o = 16; o < 64; o += 16)
                        for (int i = 0; i < 4; ++i)
                            a.add(x + o, y, PilotSample(), noisy ? (i == 0 ? 4.0 : 0.0) : 1.0, 2.0);
                }
            a.fit();
            const bool image = price == WorkPrice::Image;
            EXPECT_EQ(a.q(5, 5), image && noisy ? 0.25 : 0.5) << "noisy " << noisy << ", image " << image;
            EXPECT_EQ(a.q(20, 5), 0.0);
        }
}

// With the image's price a crop (`--crop`, a farm task's part) renders the pilot of its own
// regions and of the lattice the price is learned from (lattice_outside), and chooses as the
// whole render in every region it holds, from those samples alone.
TEST(ConnectionAllocation, ACropLearnsTheImagesPriceFromTheLattice) {
    ConnectionAllocation full(256, 256, 0, 0, 16, 1.0, TrialAllocation::Always, WorkPrice::Image);
    ConnectionAllocation crop(256, 256, 0, 0, 16, 1.0, TrialAllocation::Always, WorkPrice::Image);
    int x0 = 40, y0 = 40, x1 = 100, y1 = 100;
    const auto lattice = crop.lattice_outside(x0, y0, x1, y1);
    crop.widen_to_regions(x0, y0, x1, y1);
    EXPECT_EQ(x0, 32);
    EXPECT_EQ(x1, 112);
    size_t in_lattice = 0;
    for (size_t r = 0; r < 256; ++r) in_lattice += crop.in_lattice(r);
    EXPECT_EQ(in_lattice, ConnectionAllocation::kLatticeRegions);
    EXPECT_GT(lattice.size(), 50u);
    const auto rendered = [&](int x, int y) {
        if (x >= x0 && x < x1 && y >= y0 && y < y1) return true;
        for (const auto& r : lattice)
            if (x >= r[0] && x < r[2] && y >= r[1] && y < r[3]) return true;
        return false;
    };
    // How often BSDF sampling finds MNEE's paths varies across the film, the walks' work down it;
    // each pixel's samples are its own (its clock starts from its position), whoever renders it.
    const auto pixel = [](ConnectionAllocation& a, int x, int y) {
        int clock = x + 7 * y;
        feed(a, x, y, 4, std::pow(10.0, -4.0 + 4.0 * x / 255.0), false, std::pow(10.0, 3.0 * y / 255.0), clock);
    };
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            pixel(full, x, y);
            if (rendered(x, y)) pixel(crop, x, y);
        }
    full.fit();
    crop.fit();
    int distinct = 0;
    for (int ry = 2; ry < 7; ++ry)
        for (int rx = 2; rx < 7; ++rx) {
            EXPECT_EQ(crop.choice(16 * rx, 16 * ry), full.choice(16 * rx, 16 * ry)) << rx << "," << ry;
            distinct += full.choice(16 * rx, 16 * ry) != full.choice(32, 32);
        }
    EXPECT_GT(distinct, 0) << "the regions should not all choose alike";
    // Without the lattice's samples the crop would learn another price.
    ConnectionAllocation alone(256, 256, 0, 0, 16, 1.0, TrialAllocation::Always, WorkPrice::Image);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) pixel(alone, x, y);
    alone.fit();
    int differ = 0;
    for (int ry = 2; ry < 7; ++ry)
        for (int rx = 2; rx < 7; ++rx) differ += alone.choice(16 * rx, 16 * ry) != full.choice(16 * rx, 16 * ry);
    EXPECT_GT(differ, 0) << "the test should see the lattice's part in the price";
}

namespace {

// The droplet of test_mnee_agreement (smooth water) under a light of `light_size`, with regions
// of 8 pixels so that its 24 x 18 film holds several, one pilot sample per pixel.
std::string droplet(
    const std::string& extra, double light_size,
    const std::string& bsdf =
        R"(<bsdf type="dielectric"><float name="int_ior" value="1.33"/><float name="ext_ior" value="1"/></bsdf>)") {
    return droplet_scene(bsdf, extra, std::to_string(light_size));
}

const char* kLearned = R"(<integer name="allocation_block" value="8"/><integer name="pilot_spp" value="2"/>)";

}  // namespace

// A region at q = 0 weighs its paths as the path tracer does and keeps no suffix (MneePath): on a
// rough droplet that includes NEE at the interface's own vertices, weighed against BSDF sampling
// alone. A delta light keeps q = 1 in every region, so NEE at the interface is weighed against
// MNEE there even at q = 0: under a point light alone (which the pilot does not record, so every
// region takes the cheapest candidate, q = 0) forgetting that counts those paths twice. The
// learned allocation agrees with nee per block under both lights.
TEST(ConnectionAllocation, LearnedAllocationOnRoughGlassMatchesNee) {
    const std::string rough =
        R"(<bsdf type="roughdielectric"><float name="alpha" value="0.1"/><float name="int_ior" value="1.33"/>)"
        R"(<float name="ext_ior" value="1"/></bsdf>)";
    for (bool point : {false, true}) {
        const auto scene = [&](const std::string& extra) {
            std::string xml = droplet(extra, 1.5, rough);
            if (point) {  // the rectangular light replaced by a point light
                const size_t a = xml.rfind("<shape type=\"rectangle\">"), b = xml.find("</shape>", a) + 8;
                xml.replace(a, b - a,
                            R"(<emitter type="point"><point name="position" x="-0.6" y="3" z="-0.4"/>)"
                            R"(<rgb name="intensity" value="8"/></emitter>)");
            }
            return xml;
        };
        const std::string what = point ? "rough droplet under a point light" : "rough droplet";
        LoadedScene nee = load_xml(scene(""), {{"integrator", "nee"}});
        // BSDF sampling alone (caster_probability 0): with the default's caster sampling it finds
        // this droplet's light well enough that every region takes q = 0, and the test needs
        // regions of both kinds.
        LoadedScene mnee = load_xml(scene(std::string(kLearned) + R"(<float name="caster_probability" value="0"/>)"),
                                    {{"integrator", "mnee"}});
        const std::vector<uint64_t> regions = allocation_regions(mnee, 4, what);
        ASSERT_GE(regions.size(), 2u);
        const uint64_t all = std::accumulate(regions.begin(), regions.end(), uint64_t(0));
        EXPECT_GT(regions[0], 0u) << what << ": no region at q = 0, the test would not see its weights";
        if (!point) {
            EXPECT_LT(regions[0], all) << what << ": every region at q = 0";
        }
        expect_agreement(block_estimates(nee, *nee.integrator, 512, 8, 6, 100),
                         block_estimates(mnee, *mnee.integrator, 64, 8, 6, 200), 0.01, what.c_str());
    }
}

// A pilot at q = 1/4 (connect_probability with the learned allocation) over a quarter of the
// samples: its connections count 4 times and weigh a quarter in MIS, then the regions' q take
// over; the image still agrees with nee.
TEST(ConnectionAllocation, PilotAtItsOwnProbabilityMatchesNee) {
    const std::string pilot =
        std::string(kLearned) +
        R"(<float name="connect_probability" value="0.25"/><string name="allocation" value="learned"/>)";
    std::string xml = droplet(pilot, 0.6);
    xml.replace(xml.find(R"(<integer name="pilot_spp" value="2"/>)"), 37, R"(<integer name="pilot_spp" value="16"/>)");
    LoadedScene nee = load_xml(droplet("", 0.6), {{"integrator", "nee"}});
    LoadedScene mnee = load_xml(xml, {{"integrator", "mnee"}});
    expect_agreement(block_estimates(nee, *nee.integrator, 512, 8, 6, 100),
                     block_estimates(mnee, *mnee.integrator, 64, 8, 6, 200), 0.01, "pilot at q = 1/4");
}

// The learned allocation agrees with nee per pixel block, under a large light (the regions
// choose differently, some without walks) and a smaller one, and the same blocks see a light
// 3 % brighter in one of the two renders.
TEST(ConnectionAllocation, LearnedAllocationMatchesNee) {
    for (double size : {1.5, 0.6}) {
        LoadedScene nee = load_xml(droplet("", size), {{"integrator", "nee"}});
        LoadedScene mnee = load_xml(droplet(kLearned, size), {{"integrator", "mnee"}});
        LoadedScene brighter = load_xml(droplet(kLearned, size), {{"integrator", "mnee"}, {"radiance", "3.09"}});
        const std::string what = "learned allocation, light " + std::to_string(size);
        // The regions' choices: not all alike, so regions with and without walks are tested.
        const std::vector<uint64_t> regions = allocation_regions(mnee, 4, what);
        int kinds = 0;
        for (uint64_t n : regions) kinds += n > 0;
        EXPECT_GE(kinds, 2) << what << ": every region chose alike";

        const auto a = block_estimates(nee, *nee.integrator, 512, 8, 6, 100);
        const auto b = block_estimates(mnee, *mnee.integrator, 64, 8, 6, 200);
        expect_agreement(a, b, 0.01, what.c_str());
        const auto c = block_estimates(brighter, *brighter.integrator, 64, 8, 6, 200);
        EXPECT_GE(count_disagreements(a, c, 0.01), 1) << what << ": a 3 % brighter light passes";
    }
}

// The image stays a pure function of the seed: one thread with 16-pixel tiles and two threads
// with 7-pixel tiles give the same bits, and a crop whose edges lie on the regions' grid gives
// the full render's pixels (its regions learn from the same pilot samples).
TEST(ConnectionAllocation, ImageIsIndependentOfThreadsTilesAndCrops) {
    const std::string xml = droplet(kLearned, 1.5);
    LoadedScene ls = load_xml(xml, {{"integrator", "mnee"}});
    RenderOptions opt;
    opt.spp = 6;
    opt.progress = false;
    opt.threads = 1;
    const auto a = render(*ls.scene, *ls.integrator, ls.film, opt).film.to_linear_srgb();
    opt.threads = 2;
    opt.tile_size = 7;
    const auto b = render(*ls.scene, *ls.integrator, ls.film, opt).film.to_linear_srgb();
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "pixel component " << i;

    // A part of the frame (`--crop`, a farm task's) gives the full render's pixels: its pilot
    // covers its regions and the lattice the image's price of work is learned from.
    // Single regions learn another price without the lattice's pilot (a region alone prices work
    // at its own rate), so a part that skipped it would differ.
    for (const PixelRect& rect : {PixelRect{8, 0, 24, 16}, PixelRect{0, 0, 8, 8}, PixelRect{8, 8, 16, 16},
                                  PixelRect{16, 8, 24, 16}, PixelRect{0, 16, 8, 18}}) {
        RenderOptions part = opt;
        part.crop = rect;
        const auto p = render(*ls.scene, *ls.integrator, ls.film, part).film.to_linear_srgb();
        ASSERT_EQ(p.size(), a.size());
        for (int y = rect.y0; y < rect.y1; ++y)
            for (int x = rect.x0; x < rect.x1; ++x)
                for (int k = 0; k < 3; ++k) {
                    const size_t i = (size_t(y) * 24 + size_t(x)) * 3 + size_t(k);
                    ASSERT_EQ(p[i], a[i]) << "part pixel " << x << "," << y;
                }
    }

    // A scene's own crop window is the film whose work is priced: with each region's own price it
    // too gives the full render's pixels in the regions it holds whole.
    const std::string regional = droplet(std::string(kLearned) + R"(<string name="work_price" value="region"/>)", 1.5);
    LoadedScene lr = load_xml(regional, {{"integrator", "mnee"}});
    const auto f = render(*lr.scene, *lr.integrator, lr.film, opt).film.to_linear_srgb();
    std::string cropped = regional;
    const std::string at = R"(<integer name="height" value="18"/>)";
    cropped.insert(cropped.find(at) + at.size(),
                   R"(<integer name="crop_offset_x" value="8"/><integer name="crop_offset_y" value="0"/>
                      <integer name="crop_width" value="16"/><integer name="crop_height" value="16"/>)");
    LoadedScene lc = load_xml(cropped, {{"integrator", "mnee"}});
    const auto c = render(*lc.scene, *lc.integrator, lc.film, opt).film.to_linear_srgb();
    ASSERT_EQ(c.size(), size_t(16 * 16 * 3));
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int k = 0; k < 3; ++k)
                ASSERT_EQ(c[(size_t(y) * 16 + size_t(x)) * 3 + size_t(k)],
                          f[(size_t(y) * 24 + size_t(x + 8)) * 3 + size_t(k)])
                    << "crop pixel " << x << "," << y;
}

namespace {

// A glass ball (IOR 1.33, no Abbe number) resting on the droplet scene's plane under a large
// light behind and above it: the caustic lies at the ball's foot, inside its shadow, as in the
// gallery's ball_plane.xml, with a light large enough for nee to converge.
std::string ball_on_a_plane(const std::string& extra) {
    std::string s = droplet(extra, 0.8);
    const auto swap = [&](const std::string& from, const std::string& to) { s.replace(s.find(from), from.size(), to); };
    swap(R"(<point name="center" x="0" y="0.35" z="0"/><float name="radius" value="0.8"/>)",
         R"(<point name="center" x="0" y="0.5" z="0"/><float name="radius" value="0.5"/>)");
    swap(R"(origin="0, 3.2, 3.2" target="0, 0.2, 0")", R"(origin="0, 2.4, 3.6" target="0, 0.3, 0.3")");
    swap(R"(<rotate x="1" angle="90"/><translate x="-0.8" y="3" z="-0.5"/>)",
         R"(<rotate x="1" angle="40"/><translate x="0" y="2.2" z="-2.0"/>)");
    return s;
}

// The same with a glass cube (a 12-triangle mesh, 0.8 on a side) in the ball's place.
std::string cube_on_a_plane(const std::string& extra) {
    std::string s = ball_on_a_plane(extra);
    const std::string from = R"(<shape type="sphere">
    <point name="center" x="0" y="0.5" z="0"/><float name="radius" value="0.5"/>)";
    s.replace(s.find(from), from.size(), R"(<shape type="cube">
    <transform name="to_world"><scale value="0.4"/><rotate y="1" angle="30"/><translate y="0.4"/></transform>)");
    return s;
}

using SceneOf = std::string (*)(const std::string& extra);

// Each (name, integrator parameters) of `estimators` renders `scene` as `integrator` (mnee), at `spp_fixed` (the
// learned allocation at `learned_spp`: its regions without walks are BSDF sampling's noise), and
// must agree with nee per pixel block, see a 3 % brighter light in some block, and walk (so that
// the agreement is MNEE's and not nee's alone).
void expect_estimators_agree(SceneOf scene, const std::vector<std::pair<std::string, std::string>>& estimators,
                             int learned_spp, const std::string& integrator = "mnee", int spp_fixed = 64) {
    LoadedScene nee = load_xml(scene(""), {{"integrator", "nee"}});
    const auto a = block_estimates(nee, *nee.integrator, 512, 8, 6, 100);
    for (const auto& [what, extra] : estimators) {
        LoadedScene mnee = load_xml(scene(extra), {{"integrator", integrator}});
        LoadedScene brighter = load_xml(scene(extra), {{"integrator", integrator}, {"radiance", "3.09"}});
        const int spp = what.starts_with("learned allocation") ? learned_spp : spp_fixed;
        RenderOptions opt;
        opt.spp = 4;
        opt.progress = false;
        if (integrator == "mnee") {
            EXPECT_GT(render(*mnee.scene, *mnee.integrator, mnee.film, opt).counters[walk_counters::walks_converged],
                      100u)
                << what << ": no walks";
        }
        expect_agreement(a, block_estimates(mnee, *mnee.integrator, spp, 8, 6, 200), 0.01, what.c_str());
        // The brighter light is judged on the whole image: per block, 8 replicas leave Welch's test
        // too little power to see 3 % in every build (under water, gcc's build saw 1 or 2 of 12
        // blocks differ, clang's sanitizer build none for three of four estimators), while the
        // whole image sees it at t of 6 to 9.
        const Estimate whole = whole_image(a),
                       whole_brighter = whole_image(block_estimates(brighter, *brighter.integrator, spp, 8, 6, 200));
        EXPECT_LT(welch_p_value(whole, whole_brighter), 1e-3)
            << what << ": a 3 % brighter light passes: " << whole.mean << " +- " << whole.stderr_ << " vs "
            << whole_brighter.mean << " +- " << whole_brighter.stderr_;
    }
}

}  // namespace

// Every estimator class, and the learned allocation, agrees with nee per pixel block on a ball on
// a plane (issue 26), and each render sees a light 3 % brighter in the same blocks.
TEST(ConnectionAllocation, EveryEstimatorAgreesWithNeeOnABallOnAPlane) {
    const char* fixed = R"(<string name="allocation" value="fixed"/>)";
    expect_estimators_agree(ball_on_a_plane,
                            {
                                {"paper's (solutions=one)", R"(<string name="solutions" value="one"/>)"},
                                {"all", std::string(R"(<string name="solutions" value="all"/>)") + fixed},
                                {"unbiased", std::string(R"(<string name="solutions" value="unbiased"/>)") + fixed},
                                {"fallback", std::string(R"(<string name="solutions" value="fallback"/>)") + fixed},
                                {"keyed", std::string(R"(<string name="solutions" value="keyed"/>)") + fixed},
                                {"learned allocation", kLearned},
                                // The trials' finds beside a failed straight walk, at full
                                // weight: the ball's post-fold light is theirs then.
                                // Walks cut to four iterations: the straight walk then fails at
                                // many light samples with a solution, and the trials carry them.
                                {"unbiased, failed_walk_weight 1, four-iteration walks",
                                 std::string(R"(<float name="failed_walk_weight" value="1"/>)") +
                                     R"(<integer name="max_iterations" value="4"/>)" + fixed},
                                {"learned allocation, failed_walk_weight 1",
                                 std::string(kLearned) + R"(<float name="failed_walk_weight" value="1"/>)"},
                                // Surface weight 0.9: the trials' paths weigh nearly their full
                                // density, so a density that forgot the regions without them
                                // would lose most of the post-fold light.
                                {"learned allocation, no surface trials",
                                 std::string(kLearned) + R"(<string name="trial_allocation" value="never"/>)" +
                                     R"(<float name="surface_weight" value="0.9"/>)"},
                            },
                            64);
}

// Caster sampling (scene/caster_sampling.h) stays unbiased: `nee` aiming 50 % or 90 % of its
// directions at a glass ball or cube agrees with plain `nee` per pixel block, and sees a 3 %
// brighter light.
// A weight that read BSDF sampling's own density where the mixture drew (NEE's, or an emitter
// hit's) would count the caustic under the ball wrongly (docs/testing.md, the mutation study).
TEST(ConnectionAllocation, CasterSamplingAgreesWithNeeOnABallOnAPlane) {
    const std::vector<std::pair<std::string, std::string>> mixtures = {
        {"caster_probability 0.5", R"(<float name="caster_probability" value="0.5"/>)"},
        {"caster_probability 0.9", R"(<float name="caster_probability" value="0.9"/>)"}};
    expect_estimators_agree(ball_on_a_plane, mixtures, 64, "nee", 256);
    // A glass cube's sphere holds directions that miss it, so there NEE's shadow rays reach the
    // light inside the cone too, and its weight must read the mixture's density.
    expect_estimators_agree(cube_on_a_plane, mixtures, 64, "nee", 256);
}

namespace {

// The water's OBJ, one file per process: ctest runs test binaries side by side, and another run
// of this test must not rewrite the mesh while this one loads it.
std::filesystem::path water_obj() {
    return std::filesystem::temp_directory_path() / ("snell_test_water_" + std::to_string(::getpid()) + ".obj");
}

// A water height field over a floor (the gallery's pool.xml, small and without walls): a 16 x 16
// grid of the surface y = 0.6 + 0.06 sin(3x) cos(2.5z) over [-1, 1]^2, smooth normals, written as
// an OBJ, over the droplet's floor, under a large light: the floor beneath the water sees the
// light only through it, often enough for nee (BSDF sampling through the water) to converge.
std::string water_over_a_floor(const std::string& extra) {
    const auto obj = water_obj();
    {
        std::ofstream out(obj);
        constexpr int n = 16;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const double x = -1 + 2.0 * i / n, z = -1 + 2.0 * j / n;
                const double y = 0.6 + 0.06 * std::sin(3 * x) * std::cos(2.5 * z);
                const double dx = 0.18 * std::cos(3 * x) * std::cos(2.5 * z);
                const double dz = -0.15 * std::sin(3 * x) * std::sin(2.5 * z);
                out << "v " << x << " " << y << " " << z << "\nvn " << -dx << " 1 " << -dz << "\n";
            }
        const auto at = [&](int i, int j) { return j * (n + 1) + i + 1; };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
                out << "f " << a << "//" << a << " " << c << "//" << c << " " << b << "//" << b << "\n"
                    << "f " << a << "//" << a << " " << d << "//" << d << " " << c << "//" << c << "\n";
            }
    }
    std::string s = droplet(extra, 1.2);
    const auto swap = [&](const std::string& from, const std::string& to) { s.replace(s.find(from), from.size(), to); };
    swap(R"(<shape type="sphere">
    <point name="center" x="0" y="0.35" z="0"/><float name="radius" value="0.8"/>)",
         R"(<shape type="obj"><string name="filename" value=")" + obj.string() + R"("/>)");
    swap(R"(origin="0, 3.2, 3.2" target="0, 0.2, 0")", R"(origin="0, 3.4, 1.6" target="0, 0, 0")");
    swap(R"(<translate x="-0.8" y="3" z="-0.5"/>)", R"(<translate x="-0.3" y="2.6" z="-0.4"/>)");
    return s;
}

}  // namespace

// The estimators and the learned allocation agree with nee per pixel block on water over a floor
// (a mesh caster with smooth normals, one interface per path), and see a 3 % brighter light.
TEST(ConnectionAllocation, EveryEstimatorAgreesWithNeeUnderWater) {
    const char* fixed = R"(<string name="allocation" value="fixed"/>)";
    expect_estimators_agree(
        water_over_a_floor,
        {
            {"paper's (solutions=one)", R"(<string name="solutions" value="one"/>)"},
            {"unbiased", std::string(R"(<string name="solutions" value="unbiased"/>)") + fixed},
            {"keyed", R"(<string name="solutions" value="keyed"/><integer name="trials" value="4"/>)"},
            {"learned allocation", kLearned},
        },
        192);
    std::filesystem::remove(water_obj());
}
