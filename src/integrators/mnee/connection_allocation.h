#pragma once
// Where MNEE's walks pay (issue 26): the probability q with which the `mnee` integrator connects
// a refracting light sample by the manifold technique, chosen per image region from a pilot.
//
// A walk costs many rays, and where a focusing interface makes the light look large (a ball on a
// plane) BSDF sampling finds the same paths at a fraction of the cost; where the light is small
// behind glass (a pool) only the walks find them. MIS weighs samples, not their cost, so the
// choice is made here, as efficiency-aware MIS does (Grittmann et al. 2022): the first
// `pilot_spp` samples of every pixel record, for every candidate q, an estimate of the second
// moment the refracted light would have under q (the balance heuristic with n_mnee = q, from the
// densities every path carries, every technique's paths estimating it for all), and the
// sample's work. Each region then takes the q that minimises its variance
// times its work. q = 0 leaves a region's refracted light to BSDF sampling alone (`nee`'s
// estimator there), and is ruled out where the pilot saw light only MNEE produces.
// Where the surface trials' solutions are a technique apart in MIS (surface_weight < 1), each
// region also chooses whether its connections run them: without, their paths' MNEE density is 0
// (BSDF sampling's alone), so the pilot's surface paths are judged at density 0 and their
// work is left out. On a height field the trials cost more than the rest of a connection and
// rarely find a path the straight seed misses; on a ball on a plane they carry its post-fold
// light.
//
// Unbiased for any choice: a connection counts 1 / q and MIS weighs MNEE's density as q p_mnee
// (MneeIntegrator), and the choice depends only on the pilot's samples, which are counted too.
// Deterministic: each pixel's statistics are summed in sample order by the one thread rendering
// it, regions sum their pixels in raster order, and work is counted (rays and walk steps, see
// work_meter.h), not timed, so the image does not depend on threads or machine load.
#include <array>
#include <cstdint>
#include <vector>

#include "manifold/mnee_settings.h"

namespace snell {

/// The q a region chooses from: 0 (no walks) and powers of two down from 1.
inline constexpr std::array<double, 8> kConnectCandidates = {0.0,       1.0 / 64, 1.0 / 32, 1.0 / 16,
                                                             1.0 / 8.0, 1.0 / 4,  1.0 / 2,  1.0};
inline constexpr int kCandidateCount = int(kConnectCandidates.size());

/// What one pilot camera sample records about its refracted light paths: those MNEE produces
/// (its connections) and those the other techniques produce that MNEE could too (BSDF
/// sampling's emitter hits through the interfaces, NEE from a rough last interface vertex).
struct PilotSample {
    /// Estimates, from this sample's paths, of the second moment of the refracted light under
    /// each candidate q: the balance heuristic with n_mnee = q has second moment
    /// int f^2 / (q p_m + p_other), and each path estimates it divided by the pilot's own
    /// combined density q_pilot p_m + p_other.
    std::array<double, kCandidateCount> m2{};
    /// The same without surface trials: the surface trials' paths at MNEE density 0.
    std::array<double, kCandidateCount> m2_no_trials{};
    /// The same with the surface trials beside failed straight walks too, their finds weighed 1:
    /// the probes' paths at MNEE density q p_s (ConnectionAllocation's third kind).
    std::array<double, kCandidateCount> m2_failed_walk{};
    double m2_pilot = 0;      ///< the squares of the paths' contributions under the pilot's q
    double work_connect = 0;  ///< work of the MNEE connections made (at the pilot's q)
    double work_trials = 0;   ///< ... of which their surface trials
    double work_density = 0;  ///< work of MNEE's densities for the other techniques' MIS weights
    /// work of tracing the straight seeds beyond the one shadow ray each that q = 0 makes instead
    double work_seed = 0;
    double work_probe = 0;      ///< work of the pilot's probes (no candidate makes them)
    bool needs_mnee = false;    ///< light that only MNEE produces here: q = 0 would lose it
    bool needs_trials = false;  ///< light that only the surface trials produce here

    /// A connection made with probability q_pilot: `value` its contribution before MIS and 1 / q
    /// (mean over wavelengths, path throughput included), `count` the estimator's count of the
    /// solution (N of the 1 / p estimate; 1 for the straight seed's), p_m MNEE's density of the
    /// path in MIS, `weight` the c by which p_m is scaled from the density MNEE draws the path
    /// with (ManifoldSolution::weight), p_other the sum of the other techniques' densities of it;
    /// `surface`: a path only the surface trials reach.
    void add_connection(double value, double count, double p_m, double weight, double p_other, double q_pilot,
                        bool surface = false);
    /// A path sampled by another technique with density p_t: `value` its contribution before
    /// MIS; p_m, weight, p_other and `surface` as above (p_other includes p_t).
    void add_other(double value, double p_t, double p_m, double weight, double p_other, double q_pilot,
                   bool surface = false);

