#pragma once
// HSLT's mutations (Kaplanyan, Hanika & Dachsbacher 2014, Sec. 5): perturbations of a path in
// half-vector space, each solved by the manifold walk (paper Sec. 3.4) with the path's ends
// held, and checked to be reversible (the walk back from the proposal with the old half vectors
// must return to the current path), so that the proposal is a bijection between the two and the
// Metropolis-Hastings ratio is the ratio of the densities in the perturbed coordinates.
//
// - Half vectors: every non-specular vertex's half vector moves by a 2D Gaussian (specular ones
//   stay at 0), x_0 and x_k fixed. Ratio F(y) / F(x) times the Gaussians' ratio (their widths
//   depend on the vertices' roughness).
// - Lens: the film position moves by a 2D Gaussian (pixels), x_1 is the new camera ray's hit on
//   the same shape, and x_2 .. x_{k-1} keep their half vectors. Ratio of hslt_lens_density.
//   Only where x_1 is not specular.
// - Light: x_k moves on a spherical light by a Gaussian in its tangent plane projected radially
//   (a density of the angle between the two points alone, so symmetric), and x_1 .. x_{k-1}
//   keep their half vectors. Ratio F(y) / F(x).
#include "core/rng.h"
#include "integrators/hslt/hslt_path.h"
#include "manifold/manifold_walk.h"

namespace snell {

struct HsltMutationSettings {
    /// (perturbation_width) standard deviation of a diffuse vertex's half-vector perturbation,
    /// in tangential half-vector units; a rough vertex uses its roughness times rough_width
    /// when smaller.
    double width = 0.05;
    double rough_width = 1.0;  ///< (rough_width)
    double lens_width = 2.0;   ///< (lens_width) pixels
    double light_width = 0.1;  ///< (light_width) fraction of a spherical light's radius
    /// Relative distance (to the scene's extent) within which the reverse walk must return.
    double tolerance = 1e-5;
    WalkSettings walk;
};

enum class HsltMutation { Large, HalfVector, Lens, Light };

/// The result of a perturbation: whether a proposal exists, and the Metropolis-Hastings ratio
/// (accept with min(1, ratio)).
struct HsltProposal {
    bool valid = false;
    double ratio = 0;
};

struct HsltContext {
    const Scene* scene;
    const PerspectiveCamera* camera;
    const FilmSpec* film;
    double scene_extent;  ///< the bounding box's diagonal (tolerances)
};

HsltProposal perturb_half_vectors(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                                  HsltPath* y);
HsltProposal perturb_lens(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                          HsltPath* y);
HsltProposal perturb_light(const HsltContext& ctx, const HsltPath& x, const HsltMutationSettings& st, PCG32& rng,
                           HsltPath* y);

/// The standard deviation of vertex v's half-vector perturbation.
double half_vector_width(const ManifoldVertex& v, const SampledWavelengths& wl, const HsltMutationSettings& st);

}  // namespace snell
