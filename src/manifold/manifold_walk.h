#pragma once
// The manifold walk (paper Sec. 3.4; Jakob 2013): a predictor/corrector Newton solver that
// moves the vertices of a chain on their surfaces until every half-vector constraint holds.
// Predictor: solve_matrix_h_to_x turns the constraint error into tangent offsets. Corrector:
// project each displaced vertex back onto the shape it started on (closest point, or a ray
// cast as an option to compare).
#include <cstdint>
#include <vector>

#include "manifold/block_tridiagonal.h"
#include "manifold/constraints.h"
#include "manifold/manifold_vertex.h"

namespace snell {

class Scene;
class Props;

enum class Projection {
    ClosestPoint,  ///< closest point on the same shape (the paper's choice: robust at grazing angles)
    RayCast,       ///< ray from the previous vertex through the displaced point, same shape only
};

/// The longest window of WalkSettings' progress test.
inline constexpr int kMaxStallWindow = 16;

struct WalkSettings {
    int max_iterations = 15;            ///< paper Sec. 3.4: 15 works well in practice
    double threshold = 1e-6;            ///< convergence: max over vertices of |c_i| (dimensionless)
    bool allow_error_increase = false;  ///< Table 1 variant B: over-relaxed, error may grow
    Projection projection = Projection::ClosestPoint;
    /// A rejected step halves the step size beta (Sec. 3.4); once beta falls below this the walk
    /// has stalled and ends (WalkOutcome::Stalled). A walk that needs a tenth of its Newton step
    /// to make progress rarely converges within max_iterations, and failing walks dominate MNEE's
    /// time in a caustic (issue 10): 0.1 gives up on them early. The default keeps the paper's
    /// walks (1e-4 was the floor before the parameter existed).
    double min_step = 1e-4;
    /// Progress test: a walk whose error has not fallen below `stall_ratio` times its value
    /// `stall_window` iterations earlier (rejected steps count) ends as Stalled. Where no
    /// solution exists (most of a glass sphere's shadow outside its caustic) the error settles
    /// on a plateau and the walk would run to max_iterations; walks that converge fall by large
    /// factors per iteration (what 4 and 0.7 save and give up: docs/mnee.md). Any such rule
    /// keeps MNEE unbiased: Alg. 2 walks by the same rule, and the multi-solution estimators
    /// count what their trials reach. stall_window 0 turns the test off.
    int stall_window = 0;
    double stall_ratio = 0.7;

    /// The walk's scene parameters (max_iterations, threshold, allow_error_increase, min_step,
    /// stall_window, stall_ratio, projection; docs/integrators.md), checked.
    static WalkSettings from_props(const Props& props);
};

enum class WalkOutcome : uint8_t {
    Converged,
    MaxIterations,     ///< did not reach the threshold within max_iterations
    SingularMatrix,    ///< a pivot of the constraint matrix vanished
    ProjectionFailed,  ///< a vertex could not be brought back onto its shape
    Stalled,           ///< beta fell below min_step, or the error stopped falling (progress test)
};

struct WalkResult {
    WalkOutcome outcome = WalkOutcome::MaxIterations;
    int iterations = 0;
    double error = 0;  ///< final max |c_i|
};

/// Runs the walk on `chain` (in: seed vertices with their h_target set; out: the solution)
/// between the fixed endpoints x_b and x_c.
WalkResult manifold_walk(const Scene* scene, const Vec3& x_b, std::vector<ManifoldVertex>& chain,
                         const TangentBasis& x_c, const WalkSettings& settings);

/// Constraint derivative matrix and constraint values of a chain (blocks per Eq. 4).
/// Returns false for degenerate configurations.
bool build_constraints(const Vec3& x_b, const std::vector<ManifoldVertex>& chain, const TangentBasis& x_c,
                       BlockTridiagonal* m, std::vector<Vec2>* c);

/// Max |c_i| over the chain.
double constraint_error(const Vec3& x_b, const std::vector<ManifoldVertex>& chain, const Vec3& x_c);

/// Projects a displaced vertex back onto its shape, keeping its BSDF data (eta, h_target).
/// `*out`, which must not be `from`, is built in place; where the projection fails it is left
/// half written.
bool project_vertex(const Scene* scene, const ManifoldVertex& from, const Vec3& prev_p, const Vec3& displaced,
                    Projection mode, ManifoldVertex* out);

}  // namespace snell
