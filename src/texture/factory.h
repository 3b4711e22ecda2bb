#pragma once
// Textures from scene parameters: the plugins (bitmap, checkerboard) and the lookup every BSDF
// parameter goes through, so that any parameter Mitsuba lets vary over a surface may be a
// nested or referenced <texture> as well as a <float>, <rgb> or <spectrum>.
#include "core/props.h"
#include "texture/texture.h"

namespace snell {

/// Builds a <texture> from its `type`; unknown types, bad values and unused parameters are
/// SceneErrors. A relative `filename` is taken relative to the string parameter "__base_dir".
TextureRef create_texture(const Props& props);

/// The colour parameter `name`: a <texture name="name"> child, else the <float>/<rgb>/<spectrum>
/// upsampled for `use`, else `def`.
TextureRef get_texture(const Props& props, const std::string& name, SpectrumUse use, const Spectrum& def);
/// The scalar parameter `name`: a <texture name="name"> child (read as a scalar), else the
/// <float>, else `def`. Values outside [lo, hi] anywhere on the texture are an error.
TextureRef get_float_texture(const Props& props, const std::string& name, double def, double lo, double hi);

}  // namespace snell
