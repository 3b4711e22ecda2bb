// The texture layer on its own: image files through OpenImageIO, Mitsuba's bitmap lookups
// (texel centres, bilinear and nearest, the three wrap modes, sRGB decoding, raw), the spectral
// upsampling of texels, the checkerboard's cells.
#include <gtest/gtest.h>

#include <cmath>

#include "core/spectrum.h"
#include "io/texture_image.h"
#include "texture/bitmap.h"
#include "texture/checkerboard.h"
#include "texture/constant.h"
#include "texture/factory.h"
#include "texture_files.h"

using namespace snell;
using namespace snell::test;

namespace {

SurfaceInteraction at_uv(double u, double v) {
    SurfaceInteraction si;
    si.uv = Vec2(u, v);
    return si;
}

// A 4 x 2 grey image, row-major from the top: values k / 7 in 8 bits, so every texel differs.
std::vector<uint8_t> grey_ramp() {
    std::vector<uint8_t> px;
    for (int k = 0; k < 8; ++k) px.push_back(uint8_t(std::lround(255.0 * k / 7)));
    return px;
}

BitmapTexture load(const std::string& path, BitmapTexture::Filter f, BitmapTexture::Wrap w, bool raw = false) {
    return BitmapTexture(read_texture_image(path), f, w, raw, Transform());
}

}  // namespace

TEST(TextureImage, PngIsSrgbEncodedAndExrLinear) {
    const auto png = read_texture_image(write_texture("ramp.png", 4, 2, 1, grey_ramp()));
    EXPECT_EQ(png.width, 4);
    EXPECT_EQ(png.height, 2);
    EXPECT_EQ(png.channels, 1);
    EXPECT_TRUE(png.srgb_encoded);
    EXPECT_NEAR(png.texels[5], 5.0 / 7, 1.0 / 510);  // the file's values, in [0, 1]
    const std::vector<float> rgba = {0.5f, 2.0f, 0.25f, 1.0f, 0.1f, 0.2f, 0.3f, 0.5f};
    const auto exr = read_texture_image(write_texture("rgba.exr", 2, 1, 4, rgba));
    EXPECT_EQ(exr.channels, 3);  // alpha dropped
    EXPECT_FALSE(exr.srgb_encoded);
    EXPECT_FLOAT_EQ(exr.texels[1], 2.0f);
    EXPECT_FLOAT_EQ(exr.texels[5], 0.3f);
}

TEST(TextureImage, MissingOrCorruptFilesNameThePath) {
    try {
        read_texture_image("/nonexistent/t.png");
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/t.png"), std::string::npos);
    }
    const auto bad = texture_dir() / "bad.png";
    {
        std::FILE* f = std::fopen(bad.c_str(), "wb");
        std::fputs("not a png at all", f);
        std::fclose(f);
    }
    EXPECT_THROW(read_texture_image(bad.string()), std::runtime_error);
}

// Mitsuba 3's conventions: v = 0 is the image's top row, texel (i, j) is centred at
// ((i + 1/2) / w, (j + 1/2) / h); nearest takes the texel containing uv.
TEST(BitmapTexture, NearestReadsTheTexelUnderUvDecoded) {
    const std::string path = write_texture("ramp.png", 4, 2, 1, grey_ramp());
    const BitmapTexture t = load(path, BitmapTexture::Filter::Nearest, BitmapTexture::Wrap::Repeat);
    const BitmapTexture raw = load(path, BitmapTexture::Filter::Nearest, BitmapTexture::Wrap::Repeat, true);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 4; ++i) {
            const double stored = std::lround(255.0 * (4 * j + i) / 7) / 255.0;
            const SurfaceInteraction si = at_uv((i + 0.3) / 4, (j + 0.8) / 2);
            EXPECT_NEAR(t.eval_float(si), srgb_to_linear(stored), 1e-6) << i << "," << j;
            EXPECT_NEAR(raw.eval_float(si), stored, 1e-6);
        }
    EXPECT_NEAR(srgb_to_linear(0.5), 0.21404, 1e-5);  // IEC 61966-2-1
}

TEST(BitmapTexture, BilinearInterpolatesBetweenTexelCentres) {
    const BitmapTexture t = load(write_texture("ramp.png", 4, 2, 1, grey_ramp()), BitmapTexture::Filter::Bilinear,
                                 BitmapTexture::Wrap::Clamp, true);
    auto texel = [](int i, int j) { return std::lround(255.0 * (4 * j + i) / 7) / 255.0; };
    EXPECT_NEAR(t.eval_float(at_uv(1.5 / 4, 0.5 / 2)), texel(1, 0), 1e-6);  // a centre: the texel
    EXPECT_NEAR(t.eval_float(at_uv(2.0 / 4, 0.5 / 2)), 0.5 * (texel(1, 0) + texel(2, 0)), 1e-6);
    EXPECT_NEAR(t.eval_float(at_uv(2.0 / 4, 1.0 / 2)), 0.25 * (texel(1, 0) + texel(2, 0) + texel(1, 1) + texel(2, 1)),
                1e-6);
    // Clamp: beyond the last centre the edge texel holds.
    EXPECT_NEAR(t.eval_float(at_uv(0.99, 0.25)), texel(3, 0), 1e-6);
    EXPECT_NEAR(t.eval_float(at_uv(-3.0, 0.25)), texel(0, 0), 1e-6);
}

