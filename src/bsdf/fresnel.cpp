#include "bsdf/fresnel.h"

namespace snell {

double fresnel_diffuse_reflectance(double eta) {
    // 5-point Gauss-Legendre on equal panels. Below the critical cosine (eta < 1) R = 1
    // exactly; above it R has a square-root kink, removed by mu = mu_c + (1 - mu_c) t^2.
    static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                0.2369268850561891};
    const double mu_c = eta < 1 ? std::sqrt(1 - eta * eta) : 0.0;
    double sum = mu_c * mu_c;  // integral of 2 mu over [0, mu_c] with R = 1
    const int panels = 64;
    const double h = 1.0 / panels;
    for (int p = 0; p < panels; ++p)
        for (int k = 0; k < 5; ++k) {
            const double t = (p + 0.5 * (x[k] + 1)) * h;
            const double mu = mu_c + (1 - mu_c) * t * t, dmu_dt = 2 * (1 - mu_c) * t;
            sum += 0.5 * h * w[k] * 2 * mu * fresnel_dielectric(mu, eta).R * dmu_dt;
        }
    return sum;
}

}  // namespace snell
