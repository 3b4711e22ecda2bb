"""snell.read / write / diff / compare against the command line's."""

import json
import subprocess

import numpy as np
import pytest

import snell
from conftest import DROPLET


def test_exr_round_trip_is_exact(tmp_path):
    a = np.random.default_rng(1).random((5, 7, 3), dtype=np.float32) * 100
    snell.write(tmp_path / "a.exr", a)
    assert np.array_equal(snell.read(tmp_path / "a.exr"), a)


def test_png_round_trip_is_srgb(tmp_path):
    a = np.linspace(0, 1, 5 * 4 * 3, dtype=np.float32).reshape(5, 4, 3)
    snell.write(tmp_path / "a.png", a)
    b = snell.read(tmp_path / "a.png")
    assert b.shape == a.shape and np.max(np.abs(b - a)) < 0.01  # 8-bit sRGB steps, linearised back
    snell.write(tmp_path / "dark.png", a, exposure=-1)
    assert np.max(np.abs(snell.read(tmp_path / "dark.png") - a / 2)) < 0.01


def test_diff_is_snell_diff(tmp_path, snell_bin):
    scene = snell.load_file(DROPLET, res_x=64, res_y=48)
    a, b = scene.render(spp=2, seed=1), scene.render(spp=16, seed=2)
    snell.write(tmp_path / "a.exr", a)
    snell.write(tmp_path / "b.exr", b)
    cli = subprocess.run([snell_bin, "diff", str(tmp_path / "a.exr"), str(tmp_path / "b.exr"), "--crop", "8,8,32,16",
                          "--json"], capture_output=True, text=True, check=True)
    whole, crop = json.loads(cli.stdout)
    assert snell.diff(a, b) == pytest.approx(whole) and snell.diff(a, b)["region"] == "image"
    assert snell.diff(tmp_path / "a.exr", b, crop=(8, 8, 32, 16)) == crop
    same = snell.diff(a, a)
    assert same["rel_mse"] == 0 and same["psnr"] == float("inf")
    with pytest.raises(ValueError, match="sizes differ"):
        snell.diff(a, b[:10])
    with pytest.raises(ValueError, match="outside"):
        snell.diff(a, b, crop=(60, 40, 10, 10))


def test_compare_writes_the_report_and_returns_it(tmp_path):
    r = snell.compare(DROPLET, ["nee", "mnee"], time=0.3, out_dir=tmp_path / "cmp", reference_spp=4,
                      convergence_steps=0, res_x=32, res_y=24)
    assert [i["name"] for i in r["integrators"]] == ["nee", "mnee"]
    assert (tmp_path / "cmp" / "report.html").exists() and r["out_dir"] == str(tmp_path / "cmp")
    assert json.loads((tmp_path / "cmp" / "report.json").read_text())["integrators"][0]["name"] == "nee"
    with pytest.raises(ValueError, match="needs a reference"):
        snell.compare(DROPLET, ["nee"], time=0.3)