TEST(BitmapTexture, WrapModes) {
    const std::string path = write_texture("ramp.png", 4, 2, 1, grey_ramp());
    const auto repeat = load(path, BitmapTexture::Filter::Nearest, BitmapTexture::Wrap::Repeat, true);
    const auto mirror = load(path, BitmapTexture::Filter::Nearest, BitmapTexture::Wrap::Mirror, true);
    const auto clamp_ = load(path, BitmapTexture::Filter::Nearest, BitmapTexture::Wrap::Clamp, true);
    for (int i = -9; i <= 9; ++i) {
        EXPECT_EQ(repeat.wrap(i, 4), ((i % 4) + 4) % 4);
        EXPECT_EQ(clamp_.wrap(i, 4), std::clamp(i, 0, 3));
    }
    // Mirror: ... 1 0 | 0 1 2 3 | 3 2 1 0 | 0 1 ...
    const int expect_mirror[] = {0, 1, 2, 3, 3, 2, 1, 0, 0, 1};
    for (int i = 0; i < 10; ++i) EXPECT_EQ(mirror.wrap(i, 4), expect_mirror[i]);
    EXPECT_EQ(mirror.wrap(-1, 4), 0);
    EXPECT_EQ(mirror.wrap(-2, 4), 1);
    EXPECT_DOUBLE_EQ(repeat.eval_float(at_uv(1.3, 0.2)), repeat.eval_float(at_uv(0.3, 0.2)));
    EXPECT_DOUBLE_EQ(repeat.eval_float(at_uv(-0.7, 0.2)), repeat.eval_float(at_uv(0.3, 0.2)));
    EXPECT_DOUBLE_EQ(mirror.eval_float(at_uv(1.1, 0.2)), mirror.eval_float(at_uv(0.9, 0.2)));
    // Huge or non-finite uv cannot index outside the image.
    for (double u : {1e300, -1e300, double(NAN), double(INFINITY)})
        EXPECT_TRUE(std::isfinite(repeat.eval_float(at_uv(u, u))));
}

TEST(BitmapTexture, MeanAndRangeOverTexels) {
    const auto t = load(write_texture("ramp.png", 4, 2, 1, grey_ramp()), BitmapTexture::Filter::Bilinear,
                        BitmapTexture::Wrap::Repeat, true);
    double sum = 0;
    for (int k = 0; k < 8; ++k) sum += std::lround(255.0 * k / 7) / 255.0;
    EXPECT_NEAR(t.mean(), sum / 8, 1e-6);
    EXPECT_NEAR(t.min_value(), 0.0, 1e-7);
    EXPECT_NEAR(t.max_value(), 1.0, 1e-7);
}

// An RGB texel's spectrum reproduces its colour under the renderer's white, and a bilinear
// lookup's spectrum is the spectrum of the interpolated colour.
TEST(BitmapTexture, SpectralLookupReproducesTheTexelColour) {
    const std::vector<float> px = {0.8f, 0.1f, 0.05f, 0.1f, 0.3f, 0.9f};
    const auto t =
        load(write_texture("two.exr", 2, 1, 3, px), BitmapTexture::Filter::Bilinear, BitmapTexture::Wrap::Clamp);
    const Spectrum white = Spectrum::from_rgb_illuminant(RGB(1, 1, 1));
    auto colour_at = [&](double u) {
        std::vector<double> l, v;
        for (int i = 0; i <= 470; ++i) {
            const double lambda = 360 + i;
            l.push_back(lambda);
            v.push_back(t.eval(at_uv(u, 0.5), SampledWavelengths::single(lambda))[0] * white.eval(lambda));
        }
        return xyz_to_linear_srgb(spectrum_to_xyz(Spectrum::tabulated(l, v)));
    };
    const Vec3 left = colour_at(0.25), right = colour_at(0.75), mid = colour_at(0.5);
    EXPECT_NEAR(left.x, 0.8, 0.01);
    EXPECT_NEAR(left.y, 0.1, 0.01);
    EXPECT_NEAR(left.z, 0.05, 0.01);
    EXPECT_NEAR(right.z, 0.9, 0.01);
    EXPECT_NEAR(mid.x, 0.45, 0.01);
    EXPECT_NEAR(mid.y, 0.2, 0.01);
    EXPECT_NEAR(mid.z, 0.475, 0.01);
    const RGB rgb = t.eval_rgb(at_uv(0.5, 0.5));
    EXPECT_NEAR(rgb.r, 0.45, 1e-6);
    EXPECT_NEAR(t.eval_float(at_uv(0.25, 0.5)), RGB(0.8, 0.1, 0.05).luminance(), 1e-6);
}

