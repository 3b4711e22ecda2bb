#include "manifold/mnee_settings.h"

#include <string>

#include "core/props.h"

namespace snell {

MneeSettings MneeSettings::from_props(const Props& p) {
    MneeSettings s;
    s.max_vertices = int(p.get_int("max_vertices", s.max_vertices));
    s.ignore_occluders = p.get_bool("ignore_occluders", s.ignore_occluders);
    s.cull_margin = p.get_float("cull_margin", s.cull_margin);
    s.biased = p.get_bool("biased", s.biased);
    s.spectral_walks = p.get_bool("spectral_walks", s.spectral_walks);
    s.walk = WalkSettings::from_props(p);
    if (s.biased && !p.has("stall_window")) s.walk.stall_window = kBiasedStallWindow;
    s.max_geometry = p.get_float("max_geometry", s.max_geometry);
    s.seeding = p.get_choice("seeding", s.seeding,
                             {{"straight", MneeSeeding::Straight},
                              {"surface", MneeSeeding::Surface},
                              {"straight+surface", MneeSeeding::StraightAndSurface}});
    // The default, in the biased mode too, is `unbiased` with both kinds of seeds: the best
    // measured at equal time (docs/experiments.md, "Caustic gallery"). `solutions=one` is the
    // paper's, as is `seeding=straight` alone.
    const MneeSolutions default_solutions =
        p.has("seeding") && s.seeding != MneeSeeding::StraightAndSurface ? MneeSolutions::One : MneeSolutions::Unbiased;
    s.solutions = p.get_choice("solutions", default_solutions,
                               {{"one", MneeSolutions::One},
                                {"all", MneeSolutions::All},
                                {"unbiased", MneeSolutions::Unbiased},
                                {"fallback", MneeSolutions::Fallback},
                                {"keyed", MneeSolutions::Keyed}});
    // The estimators of several solutions walk both kinds of seeds unless told otherwise
    // (fallback: surface seeds where the straight one is blocked).
    if (s.solutions != MneeSolutions::One && !p.has("seeding")) s.seeding = MneeSeeding::StraightAndSurface;
    if (s.solutions == MneeSolutions::Fallback && s.seeding != MneeSeeding::StraightAndSurface)
        p.raise_param("seeding", "solutions=fallback takes seeding=straight+surface");
    // trials: surface seeds per caster for `all`; the first round M of `unbiased` (M = 1 is
    // SMS's 1 / p estimate; docs/mnee.md measures larger rounds).
    // `keyed` walks every one, and replays them in its density: kKeyedTrials.
    int default_trials = s.trials;
    if (s.solutions == MneeSolutions::Unbiased || s.solutions == MneeSolutions::Fallback) default_trials = 1;
    if (s.solutions == MneeSolutions::Keyed) default_trials = kKeyedTrials;
    s.trials = int(p.get_int("trials", default_trials));
    if (s.trials < 1) p.raise_param("trials", "trials must be >= 1");
    s.max_trials = int(p.get_int("max_trials", s.max_trials));
    if (s.max_trials < 1) p.raise_param("max_trials", "max_trials must be >= 1");
    // The paper's estimator counts the straight seed's solution alone; every other pairing
    // would silently drop the solutions its seeds do not reach.
    if (s.solutions == MneeSolutions::One && s.seeding != MneeSeeding::Straight)
        p.raise_param("seeding", "solutions=one takes the straight seed only; use solutions=all with surface seeds");
    if (s.solutions != MneeSolutions::One && s.seeding == MneeSeeding::Straight)
        p.raise_param("solutions", "solutions=" + p.get_string("solutions") +
                                       " needs surface seeds: seeding=surface or straight+surface");
    s.surface_side =
        p.get_choice("surface_side", s.surface_side,
                     {{"receiver", SurfaceSide::Receiver}, {"light", SurfaceSide::Light}, {"both", SurfaceSide::Both}});
    // `keyed` counts what its trials find once, so it wants them diverse: single random seeds
    // (the best of several goes to the largest basin again and again; docs/mnee.md).
    s.seed_candidates = int(p.get_int("seed_candidates", s.solutions == MneeSolutions::Keyed ? 1 : s.seed_candidates));
    if (s.seed_candidates < 1 || s.seed_candidates > 1024)
        p.raise_param("seed_candidates", "seed_candidates must lie in [1, 1024]");
    s.reflections = p.get_bool("reflections", s.reflections);
    // The paper's estimator stays the paper's: it connects through refraction alone.
    s.exterior_reflections =
        p.get_float("exterior_reflections", s.solutions != MneeSolutions::One ? kDefaultExteriorReflections : 0.0);
    if (!(s.exterior_reflections >= 0 && s.exterior_reflections <= 1))
        p.raise_param("exterior_reflections", "exterior_reflections (a probability) must lie in [0, 1]");
    // `all` counts each solution once (no 1 / p) and keeps surface_weight 1.
    const bool both_seeds = (s.solutions == MneeSolutions::Unbiased || s.solutions == MneeSolutions::All) &&
                            s.seeding == MneeSeeding::StraightAndSurface;
    // The biased mode keeps SMS's weighting (1): its outlier rule drops the BSDF-sampled paths
    // MNEE's density gives 0, and with c < 1 that is every path beside a straight walk that did
    // not converge (docs/experiments.md, "The biased mode keeps the caustic").
    s.surface_weight =
        p.get_float("surface_weight",
                    both_seeds && s.solutions == MneeSolutions::Unbiased && !s.biased ? kDefaultSurfaceWeight : 1.0);
    if (!(s.surface_weight > 0 && s.surface_weight <= 1))
        p.raise_param("surface_weight", "surface_weight must lie in (0, 1]");
    if (p.has("surface_weight") && !both_seeds)
        p.raise_param("surface_weight",
                      "surface_weight weighs the surface seeds' solutions against the straight seed's: it needs "
                      "solutions=all or unbiased with seeding=straight+surface");
    s.failed_walk_weight = p.get_float("failed_walk_weight", s.failed_walk_weight);
    if (!(s.failed_walk_weight >= 0 && s.failed_walk_weight <= 1))
        p.raise_param("failed_walk_weight", "failed_walk_weight must lie in [0, 1]");
    if (p.has("failed_walk_weight") && !(both_seeds && s.surface_weight < 1))
        p.raise_param("failed_walk_weight",
                      "failed_walk_weight weighs the surface solutions where the straight walk fails, apart from "
                      "surface_weight's: it needs solutions=all or unbiased, seeding=straight+surface and "
                      "surface_weight < 1");
    if (s.reflections && s.solutions == MneeSolutions::One)
        p.raise_param("reflections", "reflections need the surface seeds of solutions=all or unbiased");
    if (s.max_vertices < 1 || s.max_vertices > kMaxChainVertices)
        p.raise_param("max_vertices", "max_vertices must lie in [1, " + std::to_string(kMaxChainVertices) + "]");
    if (!(s.cull_margin >= 0)) p.raise_param("cull_margin", "cull_margin must be >= 0");
    if (!(s.max_geometry >= 0)) p.raise_param("max_geometry", "max_geometry must be >= 0 (0: no clamp)");
    s.connect_probability = p.get_float("connect_probability", s.connect_probability);
    if (!(s.connect_probability > 0 && s.connect_probability <= 1))
        p.raise_param("connect_probability", "connect_probability must lie in (0, 1]");
    // The allocation is learned unless q is given, or the outlier rule of the biased mode needs
    // every region's walks (issue 26; docs/experiments.md, "Where the walks pay").
    // The paper's estimator (solutions=one) walks everywhere unless told to learn.
    // `keyed` walks everywhere too: the learned q made its ball caustic noisier
    // (docs/experiments.md, "Keyed trials").
    const bool learned_default = !s.biased && !p.has("connect_probability") && s.solutions != MneeSolutions::One &&
                                 s.solutions != MneeSolutions::Keyed;
    s.learned_allocation = p.get_choice("allocation", learned_default, {{"learned", true}, {"fixed", false}});
    if (s.learned_allocation && s.biased)
        p.raise_param("allocation",
                      "allocation=learned may leave a region without walks, and the biased mode's outlier rule then "
                      "drops its refracted light: use allocation=fixed");
    s.trial_allocation = p.get_choice("trial_allocation", s.trial_allocation,
                                      {{"learned", TrialAllocation::Learned},
                                       {"always", TrialAllocation::Always},
                                       {"never", TrialAllocation::Never}});
    if (p.has("trial_allocation") && !(s.learned_allocation && s.splits_surface_solutions()))
        p.raise_param("trial_allocation",
                      "trial_allocation needs allocation=learned and surface solutions weighed apart "
                      "(solutions=unbiased or all, seeding=straight+surface, surface_weight < 1)");
    s.failed_walk_trials =
        p.get_choice("failed_walk_trials", s.failed_walk_trials, {{"learned", true}, {"never", false}});
    if (p.has("failed_walk_trials") && !(s.learned_allocation && s.splits_surface_solutions() &&
                                         s.trial_allocation == TrialAllocation::Learned && !(s.failed_walk_weight > 0)))
        p.raise_param("failed_walk_trials",
                      "failed_walk_trials lets each region choose the trials beside failed straight walks: it needs "
                      "allocation=learned, trial_allocation=learned, surface solutions weighed apart and "
                      "failed_walk_weight 0 (which runs them in every region)");
    s.work_price =
        p.get_choice("work_price", s.work_price, {{"image", WorkPrice::Image}, {"region", WorkPrice::Region}});
    if (p.has("work_price") && !s.learned_allocation)
        p.raise_param("work_price", "work_price needs allocation=learned");
    s.mis_cutoff = p.get_float("mis_cutoff", s.solutions != MneeSolutions::One && !s.biased ? kDefaultMisCutoff : 0.0);
    if (!(s.mis_cutoff >= 0 && s.mis_cutoff < kInfinity))
        p.raise_param("mis_cutoff", "mis_cutoff must be >= 0 (0: off)");
    if (s.mis_cutoff > 0 && s.biased)
        p.raise_param("mis_cutoff",
                      "the biased mode drops the paths MNEE's density gives 0, so it needs that density for every "
                      "path: mis_cutoff must be 0 there");
    s.pilot_spp = int(p.get_int("pilot_spp", s.pilot_spp));
    if (s.pilot_spp < 1 || s.pilot_spp > 4096) p.raise_param("pilot_spp", "pilot_spp must lie in [1, 4096]");
    s.allocation_block = int(p.get_int("allocation_block", s.allocation_block));
    if (s.allocation_block < 1 || s.allocation_block > 4096)
        p.raise_param("allocation_block", "allocation_block must lie in [1, 4096]");
    return s;
}

bool MneeSettings::splits_surface_solutions() const {
    return (solutions == MneeSolutions::Unbiased || solutions == MneeSolutions::All) &&
           seeding == MneeSeeding::StraightAndSurface && surface_weight < 1;
}

}  // namespace snell
