#pragma once
// User-facing settings of manifold next event estimation (scene-file names in parentheses).

#include "manifold/manifold_walk.h"

namespace snell {

class Props;

/// surface_weight's default with solutions=unbiased and both kinds of seeds (the best measured
/// at equal time on the droplets' caustics; docs/mnee.md, "surface_weight").
inline constexpr double kDefaultSurfaceWeight = 0.03;
/// exterior_reflections' default for a scene's multi-solution estimators (docs/mnee.md,
/// "Reflections off the outside of glass").
inline constexpr double kDefaultExteriorReflections = 0.05;
/// mis_cutoff's default for a scene's unbiased estimators (docs/mnee.md, "The MIS cutoff").
inline constexpr double kDefaultMisCutoff = 10;
/// The biased mode's progress test (WalkSettings::stall_window; ratio 0.7): its surface trials run
/// at every connection, and walks that cannot converge ran to max_iterations. Window 4 gave 10-50 %
/// more samples at 30 s over the gallery with the same means (docs/experiments.md, twenty-fifth
/// measurement); the unbiased default, whose regions walk little after the pilot, gains nothing.
inline constexpr int kBiasedStallWindow = 4;
/// trials' default with solutions=keyed (docs/mnee.md, "Keyed trials").
inline constexpr int kKeyedTrials = 16;
/// The most refractive vertices a path records after x_b (max_vertices' upper bound).
inline constexpr int kMaxChainVertices = 16;

/// (seeding) where the walks of one light connection start: the paper's straight segment x_b ->
/// x_c (Sec. 3.1), points drawn on the caster shapes (SMS), or both.
enum class MneeSeeding { Straight, Surface, StraightAndSurface };
/// (solutions) which solutions a light connection counts: the one the straight seed walks to
/// (the paper's Alg. 1, MIS by Alg. 2); every distinct one found by `trials` surface seeds
/// (consistent; biased low for finite trials by the solutions none of them found); or,
/// unbiased, the surface solutions weighted by a geometric estimate of 1 / p (Specular
/// Manifold Sampling's estimator), plus the straight seed's; or the straight seed's solution
/// where that seed is clear of opaque surfaces and, where an opaque surface blocks it (an object
/// inside glass), the unbiased estimator's surface solutions (`fallback`: unbiased; MIS by Alg. 2
/// where the seed is clear, by the solution density where it is blocked). A scene's `mnee`
/// defaults to `unbiased`, in the biased mode too, with surface_weight 0.03 (the biased mode: 1).
/// `keyed`: every distinct solution of the straight seed and `trials` surface trials per caster,
/// counted once, the trials drawn from a stream keyed by the connection so that the density
/// replays them (keyed_trials_estimator.h; unbiased).
enum class MneeSolutions { One, All, Unbiased, Fallback, Keyed };
/// (surface_side) where a surface seed starts: at x_b (SMS's seeds), at the light point (traced
/// through the glass from the light), or either with probability 1/2.
enum class SurfaceSide { Receiver, Light, Both };
/// (trial_allocation) which image regions run the surface trials (MneeSettings).
enum class TrialAllocation { Learned, Always, Never };
/// (work_price) what a unit of work costs a region of the learned allocation in variance: the
/// image's exchange rate (`image`: every region pays the same price, relative variance against
/// the image's work) or its own (`region`: each region minimises its variance x work alone).
enum class WorkPrice { Image, Region };

struct MneeSettings {
    int max_vertices = 8;           ///< (max_vertices) refractive vertices collected on a seed path
    bool ignore_occluders = false;  ///< (ignore_occluders) walk through opaque blockers of the seed (Sec. 3.1)
    /// (cull_margin) a seed whose direction at x_b lies more than this far below the horizon
    /// (as -cos) is culled; > 0 keeps lights that are reachable only through the refracted
    /// path (Fig. 3). 1 disables culling.
    double cull_margin = 0.5;
    bool biased = false;  ///< (biased) outlier removal of Sec. 3.5
    /// (spectral_walks) through a dispersive chain every wavelength of the path solves its own
    /// chain from the same seed and light point, with its own contribution and density; false:
    /// the hero's solution alone, carrying the others' share (cheaper, colour noisier).
    bool spectral_walks = true;
    /// (max_geometry) optional clamp on the chain's focusing ratio r = |do_b/dx_c| |x_c - x_b|^2 /
    /// |cos theta_c|: the generalised geometry term (Sec. 3.5) over the free-space one. r is O(1)
    /// through a slab and unbounded at a caustic's fold, where its tail makes MNEE's variance
    /// log-divergent (issue 10). A value t > 0 scales a connection by min(1, t / r): biased,
    /// energy is only removed. 0 (default): off.
    double max_geometry = 0;
    // The paper's estimator here; a scene's `mnee` defaults to solutions=unbiased with
    // straight+surface seeds and surface_weight 0.03 (from_props).
    MneeSeeding seeding = MneeSeeding::Straight;
    MneeSolutions solutions = MneeSolutions::One;
    /// (trials) surface seeds per light connection, each on a caster chosen for it (CasterChoice;
    /// keyed: per caster): every one walked (solutions=all and keyed), or the first round M of
    /// solutions=unbiased (the scene parameter defaults to 1
    /// there, to kKeyedTrials for keyed)
    int trials = 16;
    /// (max_trials) cap C on the Bernoulli trials of solutions=unbiased: its estimate of 1 / p is
    /// short by the factor (1 - p)^C (docs/mnee.md).
    int max_trials = 256;
    SurfaceSide surface_side = SurfaceSide::Receiver;
    /// (seed_candidates) a surface trial from x_b traces this many seeds and walks the one whose
    /// last ray passes closest to the light point (seed_miss). 4 halved the variance per second
    /// of the glass sphere's caustic against 1 (SMS's single seed); 2, 8 and 16 lay between.
    /// solutions=keyed defaults to 1: its trials must spread over the basins (docs/mnee.md).
    int seed_candidates = 4;
    /// (reflections) surface seeds may reflect at an interface (with Fresnel's probability, and
    /// always under total internal reflection), so that solutions=all and unbiased also find
    /// paths with internal reflections, and take them from BSDF sampling by MIS.
    bool reflections = false;
    /// (exterior_reflections) the probability rho with which each x_b makes a reflected
    /// connection: light reflected once off the outside of glass (smooth or rough), connected by
    /// its own manifold walk (ExteriorReflection), counted 1 / rho and weighed against BSDF
    /// sampling (and NEE from rough glass) by MIS with rho times its density. 0: none (BSDF sampling alone finds that
    /// light). The scene parameter defaults to kDefaultExteriorReflections, and to 0 for the paper's estimator.
    double exterior_reflections = 0;
    /// (surface_weight) c in (0, 1]: with the straight seed and surface seeds both walked
    /// (solutions=all or unbiased, seeding=straight+surface) and the straight segment x_b -> x_c
    /// clear, MIS takes the density of a path the straight seed does not walk to (Alg. 2 says
    /// which) as c times its solution density. c is a function of the path, so the weights of
    /// all techniques still sum to one. Why: a trial finds such a solution with probability p
    /// and the unbiased estimator counts it about 1 / p times, which multiplies its second
    /// moment by about 2 / p; MIS that ignores this gives the rare, heavily counted finds
    /// shares that BSDF sampling carries better. c near p / 2 balances them; c = 1 is SMS's
    /// weighting, and c -> 0 the paper's (Alg. 2 alone). Behind an opaque blocker (no straight
    /// solution) the surface solutions keep their full density. With c < 1, beside a clear
    /// straight seed the surface solutions count only where the straight walk converged (to
    /// any solution; elsewhere, mostly where there is none, the trials would fail at the cost
    /// of full walks), and only those crossing the straight seed's shapes in its order: the
    /// paths Alg. 2 can tell apart, so density() gives the others 0 (BSDF sampling's).
    double surface_weight = 1;
    /// (failed_walk_weight) c_f in [0, 1], with surface_weight < 1: beside a clear straight seed
    /// whose walk does not converge, the surface solutions count too, with MIS density c_f times
    /// their solution density (the same paths as above: the straight seed's shapes in its
    /// order). Past a caustic's fold the straight walk fails where other solutions exist, and
    /// BSDF sampling finds them rarely there. 0 leaves them to BSDF sampling and runs no trials
    /// there (the pilot's probes alone look). Unbiased for every c_f: a function of the path.
    double failed_walk_weight = 0;
    /// (connect_probability) q in (0, 1]: the probability with which the `mnee` integrator
    /// connects a light sample whose seed refracts by the manifold technique; otherwise it makes
    /// no connection and leaves those paths to BSDF sampling (issue 26: where a focusing ball
    /// makes the light look large, BSDF sampling finds it at a fraction of a walk's cost). A
    /// connection made counts 1 / q and MIS weighs the technique's density as q p_mnee, so the
    /// estimate stays unbiased. Lights BSDF sampling cannot hit (point, spot, directional) keep 1.
    double connect_probability = 1;
    /// (allocation) `learned`: q chosen per image region from the render's first samples
    /// (integrators/mnee/connection_allocation.h), the default of a scene's unbiased `mnee`;
    /// `fixed`: connect_probability everywhere (the default with connect_probability given,
    /// in the biased mode, whose outlier rule needs every region's walks, with solutions=keyed,
    /// and inside pssmlt and erpt, which have no pixels to learn per).
    bool learned_allocation = false;
    /// (trial_allocation) with the learned allocation and surface solutions weighed apart
    /// (splits_surface_solutions()): `learned`, each region also chooses whether its connections
    /// run the surface trials (on a height field they cost more than half of MNEE's time and
    /// rarely find a solution the straight seed misses); `always`: every region runs them;
    /// `never`: none does (their paths are left to BSDF sampling, as Alg. 2 leaves them).
    TrialAllocation trial_allocation = TrialAllocation::Learned;
    /// (failed_walk_trials) with trial_allocation `learned` and failed_walk_weight 0: `learned`,
    /// a region may also choose to run its surface trials beside failed straight walks, their
    /// finds weighed 1 (as failed_walk_weight 1 there), judged by the pilot's probes; `never`:
    /// no region does. Where a fold is in view (a ball on a plane) the trials there pay several
    /// times over; on the object inside glass they do not (docs/mnee.md, "Trials where the
    /// straight walk fails").
    bool failed_walk_trials = true;
    /// (work_price) `image`: at equal time every pixel pays for every region's walks, so a
    /// region walks where the relative variance it saves beats what that work would buy the
    /// image (one exchange rate, learned from a lattice of regions); `region`: each region
    /// minimises its own variance x work (issue 26, docs/mnee.md "The image's price of work").
    WorkPrice work_price = WorkPrice::Image;
    /// (mis_cutoff) K >= 0: MIS gives MNEE no share of a path where the other techniques'
    /// density exceeds K q times solution_density_bound, the most MNEE's density can be there
    /// (Veach's cutoff heuristic, with a bound that needs no walk). Under the power heuristic
    /// MNEE's weight there is below 1 / (1 + K^2), so the image hardly changes, but BSDF
    /// sampling's paths through the glass skip Alg. 2's walk wherever they are cut, the most
    /// of them (issue 26, point 5). The bound is a function of the path alone, so both sides
    /// of every path cut alike and the weights still sum to one. 0: off (the paper's MIS; the
    /// default with solutions=one and in the biased mode, whose outlier rule needs MNEE's
    /// density of every path).
    double mis_cutoff = 0;
    int pilot_spp = 4;          ///< (pilot_spp) samples per pixel the allocation learns from, at q
    int allocation_block = 16;  ///< (allocation_block) pixels on a side of a region
    WalkSettings walk;          ///< (max_iterations, threshold, allow_error_increase, projection, ...)

    /// Whether the surface trials' solutions are a technique apart from the straight seed's in
    /// MIS (both kinds of seeds, surface_weight < 1, solutions all or unbiased): where the
    /// straight seed is clear they weigh c times their density, and a region may then do without
    /// them (trial_allocation), their density 0 there.
    bool splits_surface_solutions() const;

    /// The scene's `mnee` parameters (docs/integrators.md), with the scene defaults: the
    /// unbiased estimator with both kinds of seeds and the learned allocation. A bad value or a
    /// contradictory pair raises a located SceneError.
    static MneeSettings from_props(const Props& props);
};

}  // namespace snell