// Mitsuba's checkerboard: 2 x 2 cells on the unit square, color0 where both fractional parts
// are on the same side of 1/2; to_uv scales the pattern.
TEST(CheckerboardTexture, CellsAndToUv) {
    const CheckerboardTexture c(ConstantTexture::make(0.4), ConstantTexture::make(0.2), Transform());
    EXPECT_DOUBLE_EQ(c.eval_float(at_uv(0.25, 0.25)), 0.4);
    EXPECT_DOUBLE_EQ(c.eval_float(at_uv(0.75, 0.75)), 0.4);
    EXPECT_DOUBLE_EQ(c.eval_float(at_uv(0.75, 0.25)), 0.2);
    EXPECT_DOUBLE_EQ(c.eval_float(at_uv(0.25, 0.75)), 0.2);
    EXPECT_DOUBLE_EQ(c.eval_float(at_uv(-0.25, 0.25)), 0.2);  // periodic
    EXPECT_DOUBLE_EQ(c.mean(), 0.3);
    const CheckerboardTexture scaled(ConstantTexture::make(1.0), ConstantTexture::make(0.0),
                                     Transform::scale(Vec3(4, 4, 1)));
    EXPECT_DOUBLE_EQ(scaled.eval_float(at_uv(0.1, 0.1)), 1.0);  // (0.4, 0.4): both low, color0
    EXPECT_DOUBLE_EQ(scaled.eval_float(at_uv(0.2, 0.1)), 0.0);  // (0.8, 0.4): mixed, color1
    EXPECT_DOUBLE_EQ(scaled.eval_float(at_uv(0.2, 0.2)), 1.0);  // (0.8, 0.8): both high
}

TEST(TextureImage, TiffJpegAndHdrRead) {
    const auto jpg = read_texture_image(write_texture("grey.jpg", 8, 8, 3, std::vector<uint8_t>(192, 128)));
    EXPECT_EQ(jpg.channels, 3);
    EXPECT_TRUE(jpg.srgb_encoded);
    EXPECT_NEAR(jpg.texels[5], 128.0 / 255, 3.0 / 255);  // lossy, but a flat image survives
    const auto tif = read_texture_image(write_texture("ramp.tif", 4, 2, 1, grey_ramp()));
    EXPECT_EQ(tif.channels, 1);
    EXPECT_TRUE(tif.srgb_encoded);
    EXPECT_NEAR(tif.texels[3], 3.0 / 7, 1.0 / 510);
    const std::vector<float> px = {0.5f, 2.0f, 0.25f, 4.0f, 0.125f, 1.0f};
    const auto hdr = read_texture_image(write_texture("two.hdr", 2, 1, 3, px));
    EXPECT_EQ(hdr.channels, 3);
    EXPECT_FALSE(hdr.srgb_encoded);
    for (size_t i = 0; i < px.size(); ++i) EXPECT_NEAR(hdr.texels[i], px[i], 0.01 * px[i]);  // RGBE: 8-bit mantissa
}

// Mitsuba's `rawconstant` keeps its value as given (a normal map's flat normal), and a bitmap's
// storage `format` is accepted (snell stores float) but checked.
TEST(TextureFactory, RawConstantAndBitmapFormat) {
    const SourceLoc loc{"test.xml", 3};
    Props raw("texture", "rawconstant", loc);
    raw.set("value", RGB(0.5, 0.5, 1.0), loc);
    const TextureRef t = create_texture(raw);
    const RGB c = t->eval_rgb(at_uv(0.3, 0.7));
    EXPECT_DOUBLE_EQ(c.r, 0.5);
    EXPECT_DOUBLE_EQ(c.b, 1.0);
    Props vec("texture", "rawconstant", loc);  // Mitsuba's test scenes write a <vector>
    vec.set("value", Vec3(0.5, 0.25, 1.0), loc);
    EXPECT_DOUBLE_EQ(create_texture(vec)->eval_rgb(at_uv(0, 0)).g, 0.25);
    const std::string png = write_texture("ramp.png", 4, 2, 1, grey_ramp());
    for (const char* f : {"auto", "variant", "fp16", "half"}) {
        Props b("texture", "bitmap", loc);
        b.set("filename", png, loc);
        b.set("format", std::string(f), loc);
        if (std::string(f) == "half")
            EXPECT_THROW(create_texture(b), SceneError);
        else
            EXPECT_NO_THROW(create_texture(b)) << f;
    }
}
