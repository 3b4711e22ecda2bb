#pragma once
// ERPT's `shapes` option: only paths whose camera subpath touches one of the listed shapes (a
// caustic seen on or through a glass object, say) have their energy redistributed, and their
// chains stay among such paths. The inner estimator is wrapped so that it reports, per li()
// call, whether a vertex of its camera subpath lay on a listed shape.
#include <memory>
#include <string>
#include <vector>

#include "core/props.h"
#include "integrators/path/radiance_estimator.h"
#include "manifold/mnee_settings.h"

namespace snell {

class Scene;
class Shape;

/// Splits a comma-separated list of shape ids ("glass, water") into trimmed ids; an empty
/// entry is an error reported through `props` at the parameter `name`.
std::vector<std::string> parse_shape_ids(const Props& props, const std::string& name, const std::string& list);

/// The shapes of `scene` whose scene-file id is one of `ids`. An id that no shape carries is a
/// SceneError at `loc` (the integrator's element) that names it and lists the ids the scene has.
std::vector<const Shape*> resolve_shape_ids(const Scene& scene, const std::vector<std::string>& ids,
                                            const SourceLoc& loc);

/// `nee` (sampler = "nee") or `mnee` (sampler = "mnee") that records, in a per-thread flag read
/// by camera_path_touched(), whether the camera subpath of its latest li() had a vertex (a
/// surface hit by the camera ray or by a BSDF-sampled ray) on one of `watched`. Estimates and
/// random numbers are exactly those of the unwrapped estimator.
std::shared_ptr<RadianceEstimator> make_watching_estimator(const std::string& sampler, const PathSettings& path,
                                                           const MneeSettings& mnee, std::vector<const Shape*> watched);

/// The flag of the latest li() of a watching estimator on the calling thread. A thread runs
/// one li() at a time, so reading it right after the call gives that call's answer.
bool camera_path_touched();

}  // namespace snell
