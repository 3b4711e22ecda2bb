#pragma once
// A state of half-vector space light transport (HSLT; Kaplanyan, Hanika & Dachsbacher 2014): one
// explicit path x_0 .. x_k from the pinhole x_0 to a light point x_k, and what the chain needs to
// weigh it in two measures.
//
// - C, its unidirectional path-tracing weight f / p (as `pt` would count it, with the length
//   drawn first): the colour every splat carries, and the ratio a large step is accepted by.
// - F, the luminance density of the same measurement in half-vector coordinates with both
//   endpoints fixed, the measure the perturbations move in (MNEE paper Sec. 3.3, HSLT Sec. 4):
//       F = Y( W G_0  L_e  prod_i rho_i |det C_i| ) / |det dH/dX|,
//   rho_i the vertex's scattering factor per projected solid angle of its half vector (kappa of
//   Eq. 9 where specular), C_i = dh_i/dx_{i+1} (the constraint block towards the next vertex:
//   rho_i |det C_i| is f_r |cos| G of the segment), and dH/dX the block-tridiagonal constraint
//   matrix of x_1 .. x_{k-1} between x_0 and x_k, whose determinant is the product of its block
//   LU pivots (Eq. 8).
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "core/sampled_spectrum.h"
#include "geometry/interaction.h"
#include "manifold/constraints.h"
#include "manifold/manifold_vertex.h"

namespace snell {

class Scene;
class PerspectiveCamera;
class Light;
struct FilmSpec;

/// The chains' target function T of a contribution in XYZ: the mean of its components. Every
/// splat then carries at most 3 b per component (xyz / (T / b + p_large)), where luminance Y let a
/// path of one wavelength near the spectrum's blue end (tiny Y, large Z) deposit its Z almost
/// whole through a large step's weight: single pixels at relMSE 10 to 10,000 on the droplet,
/// growing with the mutations (docs/experiments.md, "HSLT's step sizes and its normalisation").
/// Linear, as Y is, so that b = E[T] is the same under MNEE's estimator (the bootstrap) and under
/// path tracing's (the large steps): the largest component, tried first, is not, and MNEE's b left
/// the droplet's image 10 % bright.
inline double hslt_importance(const Vec3& xyz) { return (xyz.x + xyz.y + xyz.z) / 3; }

struct HsltPath {
    SampledWavelengths wl;
    Vec2 raster;  ///< full-film raster position of x_0 -> x_1
    Vec3 x0;      ///< the pinhole
    /// x_1 .. x_{k-1}: position, differential geometry, BSDF, eta at the hero wavelength, and the
    /// scattering asked of the vertex (reflect); h_target is the vertex's own half vector.
    std::vector<ManifoldVertex> chain;
    std::vector<uint8_t> specular;  ///< per chain vertex: scattered by a delta lobe
    const Light* light = nullptr;
    bool infinite = false;   ///< ended on a light at infinity (escaped): large steps only
    Vec3 escape_dir;         ///< the escaping direction when infinite
    SurfaceInteraction xk;   ///< the light point (area lights)
    bool hero_only = false;  ///< a dispersive delta vertex: the hero wavelength's path alone
    double depth_pmf = 1;    ///< probability of its length k, drawn first by a large step

    SampledSpectrum C;         ///< f / p, pmf of the length included
    Vec3 xyz;                  ///< C in XYZ (the splat's colour)
    double F = 0;              ///< importance density in half-vector coordinates (0: not perturbable)
    double camera_factor = 1;  ///< W G_0 of x_0 -> x_1, up to a constant
    double s_importance = 0;   ///< T(W G_0 L_e prod rho_i)
    double det_c = 1;          ///< prod_i |det C_i|

    int length() const { return int(chain.size()) + 1; }
    double target() const { return hslt_importance(xyz); }
    /// The tangent basis of x_k (the walk's fixed end).
    TangentBasis light_basis() const;
};

/// Unidirectional path sampling without light sampling, of one length k drawn from `depth_pmf`
/// (index k - 1): film position over the window grown by the filter margin, wavelengths, then
/// k - 1 BSDF samples and a k-th segment that must end on an emitter (or escape to a light at
/// infinity). False when it does not (the path carries nothing). Fills every field.
bool sample_hslt_path(const Scene& scene, const PerspectiveCamera& camera, const FilmSpec& film,
                      const std::vector<double>& depth_pmf, int spectral_samples, bool hide_emitters, PCG32& rng,
                      HsltPath* path);

/// Recomputes C, xyz and F of a path whose vertices moved (a perturbation's result), from the
/// vertices alone. False when the path carries nothing (a factor vanished, a matrix is singular).
bool evaluate_hslt_path(const Scene& scene, const PerspectiveCamera& camera, const FilmSpec& film, HsltPath* path);

/// F alone for a sub-chain: the density of the lens perturbation's coordinates (film position and
/// the half vectors of x_2 .. x_{k-1}): F with W G_0 dropped (constant per film area for a
/// pinhole) and dH/dX the matrix of x_2 .. x_{k-1} between x_1 and x_k.
double hslt_lens_density(const HsltPath& path);

/// The half vector of chain vertex i in its constraint frame (its h_target once converged).
Vec2 hslt_half_vector(const HsltPath& path, size_t i);

}  // namespace snell
