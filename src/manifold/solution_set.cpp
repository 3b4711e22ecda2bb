#include "manifold/solution_set.h"

#include <algorithm>

namespace snell {

void polish_solution(const Scene* scene, const Vec3& xb, std::vector<ManifoldVertex>& chain, const TangentBasis& xc,
                     const WalkSettings& walk) {
    WalkSettings polish = walk;
    polish.threshold = 1e-13;
    polish.max_iterations = 6;
    polish.allow_error_increase = false;
    manifold_walk(scene, xb, chain, xc, polish);
}

bool same_solution(const Vec3& xb, const std::vector<ManifoldVertex>& a, const std::vector<ManifoldVertex>& b,
                   const Vec3& xc) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        if (a[i].shape != b[i].shape) return false;
        const Vec3& prev = i == 0 ? xb : a[i - 1].p;
        const Vec3& next = i + 1 == a.size() ? xc : a[i + 1].p;
        const double scale = std::min(length(a[i].p - prev), length(next - a[i].p));
        if (!(length(a[i].p - b[i].p) <= kSameSolutionTolerance * scale)) return false;
    }
    return true;
}

}  // namespace snell
