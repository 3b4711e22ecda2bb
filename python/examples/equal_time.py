#!/usr/bin/env python3
"""Equal-time comparison of `nee` and `mnee` on the droplet, scripted with the snell module
(docs/python.md): one scene load, a reference by an independent technique (BDPT, run long),
then each integrator at a series of time budgets, scored with snell.diff and plotted against
time with matplotlib.

    PYTHONPATH=build-release/python python3 python/examples/equal_time.py \
        --out docs/images/python_equal_time.png
"""

import argparse
import json
import os
import sys
import time

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

import snell  # noqa: E402


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default=os.path.join(here, "..", "..", "scenes", "droplet", "droplet.xml"))
    ap.add_argument("--res", default="320x240", help="film size WxH")
    ap.add_argument("--budgets", default="1,2,4,8,16", help="seconds per render, comma-separated")
    ap.add_argument("--reference-time", type=float, default=360, help="seconds of BDPT for the reference")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--crop", default="230,190,190,110",
                    help="x,y,w,h at 640x480 of the caustic under the droplet (scaled with the film)")
    ap.add_argument("--out", default="equal_time.png", help="the plot (PNG); a .json of the numbers beside it")
    args = ap.parse_args()
    w, h = (int(v) for v in args.res.split("x"))
    budgets = [float(b) for b in args.budgets.split(",")]
    crop = [round(int(v) * (w / 640 if i % 2 == 0 else h / 480)) for i, v in enumerate(args.crop.split(","))]

    t0 = time.monotonic()
    scene = snell.load_file(args.scene, res_x=w, res_y=h)
    print(f"loaded {scene} in {time.monotonic() - t0:.2f} s", file=sys.stderr)
    # The scene's own integrator parameters, for every technique, so that only the technique differs.
    common = {"max_depth": 12, "spectral_samples": 4}

    def progress(f, eta):
        print(f"\r  reference {100 * f:5.1f} %", end="", file=sys.stderr, flush=True)

    ref = scene.render(integrator={"type": "bdpt", **common}, time=args.reference_time, seed=0x5EED,
                       threads=args.threads, progress=progress)
    print(f"\n  reference: bdpt, {ref.stats['spp_reached']} spp in {ref.stats['seconds']:.0f} s", file=sys.stderr)

    rows = []
    for name in ("nee", "mnee"):
        for t in budgets:
            img = scene.render(integrator={"type": name, **common}, time=t, threads=args.threads)
            m, c = snell.diff(img, ref), snell.diff(img, ref, crop=crop)
            rows.append({"integrator": name, "budget_s": t, "seconds": img.stats["seconds"],
                         "spp": img.stats["spp_mean"], "rel_mse": m["rel_mse"],
                         "median_rel_error": m["median_rel_error"], "psnr": m["psnr"],
                         "caustic_rel_mse": c["rel_mse"], "caustic_median_rel_error": c["median_rel_error"]})
            print(f"  {name:5s} {t:5.1f} s  {img.stats['spp_mean']:7.1f} spp  relMSE {m['rel_mse']:.4g}  "
                  f"median error {m['median_rel_error']:.4g}  PSNR {m['psnr']:.2f} dB  caustic relMSE "
                  f"{c['rel_mse']:.4g}  median {c['median_rel_error']:.4g}", file=sys.stderr)

    fig, axes = plt.subplots(1, 3, figsize=(12, 3.6), constrained_layout=True)
    panels = ((axes[0], "rel_mse", "relMSE, image"), (axes[1], "caustic_rel_mse", "relMSE, caustic crop"),
              (axes[2], "median_rel_error", "per-pixel median error, image"))
    for ax, key, label in panels:
        for name, style in (("nee", "o-"), ("mnee", "s-")):
            pts = [(r["seconds"], r[key]) for r in rows if r["integrator"] == name]
            ax.loglog(*zip(*pts), style, label=name)
        ax.set_xlabel("render time (s)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle(f"droplet {w}x{h}: error against a {ref.stats['seconds']:.0f} s BDPT reference")
    fig.savefig(args.out, dpi=110)
    with open(os.path.splitext(args.out)[0] + ".json", "w") as f:
        json.dump({"reference": {k: ref.stats[k] for k in ("integrator", "seconds", "spp_reached")}, "crop": crop,
                   "rows": rows},
                  f, indent=1)
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
