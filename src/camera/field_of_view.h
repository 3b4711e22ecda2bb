#pragma once
// Mitsuba's field of view, shared by the perspective sensors and the projector emitter: `fov`
// (degrees) along `fov_axis`, or a `focal_length` on 35 mm film.
#include <string>

#include "core/props.h"
#include "core/vector.h"

namespace snell {

struct FieldOfView {
    double fov_deg = 0;
    std::string axis = "x";  ///< x, y, smaller, larger or diagonal
};

/// Reads `fov`, `focal_length` and `fov_axis` as Mitsuba does: without `fov`, the focal length
/// ("50mm" unless given) is measured along the 35 mm film's diagonal. Bad values are SceneErrors
/// naming the parameter.
FieldOfView read_field_of_view(const Props& p);

/// Tangents of half the field of view along x and y of an image with aspect width / height.
Vec2 fov_tangents(const FieldOfView& fov, double aspect);

}  // namespace snell
