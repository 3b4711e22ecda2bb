#include "report/image_ops.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace snell {

Image crop_image(const Image& img, const Crop& crop_in) {
    Crop c = crop_in;
    if (c.w == 0) c = {0, 0, img.width, img.height};
    check_crop_inside(c, img.width, img.height);
    Image out;
    out.width = c.w;
    out.height = c.h;
    out.rgb.resize(size_t(c.w) * c.h * 3);
    for (int y = 0; y < c.h; ++y)
        for (int x = 0; x < c.w; ++x)
            for (int ch = 0; ch < 3; ++ch) out.at(x, y, ch) = img.at(c.x + x, c.y + y, ch);
    return out;
}

Image upscale_nearest(const Image& img, int factor) {
    if (factor < 1) throw std::invalid_argument("upscale factor must be >= 1, got " + std::to_string(factor));
    Image out;
    out.width = img.width * factor;
    out.height = img.height * factor;
    out.rgb.resize(size_t(out.width) * out.height * 3);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int ch = 0; ch < 3; ++ch) out.at(x, y, ch) = img.at(x / factor, y / factor, ch);
    return out;
}

int enlargement_factor(int w, int h, int target) {
    const int longer = std::max(1, std::max(w, h));
    return std::clamp(target / longer, 1, 16);
}

}  // namespace snell
