#pragma once
// Mitsuba plugins that snell does not have, named by the feature they belong to, so that a scene
// that needs one fails with that reason at the element's file:line (never a silent
// approximation): polarisation, participating media, curves, SDF grids, ...
#include <string>

#include "core/props.h"
#include "loader/xml_scene.h"

namespace snell {

/// The reason an object of element `tag` and plugin `type` cannot be loaded, or "" if snell
/// has no specific reason (the factories then report unknown types themselves).
std::string unsupported_feature(const std::string& tag, const std::string& type);

/// The Props of a parsed object element (its type, id and parameters); throws SceneError at the
/// element for a plugin of unsupported_feature().
Props object_props(const XmlObject& o);

}  // namespace snell
