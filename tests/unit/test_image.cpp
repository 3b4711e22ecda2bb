#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <OpenImageIO/imageio.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>

#include <filesystem>
#include <fstream>
#include <limits>

#include "io/atomic_file.h"
#include "io/image.h"
#include "io/texture_image.h"

using namespace snell;
namespace fs = std::filesystem;

namespace {

// A per-test scratch directory under the system temp dir, removed afterwards.
class ImageIO : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_dir = fs::temp_directory_path() /
                (std::string("snell_test_image_") + info->name() + "_" + std::to_string(::getpid()));
        fs::create_directories(m_dir);
    }
    void TearDown() override { fs::remove_all(m_dir); }
    std::string path(const std::string& name) const { return (m_dir / name).string(); }
    fs::path m_dir;
};

Image make_image(int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.rgb.resize(size_t(w) * h * 3);
    return img;
}

// Writes a single-part scanline EXR with the given FLOAT channels, each channel c filled with
// value(x, y, c); `origin` shifts the data window.
template <class F>
void write_raw_exr(const std::string& path, int w, int h, const std::vector<std::string>& names, F value,
                   Imath::V2i origin = {0, 0}) {
    const Imath::Box2i dw(origin, origin + Imath::V2i(w - 1, h - 1));
    Imf::Header header(dw, dw);
    std::vector<std::vector<float>> planes(names.size(), std::vector<float>(size_t(w) * h));
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) planes[c][size_t(y) * w + x] = value(x, y, int(c));
        fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, planes[c].data(), dw));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
}

}  // namespace

// Issue 12 (found by the fuzzer): an image's size is checked from its header before a pixel
// buffer is allocated; a small file whose header claimed 7 GB of pixels made the allocation fail.
TEST_F(ImageIO, HugeImageHeadersAreAnErrorNotAnAllocation) {
    std::ofstream(path("huge.hdr"), std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 30000 +X 30000\n"
                                                      << std::string(64, '\x80');
    for (const auto& read : {+[](const std::string& p) { (void)read_image(p); },
                             +[](const std::string& p) { (void)read_texture_image(p); }}) {
        try {
            read(path("huge.hdr"));
            ADD_FAILURE() << "a 30000 x 30000 header loaded";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("the header says 30000x30000 pixels"), std::string::npos) << e.what();
        }
    }
    EXPECT_NO_THROW(check_image_size("read", "x", 16384, 8192, 3));
    EXPECT_THROW(check_image_size("read", "x", 16384, 8193, 3), std::runtime_error);
    EXPECT_THROW(check_image_size("read", "x", 1 << 20, 1 << 20, 1), std::runtime_error);
}

TEST_F(ImageIO, ExrFloatRoundTripIsExact) {
    Image img = make_image(7, 5);  // non-square, odd sizes catch stride/transposition errors
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = float((x + 1) * 0.37 - y * 1.9 + c * 0.013);
    // Values half floats cannot hold: negative, huge, tiny, and a non-dyadic fraction.
    img.at(0, 0, 0) = -123.456f;
    img.at(1, 0, 1) = 3.0e7f;
    img.at(2, 0, 2) = 1.0e-20f;
    img.at(3, 1, 0) = 0.1f;
    img.at(6, 4, 2) = std::numeric_limits<float>::max();
    const std::string p = path("rt.exr");
    write_exr(p, img);
    const Image back = read_exr(p);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    ASSERT_EQ(back.rgb.size(), img.rgb.size());
    for (size_t i = 0; i < img.rgb.size(); ++i) EXPECT_EQ(back.rgb[i], img.rgb[i]) << "index " << i;
}

TEST_F(ImageIO, ExrReadsRgbaAndIgnoresAlpha) {
    const std::string p = path("rgba.exr");
    write_raw_exr(p, 4, 3, {"R", "G", "B", "A"},
                  [](int x, int y, int c) { return c == 3 ? 0.5f : float(10 * y + x + 0.25 * c); });
    const Image img = read_exr(p);
    ASSERT_EQ(img.width, 4);
    ASSERT_EQ(img.height, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), float(10 * y + x + 0.25 * c));
}

