#include "manifold/estimator_base.h"

#include <algorithm>

#include "geometry/shape.h"
#include "manifold/exterior_reflection.h"
#include "manifold/mis_cutoff.h"
#include "manifold/seed_path.h"
#include "manifold/surface_seed.h"
#include "manifold/walk_counters.h"
#include "scene/caster_sampling.h"

namespace snell {

namespace {

// Whether `set` holds, from index `from` on and for wavelength slot `slot`, the solution `chain`.
bool holds_solution(const SolutionSet& set, size_t from, int slot, const Vec3& xb,
                    const std::vector<ManifoldVertex>& chain, const Vec3& xc) {
    for (size_t i = from; i < set.solutions.size(); ++i)
        if (set.solutions[i].slot == slot && same_solution(xb, chain, set.solutions[i].chain, xc)) return true;
    return false;
}

}  // namespace

bool passes_emitter(const SurfaceInteraction* chain, int k) {
    return std::any_of(chain, chain + std::max(k, 0),
                       [](const SurfaceInteraction& v) { return v.emitter() != nullptr; });
}

PCG32 EstimatorBase::trial_stream(Sampler& sampler) { return PCG32(uint64_t(sampler.next_1d() * 0x1p53), 0x5eed); }

int EstimatorBase::add_solution(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                double pmf, const LightPoint& lp, std::vector<ManifoldVertex> chain,
                                HalfVectorDraws& draws, int max_k, bool from_surface, bool dedupe, SolutionSet& out,
                                bool* walk_converged) const {
    if (max_k >= 0 && int(chain.size()) > max_k) return -1;
    const MneeConnection c =
        mnee_connect(*m_scene, *m_settings, *q.xb, *q.bsdf_b, ctx, q.media, light, pmf, lp, chain, draws);
    if (walk_converged) *walk_converged = c.walk_converged;
    if (c.outcome != MneeOutcome::Success) return -1;
    const Vec3 first_vertex = chain[0].p;
    if (dedupe) {
        // Distinct paths only: compare polished chains (solution_set.h).
        std::vector<ManifoldVertex> polished = chain;
        polish_solution(m_scene, q.xb->p, polished, light_point_basis(lp.p, lp.n, normalize(lp.p - q.xb->p)),
                        m_settings->walk);
        for (const ManifoldSolution& other : out.solutions)
            if (other.slot == slot && same_solution(q.xb->p, polished, other.chain, lp.p)) return -1;
        chain = std::move(polished);
    }
    ManifoldSolution s;
    s.chain = std::move(chain);
    s.slot = slot;
    if (slot >= 0) {
        s.value[slot] = c.value[0];
    } else {
        // A dispersive chain solved for the hero alone (no per-wavelength walks): scale the hero
        // once, unless the path's throughput already did.
        s.value = c.hero_only && !q.hero_only ? q.ctx.wl.hero_only(c.value) : c.value;
    }
    s.density = c.pdf_mnee;
    s.bound = c.pdf_mnee;
    s.pdf_bsdf = c.pdf_bsdf;
    s.pdf_nee_last = c.pdf_nee_last;
    // The path samples x_b's direction with its own density (caster sampling): it replaces
    // BSDF sampling's in both (the direction the walk solved for, before any polish).
    if (q.directions && c.pdf_xb_direction > 0) {
        const Vec3 o_b = normalize(first_vertex - q.xb->p);
        const double p =
            q.directions->pdf(*q.xb, *q.bsdf_b, ctx.at(*q.xb), q.xb->to_local(q.xb->wo), q.xb->to_local(o_b));
        s.pdf_bsdf *= p / c.pdf_xb_direction;
        s.pdf_nee_last *= p / c.pdf_xb_direction;
    }
    s.from_surface = from_surface;
    out.solutions.push_back(std::move(s));
    return int(out.solutions.size()) - 1;
}

bool EstimatorBase::surface_trial(const ManifoldQuery& q, const BSDFContext& ctx, const CasterChoice& casters,
                                  PCG32& rng, const LightPoint& lp, HalfVectorDraws& draws, int max_k,
                                  std::vector<ManifoldVertex>* chain, bool trace_smooth) const {
    const MneeSettings& st = *m_settings;
    // Seeds from x_b: the best of `seed_candidates` traced seeds, the one whose last ray passes
    // closest to the light point (tracing is cheap, walks are not). Any fixed procedure is a
    // valid trial: the 1 / p estimate repeats the same one, and every solution keeps p > 0 (its
    // neighbourhood passes closest with positive probability).
    if (st.surface_side == SurfaceSide::Receiver) {
        double best = kInfinity;
        std::vector<ManifoldVertex> candidate;
        for (int c = 0; c < st.seed_candidates; ++c) {
            const Shape& caster = casters.pick(rng);
            const Vec2 u(rng.next_double(), rng.next_double());
            Vec3 exit_dir;
            if (trace_surface_seed(*m_scene, *q.xb, caster, u, ctx.hero(), st, trace_smooth ? nullptr : &draws,
                                   &candidate, &rng, &exit_dir) != SurfaceSeedEnd::Ok)
                continue;
            if (max_k >= 0 && int(candidate.size()) > max_k) continue;
            const double miss = st.seed_candidates > 1 ? seed_miss(candidate, exit_dir, lp.p) : 0.0;
            if (miss < best) {
                best = miss;
                std::swap(*chain, candidate);
            }
        }
        if (best == kInfinity) return false;
    } else {
        const Shape& caster = casters.pick(rng);
        const Vec2 u(rng.next_double(), rng.next_double());
        // With both, u.x picks the side and is stretched back to [0, 1).
        SurfaceSide side = st.surface_side;
        Vec2 v = u;
        if (side == SurfaceSide::Both) {
            side = u.x < 0.5 ? SurfaceSide::Receiver : SurfaceSide::Light;
            v.x = u.x < 0.5 ? 2 * u.x : 2 * u.x - 1;
        }
        const SurfaceSeedEnd end =
            side == SurfaceSide::Receiver
                ? trace_surface_seed(*m_scene, *q.xb, caster, v, ctx.hero(), st, trace_smooth ? nullptr : &draws, chain,
                                     &rng)
                : trace_light_seed(*m_scene, lp.p, caster, v, ctx.hero(), st, draws, chain, &rng);
        if (end != SurfaceSeedEnd::Ok) return false;
        if (max_k >= 0 && int(chain->size()) > max_k) return false;
    }
    // Which solution the seed walks to is all a trial asks: no visibility rays, no measurement.
    if (mnee_walk(*m_scene, *m_settings, *q.xb, *q.bsdf_b, lp, *chain, draws, /*trial_only=*/true) !=
        MneeOutcome::Success)
        return false;
    // One reflection off the outside of glass is ExteriorReflection's path (solution_density
    // gives it 0 here): a trial that walks to it has failed.
    if (st.exterior_reflections > 0 && chain->size() == 1 && (*chain)[0].reflect &&
        ExteriorReflection::in_class(q.xb->p, (*chain)[0].si, lp.p, ctx.hero()))
        return false;
    polish_solution(m_scene, q.xb->p, *chain, light_point_basis(lp.p, lp.n, normalize(lp.p - q.xb->p)),
                    m_settings->walk);
    return true;
}

void EstimatorBase::walk_every_trial(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                     double pmf, const LightPoint& lp, const CasterChoice& casters, PCG32& rng,
                                     HalfVectorDraws& draws, int max_k, const Foreign& foreign, size_t before,
                                     SolutionSet& out) const {
    // Walk each seed to its solution first (no visibility, no measurement) and evaluate only the
    // new ones.
    for (int j = 0; j < m_settings->trials; ++j) {
        std::vector<ManifoldVertex> chain;
        if (surface_trial(q, ctx, casters, rng, lp, draws, max_k, &chain) && !foreign(chain) &&
            !holds_solution(out, before, slot, q.xb->p, chain, lp.p))
            add_solution(q, ctx, slot, light, pmf, lp, std::move(chain), draws, max_k, true, true, out);
    }
}

void EstimatorBase::count_trials_to_refind(const ManifoldQuery& q, const BSDFContext& ctx, int slot, const Light& light,
                                           double pmf, const LightPoint& lp, const CasterChoice& casters, PCG32& rng,
                                           HalfVectorDraws& draws, int max_k, const Foreign& foreign, size_t before,
                                           SolutionSet& out) const {
    const MneeSettings& st = *m_settings;
    // SMS's estimator with M = `trials` first trials. Every distinct solution Y the M trials find
    // (other than the straight seed's, counted as such) is weighted by R = ceil(N / M), N the
    // number of further independent trials up to and including the first that finds Y again. A
    // round of M trials finds Y with probability q = 1 - (1 - p(Y))^M, and R counts rounds up to
    // the first that finds Y, so R is geometric with E[R] = 1 / q: every reachable solution
    // counts once in expectation. M = 1 is SMS's 1 / p estimate; a larger M finds solutions with
    // small p(Y) in the first round more often, and once M p(Y) >> 1, R = 1 almost surely (the
    // `all` estimator, without its bias).
    std::vector<int> found;
    for (int j = 0; j < st.trials; ++j) {
        std::vector<ManifoldVertex> chain;
        if (!surface_trial(q, ctx, casters, rng, lp, draws, max_k, &chain) || foreign(chain)) continue;
        if (holds_solution(out, before, slot, q.xb->p, chain, lp.p)) continue;
        const int index = add_solution(q, ctx, slot, light, pmf, lp, std::move(chain), draws, max_k, true, true, out);
        if (index >= 0) found.push_back(index);
    }
    for (const int index : found) {
        // A solution mis_cutoff gives no MIS weight needs no 1 / p estimate: it counts 0 (it stays
        // in the set, so that another caster's trials do not add it again).
        ManifoldSolution& sol = out.solutions[size_t(index)];
        if (q.cutoff_q > 0 && mis_cut_off(sol.pdf_bsdf + sol.pdf_nee_last, q.cutoff_q * sol.bound, st.mis_cutoff)) {
            ++walk_counters::mis_cut_counts;
            sol.count = 0;
            continue;
        }
        int n = 1;
        for (; n <= st.max_trials; ++n) {
            std::vector<ManifoldVertex> again;
            if (surface_trial(q, ctx, casters, rng, lp, draws, max_k, &again) &&
                same_solution(q.xb->p, again, out.solutions[size_t(index)].chain, lp.p))
                break;
        }
        ++walk_counters::bernoulli_loops;
        walk_counters::bernoulli_trials += uint64_t(std::min(n, st.max_trials));
        if (n > st.max_trials) ++walk_counters::bernoulli_capped;
        const int trials = std::min(n, st.max_trials);
        out.solutions[size_t(index)].count = double((trials + st.trials - 1) / st.trials);
    }
}

double EstimatorBase::alg2_density(const SurfaceInteraction& xb, const BSDF& bsdf_b, const SurfaceInteraction* chain,
                                   int k, const Light& light, double pmf, const Vec3& xc, const Vec3& nc, double lambda,
                                   const StraightSeed* seed, bool* walk_converged) const {
    return mnee_pdf(*m_scene, *m_settings, xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, seed, walk_converged);
}

double EstimatorBase::every_solution_density(const SurfaceInteraction& xb, const BSDF& bsdf_b,
                                             const SurfaceInteraction* chain, int k, const Light& light, double pmf,
                                             const Vec3& xc, const Vec3& nc, double lambda,
                                             const StraightSeed* seed) const {
    return solution_density(*m_scene, *m_settings, xb, bsdf_b, chain, k, light, pmf, xc, nc, lambda, seed);
}

}  // namespace snell
