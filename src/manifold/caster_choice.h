#pragma once
// Which caster a surface trial draws its seed on. One trial is one caster chosen at random, then
// a seed on it, so a connection runs `trials` trials however much glass the scene holds, and the
// 1 / p estimate (EstimatorBase::count_trials_to_refind) repeats the same choice: p(Y) is then
// the probability that one trial, caster choice included, finds Y, and the count stays unbiased.
// With a single caster nothing is drawn, so such scenes see the trials they always did.
#include <vector>

#include "core/rng.h"
#include "core/vector.h"

namespace snell {

class Scene;
class Shape;

class CasterChoice {
public:
    /// The scene's manifold casters at `lambda` (Scene::manifold_casters), or `only` alone. Each
    /// is chosen with probability mixing the solid angle of its bounding sphere seen from x_b
    /// (kSolidAngleShare) with a uniform share, so that every caster keeps p > 0 and a small,
    /// far one does not take the trials of the glass around x_b.
    CasterChoice(const Scene& scene, const Vec3& xb, double lambda, const Shape* only = nullptr);

    bool empty() const { return !m_first; }
    size_t size() const { return m_casters.empty() ? (m_first ? 1 : 0) : m_casters.size(); }
    /// The caster for the next trial; draws from `rng` only where there are several.
    const Shape& pick(PCG32& rng) const;
    /// The probability pick() returns caster number i.
    double probability(size_t i) const;
    /// The probability pick() returns `caster` (0 for a shape not in the choice).
    double probability_of(const Shape& caster) const;
    const Shape& operator[](size_t i) const { return m_casters.empty() ? *m_first : *m_casters[i]; }

    static constexpr double kSolidAngleShare = 0.9;

private:
    // One caster (most scenes, and every choice beside a clear seed) needs no allocation: the
    // trials of each connection build a choice.
    const Shape* m_first = nullptr;
    std::vector<const Shape*> m_casters;  ///< every caster, where there are several
    std::vector<double> m_cdf;            ///< m_cdf[i]: the probability of casters 0..i
};

}  // namespace snell
