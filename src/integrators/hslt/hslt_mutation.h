#pragma once
// HSLT's mutations (Kaplanyan, Hanika & Dachsbacher 2014, Sec. 5): perturbations of a path in
// half-vector space, each solved by the manifold walk (paper Sec. 3.4) with the path's ends
// held, and checked to be reversible (the walk back from the proposal with the old half vectors
// must return to the current path), so that the proposal is a bijection between the two and the
// Metropolis-Hastings ratio is the ratio of the densities in the perturbed coordinates.
//
// - Half vectors: every non-specular vertex's half vector moves by a 2D Gaussian (specular ones
//   stay at 0), x_0 and x_k fixed. Its width may follow the path's footprint on the film
//   (`footprint`) and the roughness where the vertex lies (half_vector_widths), so it depends on
//   the state: the ratio is F(y) / F(x) times the Gaussians' ratio T(y -> x) / T(x -> y).
// - Lens: the film position moves by a 2D Gaussian (pixels), x_1 is the new camera ray's hit on
//   the same shape, and x_2 .. x_{k-1} keep their half vectors. Ratio of hslt_lens_density.
//   Only where x_1 is not specular.
// - Light: x_k moves on its light, and x_1 .. x_{k-1} keep their half vectors. Ratio F(y) / F(x)
//   (the step is symmetric): on a sphere a Gaussian in its tangent plane projected radially (a
//   density of the angle between the two points alone); on any other shape a Gaussian in its
//   plane, kept where it lands on the shape in that same plane (rectangles, discs, flat meshes).
#include "core/rng.h"
#include "integrators/hslt/hslt_path.h"
#include "manifold/manifold_walk.h"

namespace snell {

struct HsltMutationSettings {
    /// (footprint) film distance, in pixels, by which a half-vector perturbation moves x_1 on
    /// average (HSLT's step size from the path's footprint); 0: fixed widths (`width`), the
    /// default: on the droplet the footprint's widths gave a higher median error at equal time
    /// (docs/experiments.md, "HSLT's step sizes").
    double footprint = 0.0;
    /// (perturbation_width) the largest standard deviation of a vertex's half-vector step, in
    /// tangential half-vector units: a diffuse vertex's, and every vertex's without footprint.
    /// A rough vertex's is its roughness times rough_width where smaller.
    double width = 0.05;
    double rough_width = 1.0;  ///< (rough_width)
    double lens_width = 2.0;   ///< (lens_width) pixels
    /// (light_width) light step: a fraction of a spherical light's radius, or of the radius of a
    /// disc of the light's area for other shapes.
    double light_width = 0.1;
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

/// The largest standard deviation of vertex v's half-vector perturbation: `width`, or the
/// vertex's roughness times `rough_width` where smaller (the glossy lobe's own width).
double half_vector_width(const ManifoldVertex& v, const SampledWavelengths& wl, const HsltMutationSettings& st);

/// The standard deviation of each chain vertex's half-vector step (0 for specular vertices): the
/// step that moves x_1 on the film by footprint / sqrt(n) pixels, n the perturbed vertices,
/// through the path's derivative d(film)/dh_i = d(film)/dx_1 (dH/dX)^-1 (HSLT's ray footprint),
/// capped by half_vector_width. Depends on the whole path, so T(x -> y) != T(y -> x).
std::vector<double> half_vector_widths(const HsltContext& ctx, const HsltPath& path, const HsltMutationSettings& st);

}  // namespace snell
