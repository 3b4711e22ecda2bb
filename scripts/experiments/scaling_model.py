#!/usr/bin/env python3
"""The scaling model of docs/distributed.md ("Scaling"): expected parallel efficiency of one frame
over N MPI nodes, from a few measured quantities. Every input is an option, so a user can put in
the numbers of their own scene and cluster; the defaults are the ones measured on the droplet
(docs/distributed.md, "Measured on this machine").

  scripts/experiments/scaling_model.py                       # a 4K frame at 4,096 spp
  scripts/experiments/scaling_model.py --spp 65536 --nodes 16 64 1024
"""
import argparse
import math

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--width", type=int, default=3840)
ap.add_argument("--height", type=int, default=2160)
ap.add_argument("--spp", type=int, default=4096)
ap.add_argument("--threads", type=int, default=32, help="threads per node")
ap.add_argument("--nodes", type=int, nargs="+", default=[1, 2, 16, 64, 1024])
ap.add_argument("--sample-cost", type=float, default=6.63e-6, help="seconds per camera sample per thread")
ap.add_argument("--dearest", type=float, default=5.1, help="dearest tile over the mean tile (cost ratio r)")
ap.add_argument("--service", type=float, default=5e-6, help="rank 0's seconds per tile request")
ap.add_argument("--startup", type=float, default=1.0, help="seconds per rank to start: MPI, scene, BVH")
ap.add_argument("--bandwidth", type=float, default=1.25e9, help="bytes/s between nodes (10 Gb/s)")
ap.add_argument("--merge-rate", type=float, default=0.4e9, help="bytes/s a rank packs and adds films (measured)")
ap.add_argument("--splat-layers", type=int, default=0, help="splat layers in use (bdpt: 1)")
a = ap.parse_args()

TILE, CHUNK, PILOT = 16, 16, 8  # tile side, samples per item past the pilot, pilot samples
P = a.width * a.height
tiles = math.ceil(a.width / TILE) * math.ceil(a.height / TILE)
T1 = P * a.spp * a.sample_cost / a.threads  # one node, seconds
film_bytes = P * (112 + 72 * a.splat_layers)
item = TILE * TILE * CHUNK * a.sample_cost  # mean item (16 samples of one tile), one thread
# The pass schedule 1, 1, 2, 4, 8, 16, 16, ...: passes of an equal-time render.
passes = 5 + max(0, a.spp - 16 + 15) // 16


def guided_requests(items, ranks, threads):
    """Requests rank 0 answers when every rank is granted remaining / (4 N T) items, at least 1
    and at most T (mpi_team.cpp, grant_size)."""
    n, remaining = 0, items
    while remaining > 0:
        g = min(threads, max(1, remaining // (4 * ranks * threads)))
        # All ranks ask at about the same rate: a round of N requests takes N grants.
        take = min(remaining, g * ranks)
        n += math.ceil(take / g)
        remaining -= take
    return n


print(f"{a.width}x{a.height} ({P / 1e6:.2f} Mpx), {a.spp} spp, {a.threads} threads per node: "
      f"{P * a.spp * a.sample_cost / 3600:.1f} thread-hours, one node {T1:.0f} s; "
      f"{tiles} tiles per pass; film {film_bytes / 1e9:.2f} GB per rank")
print(f"{'nodes':>6} {'compute s':>10} {'tail s':>7} {'pilot s':>8} {'dispatch':>9} {'reduce s':>9} "
      f"{'E fixed spp':>12} {'E tree':>7} {'E --time':>9}")
for N in a.nodes:
    threads = N * a.threads
    compute = T1 / N
    # Fixed spp: past the pilot the passes run as one, so the ranks wait once, for the dearest
    # item in flight at the end (half of one on average per thread).
    tail = a.dearest * item / 2 if N > 1 else 0.0
    # The pilot's passes (1, 1, 2, 4 samples) are split statically, tile t on rank t mod N: each
    # pass lasts at least the dearest tile-pass, and a rank's share of tiles varies.
    pilot_tile = TILE * TILE * a.sample_cost
    k_pilot = tiles / threads
    pilot = 0.0
    if N > 1:
        for ps in (1, 1, 2, 4):
            ideal = k_pilot * ps * pilot_tile
            pilot += max(ideal + a.dearest * ps * pilot_tile / 2, a.dearest * ps * pilot_tile) - ideal
    # Rank 0's dispatcher: its busy time per request; stalls when it is busier than the render.
    items = tiles * math.ceil(max(0, a.spp - PILOT) / CHUNK)
    busy = guided_requests(items, N, a.threads) * a.service if N > 1 else 0.0
    stall = max(0.0, busy - compute)
    # One reduction at the end: pipelined (about twice the film over the link and through the
    # merge), or a plain binomial tree (log2 N levels of one film each).
    per_film = film_bytes / a.bandwidth + film_bytes / a.merge_rate
    reduce_pipe = 2 * per_film if N > 1 else 0.0
    reduce_tree = math.log2(N) * per_film if N > 1 else 0.0
    start = a.startup if N > 1 else 0.0
    base = compute + tail + pilot + stall + start
    E = T1 / (N * (base + reduce_pipe))
    E_tree = T1 / (N * (base + reduce_tree))
    # --time (the pass imbalance alone): every pass ends with the ranks waiting for the dearest
    # tile-pass in flight; with k tiles per thread a pass lasts k mean tile-passes plus half a
    # dearest one, and at least one dearest one.
    k = tiles / threads
    idle_frac = max(a.dearest / (2 * k), a.dearest / k - 1)
    E_time = 1 / (1 + idle_frac) if N > 1 else 1.0
    print(f"{N:>6} {compute:>10.1f} {tail:>7.2f} {pilot:>8.2f} {busy:>8.1f}s {reduce_pipe:>9.1f} "
          f"{E:>12.3f} {E_tree:>7.3f} {E_time:>9.3f}")
