#pragma once
// MNEE's MIS cutoff (MneeSettings::mis_cutoff; issue 26, point 5).

namespace snell {

/// Veach's cutoff heuristic (his thesis, Ch. 9), read through a bound: a technique whose density
/// at a path is at most `bound` keeps no weight there where the other techniques' density exceeds
/// `ratio` times that bound; the others then share the path among themselves. The bound is a
/// function of the path, so every technique's side of the path cuts alike and the weights still
/// sum to one, and a side that would have to work for the bounded technique's density (MNEE's:
/// a walk, Alg. 2) or for its weight (a 1 / p count) need not where the path is cut. ratio 0:
/// never cut.
inline bool mis_cut_off(double p_others, double bound, double ratio) { return ratio > 0 && p_others > ratio * bound; }

}  // namespace snell
