#include "bsdf/fresnel.h"

namespace snell {

double fresnel_diffuse_reflectance(double eta) {
    // 5-point Gauss-Legendre on equal panels of each smooth piece; below the critical
    // cosine (eta < 1) R = 1 exactly, so the kink sits on a panel boundary.
    static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                0.5384693101056831, 0.9061798459386640};
    static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                0.4786286704993665, 0.2369268850561891};
    const double mu_c = eta < 1 ? std::sqrt(1 - eta * eta) : 0.0;
    double sum = mu_c * mu_c;  // integral of 2 mu over [0, mu_c] with R = 1
    const int panels = 256;
    const double h = (1 - mu_c) / panels;
    for (int p = 0; p < panels; ++p) {
        const double a = mu_c + p * h;
        for (int k = 0; k < 5; ++k) {
            const double mu = a + 0.5 * h * (x[k] + 1);
            sum += 0.5 * h * w[k] * 2 * mu * fresnel_dielectric(mu, eta).R;
        }
    }
    return sum;
}

}  // namespace snell
