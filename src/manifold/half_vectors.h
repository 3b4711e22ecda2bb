#pragma once
// Alg. 1 line 3 (Sec. 3.2): the target half vectors of a chain's rough vertices. Each vertex
// *slot* i of a chain (its position in x_1..x_k) owns one uniform pair u_i, and h_i is read from
// u_i in the vertex's constraint frame (s, t, n), not in its shading frame. The targets then
// depend on the shape sequence and the pairs alone, not on where a seed landed, so several walks
// from different seeds (issue 10: every solution per shading point) solve for the same H.
#include <array>
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
    /// The pair of slot i (0 <= i < kMaxSlots).
    Vec2 slot(int i);

private:
    Sampler* m_sampler;
    std::array<Vec2, kMaxSlots> m_u{};
    int m_drawn = 0;
};

/// The target of vertex v in slot i: (0, 0) if specular, else the (s, t) part of sample_m(u_i).
Vec2 target_half_vector(const ManifoldVertex& v, int i, HalfVectorDraws& draws);

/// Sets every vertex's h_target: (0, 0) for specular vertices; for rough ones the tangential part
/// (m.s, m.t) of m = sample_m(u_i), D(m) cos(theta_m) sampled in the constraint frame. The
/// global distribution, not visible normals (Sec. 3.2): the incoming direction changes while the
/// walk moves the path. For isotropic roughness the distribution of h is the same in any frame
/// around n, so p_dH(h) = D(h) as before.
void set_half_vectors(std::vector<ManifoldVertex>& chain, HalfVectorDraws& draws);

}  // namespace snell
