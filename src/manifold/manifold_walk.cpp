#include "manifold/manifold_walk.h"

#include "manifold/half_vectors.h"

#include <array>
#include <cmath>

#include "core/props.h"
#include "geometry/shape.h"
#include "manifold/walk_counters.h"
#include "scene/scene.h"

namespace snell {

namespace {
// Largest step, as a fraction of a vertex's local length scale, taken in one iteration.
constexpr double kTrustFraction = 0.5;

// One thread's storage for its walks: a walk runs a few iterations, and a render millions of
// walks, so heap allocations per walk showed in a profile of the pool (docs/experiments.md,
// nineteenth measurement).
// A walk never starts another on its thread before it ends, so one set per thread suffices.
struct WalkWorkspace {
    BlockTridiagonal m;
    BlockLU lu;
    std::vector<Vec2> c, dx;
    std::vector<ManifoldVertex> proposal;
};
thread_local WalkWorkspace t_walk;
}  // namespace

bool build_constraints(const Vec3& x_b, const std::vector<ManifoldVertex>& chain, const TangentBasis& x_c,
                       BlockTridiagonal* m, std::vector<Vec2>* c) {
    const size_t k = chain.size();
    m->resize(k);
    c->resize(k);
    for (size_t i = 0; i < k; ++i) {
        // x_b's basis is never used (no A block in the first row).
        const TangentBasis prev = i == 0 ? TangentBasis{x_b, Vec3(), Vec3()}
                                         : TangentBasis{chain[i - 1].p, chain[i - 1].dp_ds, chain[i - 1].dp_dt};
        const TangentBasis next =
            i + 1 == k ? x_c : TangentBasis{chain[i + 1].p, chain[i + 1].dp_ds, chain[i + 1].dp_dt};
        const ConstraintBlocks b = half_vector_constraint(prev, chain[i], next);
        if (!b.valid) return false;
        m->A[i] = b.A;
        m->B[i] = b.B;
        m->C[i] = b.C;
        (*c)[i] = b.value;
    }
    return true;
}

double constraint_error(const Vec3& x_b, const std::vector<ManifoldVertex>& chain, const Vec3& x_c) {
    double err = 0;
    for (size_t i = 0; i < chain.size(); ++i) {
        const Vec3& prev = i == 0 ? x_b : chain[i - 1].p;
        const Vec3& next = i + 1 == chain.size() ? x_c : chain[i + 1].p;
        const Vec2 c = half_vector_constraint_value(prev, chain[i], next);
        err = std::max(err, std::max(std::abs(c.x), std::abs(c.y)));
    }
    return std::isfinite(err) ? err : kInfinity;
}

bool project_vertex(const Scene* scene, const ManifoldVertex& from, const Vec3& prev_p, const Vec3& displaced,
                    Projection mode, ManifoldVertex* out) {
    // The hit is written into the vertex it builds: a walk projects every vertex at every
    // iteration, and copying a hit record and a vertex each time showed in a profile of the
    // ball on a plane (docs/experiments.md, twenty-seventh measurement).
    SurfaceInteraction& si = out->si;
    const double step = length(displaced - from.p);
    if (mode == Projection::ClosestPoint || !scene) {
        // Search radius: the step itself plus a margin; a projection further away than the
        // step cannot be the continuation of this vertex.
        if (!from.shape->closest_point_near(from.si, displaced, 2.0 * step + 1e-9 * (length(displaced) + 1.0), &si))
            return false;
    } else {
        // Cast from the previous vertex through the displaced point; accept only hits on the
        // same shape near the displaced point.
        Ray r{prev_p, normalize(displaced - prev_p), 0.0, kInfinity};
        r.tmin = Scene::ray_tmin(prev_p, length(displaced - prev_p));
        if (!scene->intersect(r, &si) || si.shape != from.shape) return false;
        if (length(si.p - displaced) > 4.0 * step + r.tmin) return false;
    }
    ManifoldVertex& v = *out;
    v.derive_from_si(from.eta);
    v.reflect = from.reflect;
    v.bsdf = from.bsdf;
    v.unit_slope = from.unit_slope;
    v.has_unit_slope = from.has_unit_slope;
    // The target is re-read with the roughness at the new point (half_vectors.h).
    v.h_target = from.has_unit_slope ? target_from_unit_slope(v, from.unit_slope) : from.h_target;
    return true;
}

WalkResult manifold_walk(const Scene* scene, const Vec3& x_b, std::vector<ManifoldVertex>& chain,
                         const TangentBasis& x_c, const WalkSettings& st) {
    WalkResult res;
    BlockTridiagonal& m = t_walk.m;
    std::vector<Vec2>& c = t_walk.c;
    std::vector<Vec2>& dx = t_walk.dx;
    // Every entry is written by its projection before it is read (a failed projection rejects
    // the step), so stale entries from an earlier walk are harmless.
    std::vector<ManifoldVertex>& proposal = t_walk.proposal;
    proposal.resize(chain.size());
    double err = constraint_error(x_b, chain, x_c.p);
    double beta = 1.0;  // step size
    const double beta_max = st.allow_error_increase ? 2.0 : 1.0;
    // The error before each iteration, for the progress test (a ring of stall_window entries).
    std::array<double, kMaxStallWindow> history{};
    const int window = std::min(st.stall_window, kMaxStallWindow);
    bool have_dx = false;  // dx holds the current chain's (trust-limited) Newton step
    for (res.iterations = 0; res.iterations < st.max_iterations; ++res.iterations) {
        if (err < st.threshold) {
            res.outcome = WalkOutcome::Converged;
            res.error = err;
            return res;
        }
        if (window > 0) {
            double& then = history[size_t(res.iterations % window)];
            if (res.iterations >= window && !(err < st.stall_ratio * then)) {
                res.outcome = WalkOutcome::Stalled;
                res.error = err;
                return res;
            }
            then = err;
        }
        // Predictor: first-order offsets that would zero the constraints. A rejected step leaves
        // the chain as it was, so its offsets stand and only beta shrinks: they are computed
        // again only after the chain moved.
        if (!have_dx) {
            if (!build_constraints(x_b, chain, x_c, &m, &c) || !solve_matrix_h_to_x(m, c, &dx, nullptr, &t_walk.lu)) {
                res.outcome = WalkOutcome::SingularMatrix;
                res.error = err;
                return res;
            }
            // Trust region: no vertex may move further than a fraction of its local length
            // scale (distance to its neighbours, radius of curvature) in one step; far from the
            // solution the linearisation is poor and unbounded steps wrap around curved shapes.
            // All lengths are the scene's own, so this is scale-free.
            double limit = 1.0;
            for (size_t i = 0; i < chain.size(); ++i) {
                const Vec3& prev = i == 0 ? x_b : chain[i - 1].p;
                const Vec3& next = i + 1 == chain.size() ? x_c.p : chain[i + 1].p;
                const double curvature = std::max(length(chain[i].dn_ds), length(chain[i].dn_dt));
                double scale = std::min(length(prev - chain[i].p), length(next - chain[i].p));
                if (curvature > 0) scale = std::min(scale, 1.0 / curvature);
                const double step = length(dx[i]);
                if (step > 0) limit = std::min(limit, kTrustFraction * scale / step);
            }
            for (Vec2& d : dx) d = d * limit;
            have_dx = true;
        }

        // Corrector: project every displaced vertex back onto its own shape.
        walk_counters::walk_vertex_steps += chain.size();
        bool projected = true;
        for (size_t i = 0; i < chain.size() && projected; ++i) {
            const Vec3 prev = i == 0 ? x_b : proposal[i - 1].p;
            projected =
                project_vertex(scene, chain[i], prev, chain[i].offset(dx[i] * beta), st.projection, &proposal[i]);
        }
        const double new_err = projected ? constraint_error(x_b, proposal, x_c.p) : kInfinity;
        if (new_err < err || (st.allow_error_increase && std::isfinite(new_err))) {
            // Accept. Newton's full step is right once the error falls fast (quadratic phase);
            // variant B over-relaxes (step > 1) only while progress is slow, to jump across
            // the local minima of Fig. 4, and halves the step after an accepted increase.
            if (new_err >= err)
                beta *= 0.5;
            else if (new_err < 0.5 * err)
                beta = std::min(1.0, beta * 2.0);
            else
                beta = std::min(beta_max, beta * 2.0);
            chain.swap(proposal);
            err = new_err;
            have_dx = false;
        } else {
            // Variant A: revert to X^i and halve the step.
            beta *= 0.5;
            if (beta < st.min_step) {
                res.outcome = projected ? WalkOutcome::Stalled : WalkOutcome::ProjectionFailed;
                res.error = err;
                return res;
            }
        }
    }
    res.error = err;
    res.outcome = err < st.threshold ? WalkOutcome::Converged : WalkOutcome::MaxIterations;
    return res;
}

WalkSettings WalkSettings::from_props(const Props& p) {
    WalkSettings s;
    s.max_iterations = int(p.get_int("max_iterations", s.max_iterations));
    s.threshold = p.get_float("threshold", s.threshold);
    s.allow_error_increase = p.get_bool("allow_error_increase", s.allow_error_increase);
    s.min_step = p.get_float("min_step", s.min_step);
    s.stall_window = int(p.get_int("stall_window", s.stall_window));
    s.stall_ratio = p.get_float("stall_ratio", s.stall_ratio);
    s.projection = p.get_choice("projection", s.projection,
                                {{"closest_point", Projection::ClosestPoint}, {"raycast", Projection::RayCast}});
    if (s.max_iterations < 1) p.raise_param("max_iterations", "max_iterations must be >= 1");
    if (!(s.threshold > 0)) p.raise_param("threshold", "threshold must be > 0");
    if (!(s.min_step > 0 && s.min_step <= 1)) p.raise_param("min_step", "min_step must lie in (0, 1]");
    if (s.stall_window < 0 || s.stall_window > kMaxStallWindow)
        p.raise_param("stall_window", "stall_window must lie in [0, " + std::to_string(kMaxStallWindow) + "]");
    if (!(s.stall_ratio > 0 && s.stall_ratio <= 1)) p.raise_param("stall_ratio", "stall_ratio must lie in (0, 1]");
    return s;
}

}  // namespace snell
