#!/usr/bin/env python3
"""Where a render's fireflies come from (issue 26, docs/experiments.md "make demo's fireflies"):
pixels dominated by one sample (its share of the pixel over 1/2), counted by the technique that
delivered that sample, by the path length the integrator may reach (max_depth), and by whether
the camera sees the droplet there; with a plot of where they sit.

    PYTHONPATH=build-release/python python3 python/examples/firefly_census.py --out fireflies.png
"""

import argparse
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import snell  # noqa: E402

DROPLET = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "droplet", "droplet.xml")
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def silhouette(xml, res):
    """Pixels where the camera sees the droplet: the droplet made black, lit by one bounce."""
    black = re.sub(r'<bsdf type="roughdielectric">.*?</bsdf>',
                   '<bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>', xml, flags=re.S)
    img = snell.load_string(black, base_dir=os.path.dirname(DROPLET), **res).render(
        spp=4, integrator={"type": "path", "max_depth": 2})
    return np.asarray(img).mean(axis=2) < 1e-6


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--res", default="320x240")
    ap.add_argument("--spp", type=int, default=48)
    ap.add_argument("--depths", default="4,5,6,12", help="max_depth values to count at (the scene's is 12)")
    ap.add_argument("--out", default="fireflies.png")
    args = ap.parse_args()
    w, h = (int(v) for v in args.res.split("x"))
    res = {"res_x": w, "res_y": h}
    scene = snell.load_file(DROPLET, **res)
    inside = silhouette(open(DROPLET).read(), res)

    print(f"{'max_depth':>9} {'dominated':>9} {'mean Y':>8}  by technique (in the droplet's silhouette / outside)")
    for depth in (int(d) for d in args.depths.split(",")):
        img = scene.render(spp=args.spp, integrator={"type": "mnee", "max_depth": depth, "spectral_samples": 4})
        d = img.dominance
        dom = d["share"] > 0.5
        parts = []
        for t, name in enumerate(d["techniques"]):
            sel = dom & (d["technique"] == t)
            if sel.any():
                parts.append(f"{name} {sel.sum()} ({np.sum(sel & inside)}/{np.sum(sel & ~inside)})")
        print(f"{depth:9d} {dom.sum():9d} {float((np.asarray(img) @ LUMINANCE).mean()):8.5f}  "
              + ", ".join(parts))
    # MNEE's light by the vertex it connects from (x_b's index on the camera path): the solutions'
    # counts, and their shares of MNEE's mean and second moment (per camera path).
    c, paths = img.stats["counters"], img.stats["paths"]
    rows = []
    for k in sorted(k for k in c if k.startswith("mnee.contribution.")):
        m = c[k]
        n = m["count"]
        rows.append((k.split(".")[-1], n, n * m["mean"] / paths,
                     n * m["mean"] ** 2 * (1 + m["relative_variance"]) / paths, m["max"]))
    m1, m2 = sum(r[2] for r in rows), sum(r[3] for r in rows)
    print(f"max_depth {depth}: MNEE's solutions by x_b's vertex   count   mean share   2nd-moment share   largest")
    for name, n, a, b, mx in rows:
        print(f"  {name:10s} {n:>36d} {a / m1:12.3f} {b / m2:18.3f} {mx:9.3g}")
    # `img` is the last (deepest) render: where its fireflies sit, over its log luminance.
    y = np.asarray(img) @ LUMINANCE
    fig, ax = plt.subplots(figsize=(7, 5.4), constrained_layout=True)
    ax.imshow(np.log10(y + 1e-4), cmap="gray")
    for name, colour in (("mnee_straight", "r"), ("mnee_surface", "y"), ("nee", "c"), ("bsdf_refracted", "m"),
                         ("bsdf_reflected", "g")):
        t = d["techniques"].index(name)
        ys, xs = np.nonzero(dom & (d["technique"] == t))
        ax.scatter(xs, ys, s=5, c=colour, label=f"{name} ({len(xs)})")
    ax.legend(loc="lower left", fontsize=8)
    ax.set_title(f"pixels dominated by one sample, max_depth {depth}, {args.spp} spp")
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