TEST_F(ImageIO, ExrMissingChannelsAreZero) {
    const std::string p = path("rg.exr");
    write_raw_exr(p, 3, 2, {"R", "G"}, [](int x, int y, int c) { return float(1 + x + y + c); });
    const Image img = read_exr(p);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            EXPECT_EQ(img.at(x, y, 0), float(1 + x + y));
            EXPECT_EQ(img.at(x, y, 1), float(2 + x + y));
            EXPECT_EQ(img.at(x, y, 2), 0.0f);
        }
}

TEST_F(ImageIO, ExrLuminanceOnlyBecomesGrey) {
    const std::string p = path("y.exr");
    write_raw_exr(p, 3, 2, {"Y"}, [](int x, int y, int) { return float(x - 2.5 * y); });
    const Image img = read_exr(p);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), float(x - 2.5 * y));
}

TEST_F(ImageIO, ExrNonZeroDataWindowReadsFromOrigin) {
    const std::string p = path("window.exr");
    write_raw_exr(
        p, 4, 3, {"R", "G", "B"}, [](int x, int y, int c) { return float(100 * c + 10 * y + x); }, Imath::V2i(-5, 17));
    const Image img = read_exr(p);
    ASSERT_EQ(img.width, 4);
    ASSERT_EQ(img.height, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), float(100 * c + 10 * y + x));
}

