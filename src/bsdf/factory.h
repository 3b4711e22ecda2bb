#pragma once
#include <memory>

#include "bsdf/bsdf.h"
#include "core/props.h"

namespace snell {

/// Builds a BSDF from its `type` (diffuse, dielectric, roughdielectric, thindielectric,
/// conductor, roughconductor, plastic, twosided). Unknown types or parameters: SceneError.
std::shared_ptr<BSDF> create_bsdf(const Props& props);

}  // namespace snell
