#!/usr/bin/env python3
"""Writes summary.md for the experiment scripts from `snell compare`'s report.json, or from the
`snell render` stats JSON and `snell diff --json` output when compare is unavailable.

  summarize.py equal_time OUT TITLE [CROP_LABEL...]   rows from OUT/report/
  summarize.py roughness OUT TITLE ALPHA...           one equal-time comparison per OUT/alpha_<a>/
  summarize.py table1 OUT TITLE                       rows from OUT/t1_<iterations>_<A|B>.json
"""
import glob
import json
import os
import sys


def rows_of(report_dir):
    """Per integrator: name, spp reached, seconds, [(relMSE, PSNR) per region], PNG path."""
    rows = []
    rj = os.path.join(report_dir, "report.json")
    if os.path.exists(rj):
        for i in json.load(open(rj))["integrators"]:
            rows.append(dict(name=i["name"], spp=i["spp_reached"], seconds=i["seconds"],
                             regions=[(m["rel_mse"], m["psnr"]) for m in i["metrics"]],
                             png=os.path.join(report_dir, i["image_png"])))
    else:
        for diff in sorted(glob.glob(os.path.join(report_dir, "*.diff.json"))):
            name = os.path.basename(diff)[: -len(".diff.json")]
            stats = json.load(open(os.path.join(report_dir, name + ".json")))
            rows.append(dict(name=name, spp=stats["spp_reached"], seconds=stats["seconds"],
                             regions=[(m["rel_mse"], m["psnr"]) for m in json.load(open(diff))],
                             png=os.path.join(report_dir, name + ".png")))
    rows.sort(key=lambda r: -r["regions"][0][1])  # by PSNR over the image, as Fig. 5
    return rows


def equal_time(out, title, labels):
    rows = rows_of(os.path.join(out, "report"))
    regions = ["image"] + labels
    md = ["# " + title, "", "Sorted by PSNR over the whole image; relMSE and PSNR as `snell diff` computes them (docs/rendering.md).", ""]
    md.append("| rank | integrator | spp | seconds | " + " | ".join("relMSE %s | PSNR %s" % (r, r) for r in regions) + " |")
    md.append("|---" * (4 + 2 * len(regions)) + "|")
    for k, r in enumerate(rows, 1):
        cells = ["%.4g | %.2f" % reg for reg in r["regions"]]
        md.append("| %d | %s | %d | %.2f | %s |" % (k, r["name"], r["spp"], r["seconds"], " | ".join(cells)))
    md.append("")
    if os.path.exists(os.path.join(out, "report", "report.html")):
        md.append("Full report: [report/report.html](report/report.html)")
        md.append("")
    for r in rows:
        md.append("![%s](%s)" % (r["name"], os.path.relpath(r["png"], out)))
    md.append("")
    return md, rows


def roughness(out, title, alphas):
    md = ["# " + title, "", "PSNR / relMSE over the whole image against a long mnee reference at each alpha.", "",
          "| alpha | nee spp | nee PSNR | nee relMSE | mnee spp | mnee PSNR | mnee relMSE | better by PSNR | better by relMSE |",
          "|---|---|---|---|---|---|---|---|---|"]
    images = []
    for a in alphas:
        rows = {r["name"]: r for r in rows_of(os.path.join(out, "alpha_" + a, "report"))}
        n, m = rows["nee"], rows["mnee"]
        by_psnr = "mnee" if m["regions"][0][1] > n["regions"][0][1] else "nee"
        by_relmse = "mnee" if m["regions"][0][0] < n["regions"][0][0] else "nee"
        md.append("| %s | %d | %.2f | %.4g | %d | %.2f | %.4g | %s | %s |" % (
            a, n["spp"], n["regions"][0][1], n["regions"][0][0], m["spp"], m["regions"][0][1], m["regions"][0][0],
            by_psnr, by_relmse))
        images.append("alpha %s: ![nee](%s) ![mnee](%s)" % (
            a, os.path.relpath(n["png"], out), os.path.relpath(m["png"], out)))
    return md + [""] + images + [""], None


def table1(out, title):
    md = ["# " + title, "",
          "A: the error must decrease every step; B: it may increase temporarily (over-relaxation).",
          "Walk seconds are summed over all threads; render seconds are wall-clock.", "",
          "| max iterations | variant | walk seconds | render seconds | mean iterations (success) | success rate | walks |",
          "|---|---|---|---|---|---|---|"]
    for it in (5, 10, 20, 35, 50):
        for var in ("A", "B"):
            d = json.load(open(os.path.join(out, "t1_%d_%s.json" % (it, var))))
            m = d["extra"]["mnee"]
            md.append("| %d | %s | %.2f | %.2f | %.2f | %.1f%% | %d |" % (
                it, var, m["walk_seconds"], d["seconds"], m["mean_iterations_success"],
                100 * m["success_rate"], m["walks_started"]))
    return md + [""], None


def main():
    mode, out, title = sys.argv[1:4]
    extra = sys.argv[4:]
    md, _ = {"equal_time": lambda: equal_time(out, title, extra),
             "roughness": lambda: roughness(out, title, extra),
             "table1": lambda: table1(out, title)}[mode]()
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(md))


if __name__ == "__main__":
    main()