TEST_F(ImageIO, ExrMissingFileThrowsWithPath) {
    const std::string p = path("does_not_exist.exr");
    try {
        read_exr(p);
        FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
}

TEST_F(ImageIO, ExrCorruptFileThrowsWithPath) {
    // Not an EXR at all.
    const std::string garbage = path("garbage.exr");
    std::ofstream(garbage) << "this is not an OpenEXR file\n";
    // A real EXR cut short: valid header, missing pixel data.
    Image img = make_image(16, 16);
    for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = float(i) * 0.001f;
    const std::string full = path("full.exr"), truncated = path("truncated.exr");
    write_exr(full, img);
    const auto size = fs::file_size(full);
    fs::copy_file(full, truncated);
    fs::resize_file(truncated, size * 2 / 3);
    for (const std::string& p : {garbage, truncated}) {
        try {
            read_exr(p);
            ADD_FAILURE() << "expected an exception for " << p;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
        }
    }
}

TEST_F(ImageIO, ExrWriteToBadPathThrowsWithPath) {
    const std::string p = path("no_such_dir/out.exr");
    Image img = make_image(2, 2);
    try {
        write_exr(p, img);
        FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
}

TEST_F(ImageIO, WriteRejectsInconsistentBuffer) {
    Image img = make_image(3, 3);
    img.rgb.pop_back();
    EXPECT_THROW(write_exr(path("bad.exr"), img), std::runtime_error);
    EXPECT_THROW(write_png(path("bad.png"), img), std::runtime_error);
}

namespace {
struct Decoded {
    int w = 0, h = 0, n = 0;
    std::vector<unsigned char> px;
};
Decoded decode_png(const std::string& p) {
    Decoded d;
    unsigned char* data = stbi_load(p.c_str(), &d.w, &d.h, &d.n, 3);
    if (!data) throw std::runtime_error("stbi_load failed: " + p);
    d.px.assign(data, data + size_t(d.w) * d.h * 3);
    stbi_image_free(data);
    return d;
}
}  // namespace

TEST_F(ImageIO, PngSrgbEncoding) {
    // Row 0: 0, 0.5, 1, 2 (clamped), -1 (clamped), 0.001 (linear segment of the OETF).
    Image img = make_image(6, 2);
    const float v[6] = {0.0f, 0.5f, 1.0f, 2.0f, -1.0f, 0.001f};
    for (int x = 0; x < 6; ++x)
        for (int c = 0; c < 3; ++c) {
            img.at(x, 0, c) = v[x];
            img.at(x, 1, c) = c == 0 ? 0.5f : 0.0f;  // row 1: channel order check
        }
    const std::string p = path("srgb.png");
    write_png(p, img);
    const Decoded d = decode_png(p);
    ASSERT_EQ(d.w, 6);
    ASSERT_EQ(d.h, 2);
    ASSERT_EQ(d.n, 3);
    // 0.5 -> 1.055 * 0.5^(1/2.4) - 0.055 = 0.73536 -> 187.5 -> 188.
    const int expect[6] = {0, 188, 255, 255, 0, 3};  // 0.001 * 12.92 * 255 = 3.29
    for (int x = 0; x < 6; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(int(d.px[size_t(x) * 3 + c]), expect[x]) << "x=" << x << " c=" << c;
    const unsigned char* row1 = d.px.data() + 6 * 3;
    EXPECT_EQ(int(row1[0]), 188);
    EXPECT_EQ(int(row1[1]), 0);
    EXPECT_EQ(int(row1[2]), 0);
}

TEST_F(ImageIO, PngExposurePlusOneDoubles) {
    // Encoding v at exposure +1 must equal encoding 2v at exposure 0, bit for bit.
    Image a = make_image(64, 1), b = make_image(64, 1);
    for (int x = 0; x < 64; ++x)
        for (int c = 0; c < 3; ++c) {
            const float v = float(x) / 100.0f + 0.001f * c;  // spans below and above 0.5 (clamp)
            a.at(x, 0, c) = v;
            b.at(x, 0, c) = 2.0f * v;
        }
    write_png(path("a.png"), a, 1.0);
    write_png(path("b.png"), b, 0.0);
    const Decoded da = decode_png(path("a.png")), db = decode_png(path("b.png"));
    EXPECT_EQ(da.px, db.px);
    // And exposure -1 undoes it: 0.5 at exposure 1 -> encoded 1.0; 1.0 at exposure -1 -> 188.
    Image c = make_image(1, 1);
    c.rgb = {1.0f, 1.0f, 1.0f};
    write_png(path("c.png"), c, -1.0);
    EXPECT_EQ(int(decode_png(path("c.png")).px[0]), 188);
}

TEST_F(ImageIO, PngBadPathThrowsWithPath) {
    const std::string p = path("no_such_dir/out.png");
    Image img = make_image(2, 2);
    try {
        write_png(p, img);
        FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
}

// Radiance .hdr images (environment maps): read back within RGBE's precision (8-bit mantissas);
// a file that is not RGBE, and an unknown extension, are errors naming the path.
TEST_F(ImageIO, ReadsRadianceHdr) {
    const int w = 4, h = 2;
    std::vector<float> px(size_t(w) * h * 3);
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(0.01 * double(i + 1) * double(i + 1));
    ASSERT_TRUE(stbi_write_hdr(path("sky.hdr").c_str(), w, h, 3, px.data()));
    const Image img = read_image(path("sky.hdr"));
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    // RGBE shares one exponent per pixel: each channel is exact to 1/256 of the pixel's largest.
    for (size_t i = 0; i < px.size(); ++i) {
        const size_t p0 = i / 3 * 3;
        const float top = std::max({px[p0], px[p0 + 1], px[p0 + 2]});
        EXPECT_NEAR(img.rgb[i], px[i], top / 128) << i;
    }
    std::ofstream(path("fake.hdr")) << "not an image";
    try {
        read_image(path("fake.hdr"));
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("fake.hdr"), std::string::npos) << e.what();
    }
}

namespace {

// A 64 x 8 run-length (new-style) Radiance file: every scanline is "2 2 w" and one run per
// channel.
std::string rle_hdr(int w, int h) {
    std::string s = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
    for (int y = 0; y < h; ++y) {
        s += {char(2), char(2), char(w >> 8), char(w & 255)};
        for (int c = 0; c < 4; ++c) s += {char(128 + w), char(c == 3 ? 128 : 100)};
    }
    return s;
}

}  // namespace

// Issue 30 (#1, #8): through stb, a 53-byte truncated run-length .hdr never finished loading as
// an envmap, and other truncations loaded black with exit 0, while the same file as a texture was
// a clean error. Envmaps now read through read_texture_image: every prefix of a valid file is an
// error naming it, the same verdict as a texture's, and the whole file reads back.
TEST_F(ImageIO, TruncatedRunLengthHdrIsAnErrorEverywhere) {
    const std::string full = rle_hdr(64, 8);
    std::ofstream(path("rle.hdr"), std::ios::binary) << full;
    const Image img = read_image(path("rle.hdr"));
    ASSERT_EQ(img.width, 64);
    ASSERT_EQ(img.height, 8);
    EXPECT_NEAR(img.rgb[0], 100.0 / 256, 1e-6);
    for (size_t n = 1; n < full.size(); ++n) {
        std::ofstream(path("cut.hdr"), std::ios::binary | std::ios::trunc) << full.substr(0, n);
        std::string as_env, as_texture;
        try {
            (void)read_image(path("cut.hdr"));
        } catch (const std::runtime_error& e) {
            as_env = e.what();
        }
        try {
            (void)read_texture_image(path("cut.hdr"));
        } catch (const std::runtime_error& e) {
            as_texture = e.what();
        }
        EXPECT_NE(as_env.find("cut.hdr"), std::string::npos) << n << " bytes: " << as_env;
        EXPECT_EQ(as_env, as_texture) << n << " bytes";
    }
}

// Issue 30 (#7): a 966-byte JPEG whose header claimed 8192 x 8192 decoded as a grey 1.7 GB
// texture in 24 s. A header that claims more pixels than the file's bytes can encode is an
// error before any pixel is decoded; a real 8-bit file, however well it compresses, is not.
TEST_F(ImageIO, HeaderClaimingMorePixelsThanTheFileHoldsIsAnError) {
    const std::vector<uint8_t> grey(size_t(64) * 64 * 3, 128);
    {
        auto out = OIIO::ImageOutput::create(path("small.jpg"));
        ASSERT_TRUE(out);
        ASSERT_TRUE(out->open(path("small.jpg"), OIIO::ImageSpec(64, 64, 3, OIIO::TypeDesc::UINT8)));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, grey.data()));
        out->close();
    }
    EXPECT_NO_THROW((void)read_image(path("small.jpg")));
    // Patch the frame header's size (SOF0: FF C0, length, precision, height, width) to 8192 x 8192.
    std::ifstream in(path("small.jpg"), std::ios::binary);
    std::string jpg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t sof = jpg.find("\xFF\xC0");
    ASSERT_NE(sof, std::string::npos);
    jpg[sof + 5] = jpg[sof + 7] = char(0x20);
    jpg[sof + 6] = jpg[sof + 8] = char(0);
    std::ofstream(path("huge.jpg"), std::ios::binary) << jpg;
    ASSERT_LT(jpg.size(), 4096u);
    try {
        (void)read_image(path("huge.jpg"));
        ADD_FAILURE() << "an 8192 x 8192 header in " << jpg.size() << " bytes loaded";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("8192x8192 pixels, more than a"), std::string::npos) << e.what();
    }
    EXPECT_NO_THROW(check_image_size_against_file("x", 16384, 8192, 8192));
    EXPECT_THROW(check_image_size_against_file("x", 16384, 8192, 4096), std::runtime_error);
}

