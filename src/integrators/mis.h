#pragma once
// Multiple importance sampling weights (Veach & Guibas 1995).
#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace snell {

/// Power heuristic with beta = 2 for one sample from technique a and one from b.
inline double power_heuristic(double pdf_a, double pdf_b) {
    const double a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    if (a == 0) return 0.0;
    if (!(b < 1e300 * 1e300)) return 0.0;  // b infinite: the other technique owns the path
    return a / (a + b);
}

/// Power heuristic (beta = 2) of technique a among a and `others` (densities in one measure),
/// normalised by the largest density so that squaring cannot overflow. Infinite densities (a
/// delta the others cannot produce) share the path among themselves.
inline double power_heuristic(double a, std::initializer_list<double> others) {
    double m = a;
    for (double o : others) m = std::max(m, o);
    if (!(m > 0)) return 0.0;
    if (std::isinf(m)) {
        if (!std::isinf(a)) return 0.0;
        int n = 1;
        for (double o : others) n += std::isinf(o);
        return 1.0 / n;
    }
    const double wa = (a / m) * (a / m);
    double sum = wa;
    for (double o : others) sum += (o / m) * (o / m);
    return wa / sum;
}

}  // namespace snell
