#include "io/image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <stdexcept>

#include "core/srgb.h"
#include "io/atomic_file.h"
#include "io/texture_image.h"

namespace snell {

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& path, const std::string& reason) {
    throw std::runtime_error(what + " '" + path + "': " + reason);
}

}  // namespace

void check_image_size(const std::string& what, const std::string& path, int64_t w, int64_t h, int64_t channels) {
    if (w <= 0 || h <= 0 || channels <= 0)
        fail(what, path, "empty image (" + std::to_string(w) + "x" + std::to_string(h) + ")");
    if (w > kMaxImagePixels / h || w * h > kMaxImageFloats / channels)
        fail(what, path,
             "the header says " + std::to_string(w) + "x" + std::to_string(h) + " pixels of " +
                 std::to_string(channels) + " channels; snell reads at most " + std::to_string(kMaxImagePixels) +
                 " pixels (16384 x 8192) and " + std::to_string(kMaxImageFloats) + " values");
}

namespace {

void check_image(const std::string& what, const std::string& path, const Image& img) {
    if (img.width <= 0 || img.height <= 0)
        fail(what, path, "image has non-positive size " + std::to_string(img.width) + "x" + std::to_string(img.height));
    if (img.rgb.size() != size_t(img.width) * img.height * 3)
        fail(what, path, "pixel buffer holds " + std::to_string(img.rgb.size()) + " floats, expected 3*width*height");
}

}  // namespace

void write_exr(const std::string& path, const Image& img) {
    check_image("cannot write EXR", path, img);
    try {
        // FLOAT, not HALF: reference images are compared bit-for-bit and half would round.
        Imf::Header header(img.width, img.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        const char* names[3] = {"R", "G", "B"};
        for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer fb;
        // The interleaved buffer is described with strides; OpenEXR does not write through it.
        char* base = reinterpret_cast<char*>(const_cast<float*>(img.rgb.data()));
        const size_t xs = 3 * sizeof(float), ys = xs * size_t(img.width);
        for (int c = 0; c < 3; ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
        // Encoded in memory, then written atomically (io/atomic_file.h): a failed write never
        // leaves a truncated file in place of a good one.
        Imf::StdOSStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(fb);
            file.writePixels(img.height);
        }  // the file's destructor writes the line-offset table
        write_file_atomically(path, stream.str());
    } catch (const std::exception& e) {
        fail("cannot write EXR", path, e.what());
    }
}

Image read_exr(const std::string& path) {
    std::error_code ec;  // only regular files: opening a FIFO would block (issue 12)
    if (!std::filesystem::is_regular_file(path, ec)) fail("cannot read EXR", path, "not a file");
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int64_t w64 = int64_t(dw.max.x) - dw.min.x + 1, h64 = int64_t(dw.max.y) - dw.min.y + 1;
        check_image_size("cannot read EXR", path, w64, h64, 3);
        const int w = int(w64), h = int(h64);
        Image img;
        img.width = w;
        img.height = h;
        img.rgb.assign(size_t(w) * h * 3, 0.0f);
        const Imf::ChannelList& channels = file.header().channels();
        const bool has_rgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
        const bool has_y = channels.findChannel("Y") != nullptr;
        if (!has_rgb && !has_y) fail("cannot read EXR", path, "no R, G, B or Y channel");
        // Slice::Make maps data-window pixel (min.x, min.y) to the buffer start, so files with
        // a non-zero data-window origin read into a 0-based image.
        const size_t xs = 3 * sizeof(float), ys = xs * size_t(w);
        char* base = reinterpret_cast<char*>(img.rgb.data());
        Imf::FrameBuffer fb;
        if (has_rgb) {
            // Missing colour channels are filled with 0 (the Slice fill value); A is ignored.
            const char* names[3] = {"R", "G", "B"};
            for (int c = 0; c < 3; ++c)
                fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), dw, xs, ys, 1, 1, 0.0));
        } else {
            // Luminance-only: read Y into R, copy to G and B afterwards.
            fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, base, dw, xs, ys, 1, 1, 0.0));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!has_rgb)
            for (size_t i = 0; i < img.rgb.size(); i += 3) img.rgb[i + 1] = img.rgb[i + 2] = img.rgb[i];
        return img;
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        if (msg.find(path) != std::string::npos) throw;  // already ours
        fail("cannot read EXR", path, msg);
    } catch (const std::exception& e) {
        fail("cannot read EXR", path, e.what());
    }
}

void write_png(const std::string& path, const Image& img, double exposure) {
    check_image("cannot write PNG", path, img);
    const double scale = std::exp2(exposure);
    std::vector<uint8_t> bytes(img.rgb.size());
    for (size_t i = 0; i < img.rgb.size(); ++i) {
        const double v = double(img.rgb[i]) * scale;
        // NaN maps to black rather than to an undefined cast.
        bytes[i] = std::isnan(v) ? 0 : uint8_t(std::lround(255.0 * linear_to_srgb(v)));
    }
    // Encoded in memory, then written atomically (io/atomic_file.h).
    std::string data;
    const auto append = [](void* ctx, void* chunk, int size) {
        static_cast<std::string*>(ctx)->append(static_cast<const char*>(chunk), size_t(size));
    };
    if (!stbi_write_png_to_func(append, &data, img.width, img.height, 3, bytes.data(), img.width * 3))
        fail("cannot write PNG", path, "stb_image_write failed (out of memory)");
    try {
        write_file_atomically(path, data);
    } catch (const std::exception& e) {
        fail("cannot write PNG", path, e.what());
    }
}

// One reader for every image a scene names (issue 30): an environment map and a texture made
// from one file get one verdict. Through stb, a truncated run-length .hdr hung as an envmap,
// or loaded black, while the same file was a clean error as a texture.
Image read_image(const std::string& path) {
    const TextureImage t = read_texture_image(path);
    Image img;
    img.width = t.width;
    img.height = t.height;
    const size_t n = size_t(t.width) * size_t(t.height);
    img.rgb.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = t.texels[i * size_t(t.channels) + size_t(t.channels == 3 ? c : 0)];
            img.rgb[i * 3 + size_t(c)] = t.srgb_encoded ? float(srgb_to_linear(v)) : v;
        }
    return img;
}

}  // namespace snell
