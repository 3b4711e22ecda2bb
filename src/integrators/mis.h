#pragma once
// Multiple importance sampling weights (Veach & Guibas 1995).

namespace snell {

/// Power heuristic with beta = 2 for one sample from technique a and one from b.
inline double power_heuristic(double pdf_a, double pdf_b) {
    const double a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    if (a == 0) return 0.0;
    if (!(b < 1e300 * 1e300)) return 0.0;  // b infinite: the other technique owns the path
    return a / (a + b);
}

}  // namespace snell
