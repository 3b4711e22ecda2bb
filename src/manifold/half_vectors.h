#pragma once
// Alg. 1 line 3 (Sec. 3.2): the target half vectors of a chain's rough vertices. Each vertex
// *slot* i of a chain (its position in x_1..x_k) owns one uniform pair u_i, and h_i is read from
// u_i in the vertex's constraint frame (s, t, n), not in its shading frame. The targets then
// depend on the shape sequence and the pairs alone, not on where a seed landed, so several walks
// from different seeds (issue 10: every solution per shading point) solve for the same H.
#include <array>
#include <initializer_list>
#include <vector>

#include "core/sampler.h"
#include "manifold/manifold_vertex.h"

namespace snell {

/// The uniform pairs of the slots of one light connection, drawn from the sampler on first
/// use, in slot order (slot i is always the (i+1)-th pair drawn).
class HalfVectorDraws {
public:
    static constexpr int kMaxSlots = 16;
    explicit HalfVectorDraws(Sampler& sampler) : m_sampler(&sampler) {}
    /// Slots given as unit-roughness slopes instead of draws (slopes of a given path's half
    /// vectors, as Alg. 2 walks them); the slots past the end read slope (0, 0).
    static HalfVectorDraws of_unit_slopes(std::vector<Vec2> slopes);
    /// Slots whose uniform pairs the caller drew (from a generator of its own, so that the
    /// sampler's dimensions do not depend on whether a walk runs); slot i reads pairs[i].
    static HalfVectorDraws of_pairs(std::initializer_list<Vec2> pairs);
    /// The pair of slot i (0 <= i < kMaxSlots); drawn slots only.
    Vec2 slot(int i);
    /// Slot i as the unit-roughness slope of distribution `type` it stands for.
    Vec2 unit_slope(int i, int type);

private:
    HalfVectorDraws() = default;
    Sampler* m_sampler = nullptr;
    std::vector<Vec2> m_slopes;  ///< given slopes (m_sampler null, m_given_pairs false)
    bool m_given_pairs = false;  ///< of_pairs: m_u holds the pairs (m_sampler null)
    std::array<Vec2, kMaxSlots> m_u{};
    int m_drawn = 0;
};

/// The target of vertex v in slot i: (0, 0) if specular, else the (s, t) part of sample_m(u_i)
/// with the distribution where v lies. Records the draw in v.unit_slope.
///
/// Spatially varying roughness (a texture): Beckmann and GGX are stretch-invariant (Heitz 2014),
/// so sample_m(u) with (alpha_u, alpha_v) is the unit-roughness sample's slope stretched by
/// (alpha_u, alpha_v). The walk keeps the unit slope and re-stretches it with the roughness at
/// each projected point; a converged vertex x then has h = stretch(slope, alpha(x)), whose
/// density is D at x. Exact where alpha is locally constant (checkerboards, nearest texels);
/// bilinear roughness adds a term in grad alpha that is left out (docs/scene-format.md).
Vec2 target_half_vector(ManifoldVertex& v, int i, HalfVectorDraws& draws);
/// h_target for a unit-roughness slope at v's point (v rough).
Vec2 target_from_unit_slope(const ManifoldVertex& v, const Vec2& unit_slope);
/// The inverse: the unit slope whose target at v is the tangential half vector h (Alg. 2 walks
/// a given path's half vectors the way the estimator would have drawn them).
Vec2 unit_slope_of(const ManifoldVertex& v, const Vec2& h);

/// Sets every vertex's h_target: (0, 0) for specular vertices; for rough ones the tangential part
/// (m.s, m.t) of m = sample_m(u_i), D(m) cos(theta_m) sampled in the constraint frame. The
/// global distribution, not visible normals (Sec. 3.2): the incoming direction changes while the
/// walk moves the path. For isotropic roughness the distribution of h is the same in any frame
/// around n, so p_dH(h) = D(h) as before.
void set_half_vectors(std::vector<ManifoldVertex>& chain, HalfVectorDraws& draws);

}  // namespace snell
