#pragma once
#include <memory>

#include "core/props.h"
#include "geometry/shape.h"
#include "light/light.h"

namespace snell {

/// Builds a stand-alone emitter from its `type` (point, spot, directional, constant, envmap).
std::shared_ptr<Light> create_light(const Props& props);
/// Builds an `area` emitter attached to `shape` (and registers itself with the shape).
std::shared_ptr<Light> create_area_light(const Props& props, const std::shared_ptr<Shape>& shape);

}  // namespace snell
