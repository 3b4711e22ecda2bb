#pragma once
// Mitsuba plugins that snell does not have, named by the feature they belong to, so that a scene
// that needs one fails with that reason at the element's file:line (never a silent
// approximation): polarisation, participating media, curves, SDF grids, ...
#include <string>

namespace snell {

/// The reason an object of element `tag` and plugin `type` cannot be loaded, or "" if snell
/// has no specific reason (the factories then report unknown types themselves).
std::string unsupported_feature(const std::string& tag, const std::string& type);

}  // namespace snell