    /// A path the pilot's probes found beside a straight walk that did not converge
    /// (ManifoldQuery::probes): not counted in the image, and BSDF sampling's alone under every
    /// candidate. `value`, `count` as for a connection, p_s the density the probes find it with.
    void add_probe(double value, double count, double p_s, double p_other, double q_pilot);
    /// The same kind of path sampled by another technique with density p_t (counted, at MNEE
    /// density 0): p_s the density the probes would find it with (DensityDetail::probe).
    void add_probe_other(double value, double p_t, double p_s, double p_other, double q_pilot);

private:
    /// A path of integrand f drawn by MNEE (`own`, counted n times) or another technique (n = 1);
    /// p_m its MNEE density in MIS, p_s the one MNEE draws it with; `realized` its weighted
    /// contribution to the pilot's sample.
    void add_path(double f, double n, double p_m, double p_s, double p_other, double q_pilot, bool surface, bool own,
                  double realized);
    /// A path of integrand f that only the third kind gives to MNEE, drawn by the probes
    /// (`own`, counted n times) or another technique (n = 1), which the probes find with
    /// density p_s.
    void add_common(double f, double n, double p_s, double p_other, double q_pilot, bool own, double realized);
};

class ConnectionAllocation {
public:
    /// The pilot renders at q_pilot. Pixels are the film window's (width x height at offset
    /// crop_x, crop_y of the full film); regions are `block` x `block` squares of the full film,
    /// so a crop's regions are the full render's where they lie wholly inside it.
    /// `trials`: whether each region chooses to run the surface trials (Learned), or every region
    /// runs them (Always) or none does (Never).
    /// `price`: whether each region pays the image's price for its work (Image) or its own
    /// (Region: least variance x work, region by region).
    /// `failed_walk_kind`: with learned trials, a region may also choose to run them beside
    /// failed straight walks, their finds weighed 1 (the pilot's probes tell their variance).
    ConnectionAllocation(int width, int height, int crop_x, int crop_y, int block, double q_pilot,
                         TrialAllocation trials = TrialAllocation::Always, WorkPrice price = WorkPrice::Region,
                         bool failed_walk_kind = false);

    bool learning() const { return !m_fitted; }
    double q_pilot() const { return m_q_pilot; }
    /// q for a sample of full-film pixel (x, y): the pilot's while learning, then its region's.
    double q(int x, int y) const;
    /// Whether a sample of full-film pixel (x, y) runs the surface trials: always while learning.
    bool surface_trials(int x, int y) const;
    /// Whether it runs them beside failed straight walks too: never while learning.
    bool failed_walk_trials(int x, int y) const;
    /// One pilot sample of full-film pixel (x, y): what it recorded, its value (mean over
    /// wavelengths) and its whole work. Only the thread rendering the pixel may call this.
    void add(int x, int y, const PilotSample& s, double value, double work);
    /// Ends the pilot: every region takes the candidate (q, and with or without trials) of least
    /// variance x work (WorkPrice::Region), or of least relative variance plus the image's price
    /// times work (WorkPrice::Image).
    void fit();

    /// Widens the window rectangle [x0, x1) x [y0, y1) (pixels of the film window) to the whole
    /// regions it meets, clipped to the window: the pixels a crop's choices depend on.
    void widen_to_regions(int& x0, int& y0, int& x1, int& y1) const;
    /// The pixel rectangles {x0, y0, x1, y1} (of the film window) of the lattice regions that
    /// lie outside the rectangle [x0, x1) x [y0, y1) (widened to regions): with the image's
    /// price, every crop's choices depend on them too, so its pilot renders them.
    std::vector<std::array<int, 4>> lattice_outside(int x0, int y0, int x1, int y1) const;
    /// Whether region r (an index into the regions meeting the window, raster order) is one of
    /// the lattice the image's price is learned from: every k-th region in raster order, k
    /// chosen from the window alone so that about kLatticeRegions are, and a crop or an MPI
    /// rank learns the price from the same pixels as the whole render.
    bool in_lattice(size_t r) const;
    static constexpr size_t kLatticeRegions = 64;
    /// The pilot's per-pixel records as doubles (zero for pixels without pilot samples, so that
    /// the records of MPI ranks that rendered different pixels sum exactly), and back.
    std::vector<double> pilot_state() const;
    void set_pilot_state(const std::vector<double>& state);

    /// Regions by chosen candidate (kCandidateCount bins), for the statistics.
    std::array<uint64_t, kCandidateCount> histogram() const;
    /// Regions that run no surface trials, for the statistics.
    uint64_t regions_without_trials() const;
    /// Regions that run the trials beside failed straight walks too, for the statistics.
    uint64_t regions_with_failed_walk_trials() const;
    /// The candidate index chosen by the region of full-film pixel (x, y) (-1 while learning).
    int choice(int x, int y) const;

private:
    struct PixelStats {
        std::array<double, kCandidateCount> m2{}, m2_no_trials{}, m2_failed_walk{};
        double m2_pilot = 0;
        double sum = 0, sum2 = 0;  ///< the samples' values and squares
        double work = 0, work_connect = 0, work_trials = 0, work_density = 0, work_seed = 0, work_probe = 0;
        uint32_t n = 0;
        bool needs_mnee = false, needs_trials = false;
    };
    int region_of(int x, int y) const;

    int m_width, m_height, m_crop_x, m_crop_y, m_block;
    int m_rx0, m_ry0, m_rw, m_rh;  ///< the regions that meet the window
    double m_q_pilot;
    TrialAllocation m_trial_allocation;
    WorkPrice m_price;
    bool m_failed_walk_kind;
    bool m_fitted = false;
    std::vector<PixelStats> m_pixels;  ///< freed by fit()
    std::vector<int8_t> m_choice;      ///< per region
    /// per region: 0 no surface trials, 1 the trials (beside converged straight walks where
    /// surface solutions are weighed apart), 2 the trials beside failed straight walks too
    std::vector<int8_t> m_trials;
};

}  // namespace snell
