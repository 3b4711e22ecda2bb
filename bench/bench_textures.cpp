// `make bench`: bitmap texture lookups, snell's BitmapTexture against OpenImageIO's
// TextureSystem on the same 1024 x 1024 RGB float image (issue 11: "OpenImageIO with its texture
// system, unless you measure something better"). Both bilinear, repeat wrap, no MIP level (the
// integrators carry no ray differentials, so every lookup has a zero footprint), single thread,
// random uv. TextureSystem reads the image through its cache from a file written here.
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "core/rng.h"
#include "texture/bitmap.h"

using namespace snell;

namespace {

constexpr int kRes = 1024;

TextureImage make_image() {
    TextureImage img;
    img.width = img.height = kRes;
    img.channels = 3;
    img.texels.resize(size_t(kRes) * kRes * 3);
    PCG32 rng(1, 2);
    for (float& v : img.texels) v = float(rng.next_double());
    return img;
}

const std::string& image_file() {
    static const std::string path = [] {
        const std::string p = (std::filesystem::temp_directory_path() / "snell_bench_texture.exr").string();
        const TextureImage img = make_image();
        auto out = OIIO::ImageOutput::create(p);
        OIIO::ImageSpec spec(kRes, kRes, 3, OIIO::TypeDesc::FLOAT);
        out->open(p, spec);
        out->write_image(OIIO::TypeDesc::FLOAT, img.texels.data());
        out->close();
        return p;
    }();
    return path;
}

void BM_BitmapTextureLookup(benchmark::State& state) {
    const BitmapTexture tex(make_image(), BitmapTexture::Filter::Bilinear, BitmapTexture::Wrap::Repeat, true,
                            Transform());
    PCG32 rng(3, 4);
    SurfaceInteraction si;
    double sum = 0;
    for (auto _ : state) {
        for (int i = 0; i < 1024; ++i) {
            si.uv = Vec2(rng.next_double(), rng.next_double());
            sum += tex.eval_rgb(si).g;
        }
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(state.iterations() * 1024);
}

void BM_OiioTextureSystemLookup(benchmark::State& state) {
    OIIO::TextureSystem* ts = OIIO::TextureSystem::create(false);
    ts->attribute("automip", 0);
    OIIO::TextureOpt opt;
    opt.interpmode = OIIO::TextureOpt::InterpBilinear;
    opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
    opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
    const OIIO::ustring name(image_file());
    OIIO::TextureSystem::TextureHandle* handle = ts->get_texture_handle(name);
    OIIO::TextureSystem::Perthread* thread = ts->get_perthread_info();
    PCG32 rng(3, 4);
    float rgb[3];
    double sum = 0;
    for (auto _ : state) {
        for (int i = 0; i < 1024; ++i) {
            ts->texture(handle, thread, opt, float(rng.next_double()), float(rng.next_double()), 0, 0, 0, 0, 3, rgb);
            sum += rgb[1];
        }
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(state.iterations() * 1024);
    OIIO::TextureSystem::destroy(ts);
}

}  // namespace

BENCHMARK(BM_BitmapTextureLookup)->MinTime(1.0);
BENCHMARK(BM_OiioTextureSystemLookup)->MinTime(1.0);
