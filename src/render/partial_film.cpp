#include "render/partial_film.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/spectrum.h"
#include "io/atomic_file.h"
#include "render/renderer.h"

namespace snell {

namespace {

constexpr const char* kInfoAttribute = "snell.partial";
constexpr int kFormatVersion = 1;

// The exact channels of one pixel, as 32-bit words: XYZ sums (3 x 6), count (2), largest
// sample (3 x 2, its doubles' bits), technique + 1 (1).
constexpr int kWordsPerPixel = 18 + 2 + 6 + 1;
constexpr int kWordsPerSplat = 18;

std::vector<std::string> pixel_channel_names() {
    std::vector<std::string> n;
    for (const char* c : {"X", "Y", "Z"})
        for (int k = 0; k < 6; ++k) n.push_back(std::string("snell.sum.") + c + "." + std::to_string(k));
    n.push_back("snell.count.0");
    n.push_back("snell.count.1");
    for (const char* c : {"X", "Y", "Z"})
        for (int k = 0; k < 2; ++k) n.push_back(std::string("snell.largest.") + c + "." + std::to_string(k));
    n.push_back("snell.technique");
    return n;
}

std::vector<std::string> splat_channel_names(int layer) {
    std::vector<std::string> n;
    for (const char* c : {"X", "Y", "Z"})
        for (int k = 0; k < 6; ++k)
            n.push_back("snell.splat" + std::to_string(layer) + "." + c + "." + std::to_string(k));
    return n;
}

void put_u64(uint32_t* w, uint64_t v) {
    w[0] = uint32_t(v);
    w[1] = uint32_t(v >> 32);
}
uint64_t get_u64(const uint32_t* w) { return uint64_t(w[0]) | uint64_t(w[1]) << 32; }
uint64_t bits(double d) {
    uint64_t b;
    std::memcpy(&b, &d, sizeof b);
    return b;
}
double from_bits(uint64_t b) {
    double d;
    std::memcpy(&d, &b, sizeof d);
    return d;
}

void put_sums(uint32_t* w, const ExactSum3& s) {
    const ExactSum* c[3] = {&s.x, &s.y, &s.z};
    for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) put_u64(w + 6 * k + 2 * l, c[k]->limbs()[size_t(l)]);
}
ExactSum3 get_sums(const uint32_t* w) {
    ExactSum3 s;
    ExactSum* c[3] = {&s.x, &s.y, &s.z};
    for (int k = 0; k < 3; ++k)
        *c[k] = ExactSum::from_limbs({get_u64(w + 6 * k), get_u64(w + 6 * k + 2), get_u64(w + 6 * k + 4)});
    return s;
}

nlohmann::json to_json(const PartialFilmInfo& i) {
    return {{"version", kFormatVersion},
            {"scene_hash", i.scene_hash},
            {"integrator", i.integrator},
            {"seed", i.seed},
            {"width", i.width},
            {"height", i.height},
            {"spp", i.spp},
            {"spectral_samples", i.spectral_samples},
            {"max_sample_share", i.max_sample_share},
            {"clamp_spread", i.clamp_spread},
            {"technique_names", i.technique_names},
            {"layer_names", i.layer_names},
            {"crop", {i.crop.x0, i.crop.y0, i.crop.width(), i.crop.height()}},
            {"sample_range", {i.sample_begin, i.sample_end}}};
}

PartialFilmInfo from_json(const nlohmann::json& j) {
    PartialFilmInfo i;
    if (j.at("version").get<int>() != kFormatVersion)
        throw std::runtime_error("partial film format version " + j.at("version").dump() + ", expected " +
                                 std::to_string(kFormatVersion));
    i.scene_hash = j.at("scene_hash").get<std::string>();
    i.integrator = j.at("integrator").get<std::string>();
    i.seed = j.at("seed").get<uint64_t>();
    i.width = j.at("width").get<int>();
    i.height = j.at("height").get<int>();
    i.spp = j.at("spp").get<uint64_t>();
    i.spectral_samples = j.at("spectral_samples").get<int>();
    i.max_sample_share = j.at("max_sample_share").get<double>();
    i.clamp_spread = j.at("clamp_spread").get<int>();
    i.technique_names = j.at("technique_names").get<std::vector<std::string>>();
    i.layer_names = j.at("layer_names").get<std::vector<std::string>>();
    const auto c = j.at("crop").get<std::vector<int>>();
    if (c.size() != 4) throw std::runtime_error("crop is not x, y, w, h");
    i.crop = {c[0], c[1], c[0] + c[2], c[1] + c[3]};
    const auto r = j.at("sample_range").get<std::vector<uint64_t>>();
    if (r.size() != 2) throw std::runtime_error("sample_range is not a, b");
    i.sample_begin = r[0];
    i.sample_end = r[1];
    if (i.width <= 0 || i.height <= 0 || int64_t(i.width) * i.height > (int64_t(1) << 28))
        throw std::runtime_error("film size " + std::to_string(i.width) + "x" + std::to_string(i.height));
    if (i.crop.empty() || i.crop.x0 < 0 || i.crop.y0 < 0 || i.crop.x1 > i.width || i.crop.y1 > i.height)
        throw std::runtime_error("crop outside the film");
    if (i.sample_begin >= i.sample_end) throw std::runtime_error("empty sample range");
    return i;
}

/// What must agree between two partial films of one render (empty: they agree).
std::string mismatch(const PartialFilmInfo& a, const PartialFilmInfo& b) {
    if (a.scene_hash != b.scene_hash) return "scene (hash " + a.scene_hash + " against " + b.scene_hash + ")";
    if (a.integrator != b.integrator) return "integrator (" + a.integrator + " against " + b.integrator + ")";
    if (a.seed != b.seed) return "seed (" + std::to_string(a.seed) + " against " + std::to_string(b.seed) + ")";
    if (a.width != b.width || a.height != b.height) return "film size";
    if (a.spp != b.spp) return "spp (" + std::to_string(a.spp) + " against " + std::to_string(b.spp) + ")";
    if (a.spectral_samples != b.spectral_samples) return "spectral samples";
    if (a.max_sample_share != b.max_sample_share || a.clamp_spread != b.clamp_spread) return "outlier clamp";
    if (a.technique_names != b.technique_names || a.layer_names != b.layer_names) return "techniques or layers";
    return "";
}

bool overlaps(const PartialFilmInfo& a, const PartialFilmInfo& b) {
    const bool pixels =
        a.crop.x0 < b.crop.x1 && b.crop.x0 < a.crop.x1 && a.crop.y0 < b.crop.y1 && b.crop.y0 < a.crop.y1;
    return pixels && a.sample_begin < b.sample_end && b.sample_begin < a.sample_end;
}

}  // namespace