// Issue 12: output is written atomically and every write is checked. Writing onto /dev/full
// (a device that reports "no space left" on every write) is an error for EXR, PNG and the stats
// writer's helper; and when the new file cannot be completed (here: its temporary file cannot be
// created, because a folder has taken its name), the existing good file is left as it was.
TEST_F(ImageIO, OutputIsAtomicAndWriteErrorsAreCaught) {
    Image img;
    img.width = img.height = 2;
    img.rgb.assign(12, 0.5f);
    EXPECT_THROW(write_exr("/dev/full", img), std::runtime_error);
    EXPECT_THROW(write_png("/dev/full", img, 0.0), std::runtime_error);
    EXPECT_THROW(write_file_atomically("/dev/full", "data"), std::runtime_error);
    const std::string good = path("good.exr");
    write_exr(good, img);
    const auto size_before = fs::file_size(good);
    fs::create_directories(path(".good.exr.tmp" + std::to_string(::getpid())));
    Image other = img;
    other.rgb.assign(12, 0.25f);
    EXPECT_THROW(write_exr(good, other), std::runtime_error);
    EXPECT_EQ(fs::file_size(good), size_before);
    EXPECT_FLOAT_EQ(read_exr(good).rgb[0], 0.5f);
    fs::remove(path(".good.exr.tmp" + std::to_string(::getpid())));
    write_exr(good, other);  // and with the way clear it is replaced
    EXPECT_FLOAT_EQ(read_exr(good).rgb[0], 0.25f);
    for (const auto& e : fs::directory_iterator(fs::path(good).parent_path()))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "left over: " << e.path();
}
