// Environment map emitter (:monosp:`envmap`), Mitsuba 3 semantics.
//
// | parameter | type      | meaning                                                         |
// |-----------|-----------|-----------------------------------------------------------------|
// | filename  | string    | latitude-longitude OpenEXR image of radiance (linear sRGB)     |
// | scale     | float     | factor applied to the radiance values (default 1)               |
// | to_world  | transform | emitter-to-world rotation; local +y is the map's up axis        |
//
//   <emitter type="envmap"> <string name="filename" value="sky.exr"/>
//       <float name="scale" value="2"/> </emitter>
//
// The direction <-> pixel convention is documented on EnvironmentMap (envmap.h).
#include "light/envmap.h"

#include <cmath>
#include <stdexcept>

#include "light/rgb_illuminant_table.h"

namespace snell {

namespace {

// Integral over [a, b] of the unit hat function centred at k (support [k-1, k+1]).
double hat_integral(double a, double b, double k) {
    auto G = [](double t) {  // antiderivative of max(0, 1 - |t|), 0 at t = -1
        if (t <= -1) return 0.0;
        if (t >= 1) return 1.0;
        return t < 0 ? 0.5 * sqr(t + 1) : 1.0 - 0.5 * sqr(1 - t);
    };
    return G(b - k) - G(a - k);
}

RGB clean_rgb(const Image& img, int x, int y) {
    auto ok = [](float v) { return std::isfinite(v) && v > 0 ? double(v) : 0.0; };
    return {ok(img.at(x, y, 0)), ok(img.at(x, y, 1)), ok(img.at(x, y, 2))};
}

}  // namespace

Vec2 EnvironmentMap::direction_to_uv(const Vec3& d) {
    double u = std::atan2(d.x, -d.z) * kInv2Pi;
    if (u < 0) u += 1;
    if (u >= 1) u = 0;
    return {u, std::acos(clamp(d.y, -1.0, 1.0)) * kInvPi};
}

Vec3 EnvironmentMap::uv_to_direction(const Vec2& uv) {
    const double theta = uv.y * kPi, phi = uv.x * 2 * kPi;
    const double st = std::sin(theta);
    return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
}

EnvironmentMap::EnvironmentMap(Image image, double scale, const Transform& to_world)
    : m_image(std::move(image)), m_scale(scale), m_to_world(to_world), m_to_local(to_world.inverse()) {
    const int W = m_image.width, H = m_image.height;
    if (W < 2 || H < 3) throw std::invalid_argument("environment map must be at least 2x3 pixels");
    if (m_image.rgb.size() != size_t(3) * size_t(W) * size_t(H))
        throw std::invalid_argument("environment map: pixel buffer size does not match its resolution");
    // Non-finite and negative values carry no meaningful radiance: store them as 0.
    for (float& v : m_image.rgb)
        if (!(std::isfinite(v) && v > 0)) v = 0;

    std::vector<double> lum(size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) lum[size_t(y) * W + x] = clean_rgb(m_image, x, y).luminance();

    // Bin (i, j) covers u in [i/W, (i+1)/W), v in [j/H, (j+1)/H). In texel-node units it spans
    // x in [i - 1/2, i + 1/2] (nodes i-1, i, i+1 with hat integrals 1/8, 3/4, 1/8) and
    // y in [j (H-1)/H, (j+1) (H-1)/H]. The bin value is the exact integral of the bilinear
    // luminance over the bin (in du dv) times the bin's mean sin(theta).
    std::vector<double> f(size_t(W) * H, 0.0);
    double total = 0;
    for (int j = 0; j < H; ++j) {
        const double lo = double(j) * (H - 1) / H, hi = double(j + 1) * (H - 1) / H;
        const double th0 = kPi * j / H, th1 = kPi * (j + 1) / H;
        const double mean_sin = (std::cos(th0) - std::cos(th1)) / (th1 - th0);
        const int k0 = std::max(0, int(std::floor(lo))), k1 = std::min(H - 1, int(std::ceil(hi)));
        for (int i = 0; i < W; ++i) {
            double s = 0;
            for (int k = k0; k <= k1; ++k) {
                const double wy = hat_integral(lo, hi, k) / (H - 1);  // dy -> dv
                if (wy <= 0) continue;
                const double* row = &lum[size_t(k) * W];
                const double lx = 0.125 * row[(i + W - 1) % W] + 0.75 * row[i] + 0.125 * row[(i + 1) % W];
                s += wy * lx / W;  // dx -> du
            }
            f[size_t(j) * W + i] = s * mean_sin;
            total += s * mean_sin;
        }
    }
    // d(omega) = sin(theta) d(theta) d(phi) = 2 pi^2 sin(theta) du dv.
    m_luminance_integral = 2 * kPi * kPi * total;
    m_dist = Distribution2D(f, size_t(W), size_t(H));
    (void)RGBIlluminantTable::get();  // build the lattice now rather than during rendering
}

RGB EnvironmentMap::lookup_rgb(const Vec2& uv) const {
    const int W = m_image.width, H = m_image.height;
    // Column centres at u = (i + 1/2) / W (periodic); rows on v = j / (H - 1).
    double x = uv.x * W - 0.5;
    x -= std::floor(x / W) * W;
    const double y = clamp(uv.y, 0.0, 1.0) * (H - 1);
    const int ix = std::min(W - 1, int(x)), iy = std::min(H - 2, int(y));
    const int ix1 = (ix + 1) % W;
    const double fx = x - ix, fy = y - iy;
    RGB out;
    const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    const int xs[4] = {ix, ix1, ix, ix1}, ys[4] = {iy, iy, iy + 1, iy + 1};
    for (int c = 0; c < 4; ++c) {
        if (w[c] == 0) continue;
        out.r += w[c] * m_image.at(xs[c], ys[c], 0);
        out.g += w[c] * m_image.at(xs[c], ys[c], 1);
        out.b += w[c] * m_image.at(xs[c], ys[c], 2);
    }
    return out;
}

Vec3 EnvironmentMap::sample_direction(const Vec2& u, double* pdf, Vec2* uv_out) const {
    double pdf_uv = 0;
    const Vec2 uv = m_dist.sample(u, &pdf_uv);
    const double sin_theta = std::sin(uv.y * kPi);
    if (uv_out) *uv_out = uv;
    if (!(pdf_uv > 0) || !(sin_theta > 0)) {
        *pdf = 0;
        return Vec3(0, 1, 0);
    }
    *pdf = pdf_uv / (2 * kPi * kPi * sin_theta);  // Jacobian of (u, v) -> direction
    return normalize(m_to_world.vector(uv_to_direction(uv)));
}

std::optional<LightSample> EnvironmentMap::sample_li(const LightSampleContext& ref, const Vec2& u,
                                                     const SampledWavelengths& wl) const {
    LightSample ls;
    Vec2 uv;
    ls.wi = sample_direction(u, &ls.pdf, &uv);
    if (!(ls.pdf > 0)) return std::nullopt;
    // Bins next to black texels can yield directions whose radiance is exactly 0.
    ls.Le = m_scale * RGBIlluminantTable::get().eval(lookup_rgb(uv), wl);
    if (ls.Le.is_zero()) return std::nullopt;
    ls.p = ref.p + ls.wi * m_sphere.far_distance(ref.p);
    ls.dist = kInfinity;
    return ls;
}

double EnvironmentMap::pdf_li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3& wi) const {
    const Vec3 d = normalize(m_to_local.vector(wi));
    const double sin_theta = std::sqrt(d.x * d.x + d.z * d.z);
    if (!(sin_theta > 0)) return 0;
    return m_dist.pdf(direction_to_uv(d)) / (2 * kPi * kPi * sin_theta);
}

SampledSpectrum EnvironmentMap::le_escaped(const Vec3& d, const SampledWavelengths& wl) const {
    const Vec2 uv = direction_to_uv(normalize(m_to_local.vector(d)));
    return m_scale * RGBIlluminantTable::get().eval(lookup_rgb(uv), wl);
}

double EnvironmentMap::power() const {
    // Luminance of RGB approximates the mean spectral value of its upsampled spectrum in units
    // of the white illuminant's mean.
    static const double white_avg = Spectrum::from_rgb_illuminant(RGB(1.0)).average();
    return m_scale * white_avg * m_luminance_integral * kPi * sqr(m_sphere.radius);
}

}  // namespace snell
