#pragma once
// One camera sample of the `mnee` integrator (paper Sec. 3): path tracing whose light connection
// from a non-specular vertex x_b is manifold next event estimation (ManifoldTechnique::connect,
// Alg. 1), weighted against BSDF sampling through the interfaces after x_b and against NEE from
// a rough last interface vertex by the power heuristic, with Alg. 2's densities. The loop is
// the path tracer's (camera_walk.h); what MNEE adds is the refractive suffix since x_b, which
// every MIS weight needs.
#include "integrators/mnee/connection_allocation.h"
#include "integrators/mnee/refractive_suffix.h"
#include "integrators/path/camera_walk.h"
#include "manifold/exterior_reflection.h"
#include "manifold/manifold_technique.h"
#include "manifold/mnee_settings.h"

namespace snell {

/// The reflected connection's MIS weight (power heuristic) against the two other techniques that
/// make its paths: BSDF sampling from x_b and, at rough glass, NEE from y. The three weights of a
/// path sum to 1 (ExteriorReflection.DensityReplaysTheConnectionAtRoughGlass checks it).
double reflected_connection_weight(const ReflectedConnection& r);

class MneePath {
public:
    /// `q`: the connection probability of this sample's region (ConnectionAllocation; < 0:
    /// MneeSettings::connect_probability); `surface_trials`: whether the region runs the surface
    /// trials, `failed_walk_trials` whether also beside failed straight walks (ManifoldQuery).
    /// `pilot`: the allocation's pilot records this sample.
    MneePath(const Scene& scene, const PathSettings& path, const MneeSettings& mnee, const SampledWavelengths& wl,
             const Ray& camera_ray, PathObserver* observer, double q, PilotSample* pilot, bool surface_trials = true,
             bool failed_walk_trials = false);

    /// The sample's radiance (all randomness from `sampler`).
    SampleEstimate trace(Sampler& sampler);

private:
    /// At a non-specular vertex that is no interface: Alg. 1 from x_b = si. At a rough
    /// interface vertex: NEE, weighted against BSDF sampling and MNEE from the path's x_b.
    void connect(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx, Sampler& sampler);
    /// The light reflected once off the outside of glass, from x_b = si (ExteriorReflection),
    /// weighed against BSDF sampling.
    void connect_reflected(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx, Sampler& sampler);
    /// The path at x_b = si as the manifold techniques need it.
    ManifoldQuery query_at(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx) const;
    SampledSpectrum connect_at_interface(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx,
                                         Sampler& sampler);
    /// MIS weight of an emitter that BSDF sampling reached at (p, n) (zero for lights at
    /// infinity) along d, emitting `value` (path throughput included) towards the path.
    double emitter_weight(const Light& light, const Vec3& p, const Vec3& n, const Vec3& d,
                          const SampledSpectrum& value) const;
    /// The technique credited with such an emitter (statistics only).
    Technique emitter_technique() const;
    /// The path arrived at `si`: an interface after x_b joins the suffix.
    void arrive(const SurfaceInteraction& si);
    /// The BSDF at `si` sampled `bs` (world space) with the path in `media_before` at si: the
    /// suffix grows, or si becomes the new x_b, or the path leaves MNEE's class.
    void scattered(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFSample& bs,
                   const MediumStack& media_before);

    /// q for a light on this path: the region's or the settings'; 1 for delta lights, which BSDF
    /// sampling cannot hit.
    double connect_probability(const Light& light) const;
    /// Whether the manifold technique can produce a path whose suffix after x_b is the
    /// recorded one (the last vertex refracting or not): refractions only, or any suffix when
    /// its surface seeds also reflect (solutions other than one, with reflections).
    bool covers(bool last_refracts) const;
    /// MNEE's density of the BSDF-sampled suffix ending at the light point (p, n), or 0 when the
    /// technique cannot produce it or q is 0; its work goes to the pilot's record, and `detail`
    /// tells whether only the surface trials reach it, and the rest of DensityDetail (the probe's
    /// density in the pilot). `*cut`: mis_cutoff gives MNEE no share of the path against the
    /// other techniques' density p_others, so MIS weighs it as if MNEE's density were 0; outside
    /// the pilot it is then not computed (0); in the pilot it is, for the record and its work.
    double mnee_density(bool last_refracts, const Light& light, double pmf, const Vec3& p, const Vec3& n, double q,
                        double p_others, DensityDetail* detail, bool* cut) const;
    /// Whether mis_cutoff gives this solution of a connection made with probability q no MIS
    /// weight: the same test as mnee_density's on the path's other side.
    bool cut_off(const ManifoldSolution& sol, double q) const;
    /// The pilot's record of a path another technique sampled with density p_t (ConnectionAllocation).
    void record_other(double value, double p_t, double p_m, const DensityDetail& detail, double p_other,
                      double q) const;

    const Scene* m_scene;
    const PathSettings* m_path;
    const MneeSettings* m_mnee;
    ManifoldTechnique m_technique;
    ExteriorReflection m_reflection;
    BSDFContext m_ctx;
    CameraWalk m_walk;
    PreviousVertex m_prev;
    RefractiveSuffix m_suffix;
    double m_q;
    PilotSample* m_pilot;
    bool m_surface_trials;
    bool m_failed_walk_trials;
    /// The reflected connection is made (ExteriorReflection::made: exterior_reflections > 0 and
    /// the scene holds smooth glass), in every region.
    bool m_reflects;
    /// Whether any MIS weight reads MNEE's density: q != 0 or a delta light in the scene. Where
    /// none, no connection competes with BSDF sampling or with NEE at a rough interface, their
    /// weights are the path tracer's, and the suffix keeps only its counters, and x_b and its
    /// first vertex where the reflected connection weighs that one-vertex class
    /// (docs/experiments.md, "What a region at q = 0 costs").
    bool m_weighs_mnee;
    SampleRadiance m_out;
};

}  // namespace snell
