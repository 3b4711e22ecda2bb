#pragma once
// Factories of camera-side plugins that read a parameter dictionary (core/props.h). Kept apart
// from camera/filter.h, which the camera and the render loop use without a dictionary.
#include <memory>

#include "camera/filter.h"
#include "core/props.h"

namespace snell {

/// Builds a reconstruction filter from an <rfilter>'s props: `box` (no parameters),
/// `tent` (`radius`, default 1) or `gaussian` (`stddev`, default 0.5). Unknown types,
/// non-positive or non-finite parameters: SceneError at the element or the parameter.
/// Unused parameters are left for the caller's check_unused().
std::shared_ptr<const Filter> create_filter(const Props& props);

}  // namespace snell
