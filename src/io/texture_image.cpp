#include "io/texture_image.h"

#include "io/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace snell {

void check_image_size_against_file(const std::string& path, int64_t w, int64_t h, uintmax_t bytes) {
    // Image sizes against the data actually present (issue 30): a 966-byte JPEG whose header
    // claimed 8192 x 8192 decoded, as grey, into 1.7 GB in 24 s without an error. No format
    // snell reads packs more than kMaxPixelsPerByte pixels into a byte (deflate's limit is 1032:1,
    // times 8 one-bit pixels per byte), so a larger claim is a header the file cannot back.
    if (w > 0 && h > 0 && double(w) * double(h) > double(kFreePixels) + double(kMaxPixelsPerByte) * double(bytes))
        throw std::runtime_error("cannot read image '" + path + "': the header says " + std::to_string(w) + "x" +
                                 std::to_string(h) + " pixels, more than a " + std::to_string(bytes) +
                                 "-byte file can hold (truncated or corrupt)");
}

TextureImage read_texture_image(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error("cannot open image '" + path + "'");
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error("cannot read image '" + path + "': " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
        throw std::runtime_error("image '" + path + "' has no 2D pixels");
    check_image_size("cannot read image", path, spec.width, spec.height, spec.nchannels);
    check_image_size_against_file(path, spec.width, spec.height, std::filesystem::file_size(path, ec));
    const int nc = spec.nchannels;
    std::vector<float> all(size_t(spec.width) * size_t(spec.height) * size_t(nc));
    const auto failed = [&] { return std::runtime_error("cannot read image '" + path + "': " + in->geterror()); };
    if (spec.tile_width == 0) {
        // Row by row: OpenImageIO 2.4's read_image converts chunks of up to 256 scanlines through
        // a buffer of that size whatever the image's height, so a 2-row image 2.4 million pixels
        // wide asked for 7 GB (found by the fuzzer).
        const size_t row = size_t(spec.width) * size_t(nc);
        for (int y = 0; y < spec.height; ++y)
            if (!in->read_scanline(spec.y + y, spec.z, OIIO::TypeDesc::FLOAT, all.data() + size_t(y) * row))
                throw failed();
    } else {
        check_image_size("cannot read image", path, spec.tile_width, spec.tile_height,
                         int64_t(nc) * std::max(1, spec.tile_depth));
        if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, all.data())) throw failed();
    }

    TextureImage img;
    img.width = spec.width;
    img.height = spec.height;
    // Grey, grey + alpha -> 1 channel; RGB, RGBA and more -> the first three.
    img.channels = nc <= 2 ? 1 : 3;
    const size_t n = size_t(img.width) * size_t(img.height);
    img.texels.resize(n * size_t(img.channels));
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < img.channels; ++c)
            img.texels[i * size_t(img.channels) + size_t(c)] = all[i * size_t(nc) + size_t(c)];
    const std::string space = spec.get_string_attribute("oiio:ColorSpace");
    const bool integer = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                         spec.format.basetype != OIIO::TypeDesc::HALF && spec.format.basetype != OIIO::TypeDesc::DOUBLE;
    img.srgb_encoded = integer && space != "Linear" && space != "linear";
    in->close();
    return img;
}

}  // namespace snell