uint64_t fnv1a(const std::string& bytes, uint64_t h) {
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

void write_partial_film(const std::string& path, const Film& film, const PartialFilmInfo& info) {
    const int w = film.width(), h = film.height();
    const size_t n = size_t(w) * size_t(h);
    // The look: the partial's own estimate in linear sRGB (a copy, so the caller's film keeps
    // its state; the merge applies the clamp, not the part).
    Film look = film;
    finish_film(look, 0, 0);
    const std::vector<float> rgb = look.to_linear_srgb();
    std::vector<uint32_t> words(n * kWordsPerPixel);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint32_t* p = words.data() + (size_t(y) * w + x) * kWordsPerPixel;
            put_sums(p, film.exact_sum(x, y));
            put_u64(p + 18, film.samples(x, y));
            const Vec3 m = film.largest_sample_xyz(x, y);
            put_u64(p + 20, bits(m.x));
            put_u64(p + 22, bits(m.y));
            put_u64(p + 24, bits(m.z));
            p[26] = uint32_t(film.largest_sample_technique(x, y) + 1);
        }
    std::vector<int> layers;
    for (int l = 0; l < film.splat_layers(); ++l)
        if (film.has_splats(l)) layers.push_back(l);
    std::vector<std::vector<uint32_t>> splat_words(layers.size(), std::vector<uint32_t>(n * kWordsPerSplat));
    for (size_t k = 0; k < layers.size(); ++k)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                put_sums(splat_words[k].data() + (size_t(y) * w + x) * kWordsPerSplat,
                         film.exact_splat(layers[k], x, y));
    try {
        Imf::Header header(w, h);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.insert(kInfoAttribute, Imf::StringAttribute(to_json(info).dump()));
        Imf::FrameBuffer fb;
        const char* rgb_names[3] = {"R", "G", "B"};
        char* base = reinterpret_cast<char*>(const_cast<float*>(rgb.data()));
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(rgb_names[c], Imf::Channel(Imf::FLOAT));
            fb.insert(rgb_names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 3 * sizeof(float),
                                               3 * sizeof(float) * size_t(w)));
        }
        const auto insert = [&](const std::vector<std::string>& names, std::vector<uint32_t>& data, int stride) {
            char* b = reinterpret_cast<char*>(data.data());
            for (size_t c = 0; c < names.size(); ++c) {
                header.channels().insert(names[c], Imf::Channel(Imf::UINT));
                fb.insert(names[c], Imf::Slice(Imf::UINT, b + c * sizeof(uint32_t), stride * sizeof(uint32_t),
                                               stride * sizeof(uint32_t) * size_t(w)));
            }
        };
        insert(pixel_channel_names(), words, kWordsPerPixel);
        for (size_t k = 0; k < layers.size(); ++k)
            insert(splat_channel_names(layers[k]), splat_words[k], kWordsPerSplat);
        Imf::StdOSStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(fb);
            file.writePixels(h);
        }
        write_file_atomically(path, stream.str());
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot write partial film " + path + ": " + e.what());
    }
}

