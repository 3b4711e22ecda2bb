#pragma once
// The settings of the path-tracing family, read by every integrator built on paths.
namespace snell {

class Props;

/// Settings shared by the path-tracing family (Mitsuba names).
struct PathSettings {
    int max_depth = -1;          ///< longest path in segments; -1: unbounded; 1: visible emitters only
    int rr_depth = 5;            ///< Russian roulette starts at this depth
    bool hide_emitters = false;  ///< directly visible emitters are black
    /// (hide_specular_emitters) emitters the camera sees through smooth specular vertices alone
    /// (paths C S+ L: a light's mirror images, a water surface's glints) are black. They are no
    /// caustic, and no technique at a diffuse vertex changes their noise, so a caustic's error
    /// can be scored without them (docs/experiments.md, thirteenth measurement). Only one
    /// technique produces such a path (BSDF sampling; BDPT's s = 0), so no MIS weight changes.
    bool hide_specular_emitters = false;
    /// (max_sample_share) the film's outlier clamp (apply_outlier_clamp, camera/outlier_clamp.h): a pixel's
    /// largest sample carries at most this share of it. Biased; 0 (default): off. mnee's
    /// `biased` mode defaults it to 0.5 (MneeIntegrator::path_settings_from_props).
    double max_sample_share = 0;
    /// (clamp_spread) with the clamp, the widest disc (pixels) its light is spread over instead
    /// of being dropped (apply_outlier_clamp, camera/outlier_clamp.h); 0 (default): dropped. mnee's `biased` mode
    /// defaults it to kBiasedClampSpread.
    int clamp_spread = 0;
    /// (caster_probability) the share of directions sampled at a reflecting, non-delta vertex
    /// that aim at the scene's refractive shapes rather than follow the BSDF (caster_sampling.h).
    /// 0 (default of pt, path and nee): BSDF sampling alone; `mnee` defaults it to
    /// kMneeCasterProbability.
    double caster_probability = 0;
    /// The settings every integrator built on paths reads (bdpt, pssmlt and erpt too).
    static PathSettings from_props(const Props& props);
    /// from_props plus max_sample_share: the integrators whose samples the film clamps (the
    /// RadianceTracer family: pt, path, nee, mnee); elsewhere the parameter is not read.
    static PathSettings tracer_from_props(const Props& props);
};

}  // namespace snell
