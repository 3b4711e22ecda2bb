#include "texture/checkerboard.h"

#include <cmath>

namespace snell {

bool CheckerboardTexture::first_at(const Vec2& uv_in) const {
    const Vec2 uv = transform_uv(m_to_uv, uv_in);
    const bool u_high = uv.x - std::floor(uv.x) > 0.5, v_high = uv.y - std::floor(uv.y) > 0.5;
    return u_high == v_high;
}

}  // namespace snell