PartialFilm read_partial_film(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw std::runtime_error("cannot read partial film " + path + ": not a file");
    try {
        Imf::InputFile file(path.c_str());
        const auto* attr = file.header().findTypedAttribute<Imf::StringAttribute>(kInfoAttribute);
        if (!attr)
            throw std::runtime_error("not a partial film (no " + std::string(kInfoAttribute) +
                                     " attribute; write one with snell render --crop or --sample-range)");
        PartialFilm p;
        p.info = from_json(nlohmann::json::parse(attr->value()));
        const Imath::Box2i dw = file.header().dataWindow();
        if (dw.min.x != 0 || dw.min.y != 0 || dw.max.x != p.info.width - 1 || dw.max.y != p.info.height - 1)
            throw std::runtime_error("its data window is not the film's " + std::to_string(p.info.width) + "x" +
                                     std::to_string(p.info.height));
        const int w = p.info.width, h = p.info.height;
        const size_t n = size_t(w) * size_t(h);
        std::vector<uint32_t> words(n * kWordsPerPixel);
        Imf::FrameBuffer fb;
        const auto insert = [&](const std::vector<std::string>& names, std::vector<uint32_t>& data, int stride) {
            char* b = reinterpret_cast<char*>(data.data());
            for (size_t c = 0; c < names.size(); ++c) {
                if (!file.header().channels().findChannel(names[c]))
                    throw std::runtime_error("channel " + names[c] + " is missing");
                fb.insert(names[c], Imf::Slice(Imf::UINT, b + c * sizeof(uint32_t), stride * sizeof(uint32_t),
                                               stride * sizeof(uint32_t) * size_t(w)));
            }
        };
        insert(pixel_channel_names(), words, kWordsPerPixel);
        std::vector<int> layers;
        for (int l = 0; l < 1 + int(p.info.layer_names.size()); ++l)
            if (file.header().channels().findChannel(splat_channel_names(l)[0])) layers.push_back(l);
        std::vector<std::vector<uint32_t>> splat_words(layers.size(), std::vector<uint32_t>(n * kWordsPerSplat));
        for (size_t k = 0; k < layers.size(); ++k)
            insert(splat_channel_names(layers[k]), splat_words[k], kWordsPerSplat);
        file.setFrameBuffer(fb);
        file.readPixels(0, h - 1);
        p.film = Film(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const uint32_t* q = words.data() + (size_t(y) * w + x) * kWordsPerPixel;
                const Vec3 m(from_bits(get_u64(q + 20)), from_bits(get_u64(q + 22)), from_bits(get_u64(q + 24)));
                const bool inside = p.info.crop.contains(x, y);
                const uint64_t count = get_u64(q + 18);
                if (!inside && count > 0) throw std::runtime_error("samples outside its crop");
                p.film.set_pixel(x, y, get_sums(q), count, m, int(q[26]) - 1);
            }
        for (size_t k = 0; k < layers.size(); ++k)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    p.film.set_splat(layers[k], x, y,
                                     get_sums(splat_words[k].data() + (size_t(y) * w + x) * kWordsPerSplat));
        return p;
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot read partial film " + path + ": " + e.what());
    }
}

PartialFilm merge_partial_films(const std::vector<std::string>& paths, double* coverage) {
    if (paths.empty()) throw std::runtime_error("merge: no partial films");
    std::vector<PartialFilmInfo> parts;
    PartialFilm out;
    double held = 0;
    for (size_t k = 0; k < paths.size(); ++k) {
        PartialFilm p = read_partial_film(paths[k]);
        for (size_t j = 0; j < parts.size(); ++j) {
            if (const std::string m = mismatch(parts[j], p.info); !m.empty())
                throw std::runtime_error("merge: " + paths[k] + " is not a part of the render " + paths[j] +
                                         " is a part of: they differ in " + m);
            if (overlaps(parts[j], p.info))
                throw std::runtime_error("merge: " + paths[k] + " and " + paths[j] +
                                         " overlap (both hold samples of the same pixels)");
        }
        held += double(p.info.crop.width()) * p.info.crop.height() *
                double(std::min(p.info.sample_end, p.info.spp) - std::min(p.info.sample_begin, p.info.spp));
        if (k == 0)
            out = std::move(p);
        else
            out.film.merge(p.film);
        parts.push_back(k == 0 ? out.info : p.info);
    }
    // The merged film is of the whole render: its crop and range are the frame's.
    out.info.crop = {0, 0, out.info.width, out.info.height};
    out.info.sample_begin = 0;
    out.info.sample_end = out.info.spp;
    if (coverage)
        *coverage = held / (double(out.info.width) * out.info.height * double(std::max<uint64_t>(1, out.info.spp)));
    finish_film(out.film, out.info.max_sample_share, out.info.clamp_spread);
    return out;
}

}  // namespace snell
