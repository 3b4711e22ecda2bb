"""Scene.render: the array, its stats, the integrator it renders with, and the command line's
image bit for bit."""

import json
import os
import subprocess

import numpy as np
import pytest

import snell
from conftest import DROPLET, SMALL


def test_render_returns_a_view_of_the_film(droplet):
    img = droplet.render(spp=2)
    assert img.shape == (48, 64, 3)
    assert img.dtype == np.float32
    assert isinstance(img, snell.Image)
    assert isinstance(img.base, snell.Film) and img.base is img.film  # no copy: the film's buffer
    assert np.shares_memory(img, np.asarray(img.film))
    assert np.all(np.isfinite(img)) and float(img.mean()) > 0
    # Slices keep the film; arithmetic is a plain array.
    assert img[10:20].film is img.film
    assert type(img * 2) is np.ndarray


def test_image_outlives_its_scene():
    img = snell.load_file(DROPLET, **SMALL).render(spp=1)
    assert img.shape == (48, 64, 3) and float(img.sum()) > 0


def test_bit_identical_to_the_command_line(droplet, snell_bin, tmp_path):
    out = tmp_path / "cli.exr"
    subprocess.run(
        [snell_bin, "render", DROPLET, "-D", "res_x=64", "-D", "res_y=48", "--spp", "3", "--seed", "7", "-t", "1",
         "-q", "-o", str(out)],
        check=True,
    )
    img = droplet.render(spp=3, seed=7, threads=2)
    assert np.array_equal(snell.read(out), img)  # EXRs are 32-bit float: exact
    snell.write(tmp_path / "py.exr", img)
    assert (tmp_path / "py.exr").read_bytes() == out.read_bytes()
    # The stats are the stats JSON's fields.
    cli = json.loads((tmp_path / "cli.json").read_text())
    assert set(img.stats) == set(cli)
    for key in ("integrator", "width", "height", "spp_requested", "spp_reached", "seed", "paths", "rays"):
        assert img.stats[key] == cli[key], key


def test_defaults_are_the_scenes_as_on_the_command_line(droplet):
    assert droplet.spp == 64 and droplet.integrator == "mnee"
    a = snell.load_file(DROPLET, res_x=16, res_y=12, spp=2).render()
    assert a.stats["spp_reached"] == 2 and a.shape == (12, 16, 3)


def test_defines_as_keywords():
    s = snell.load_file(DROPLET, res_x=32, res_y=24, integrator="nee", max_depth=4)
    assert (s.width, s.height, s.integrator) == (32, 24, "nee")
    with pytest.raises(TypeError, match="define res_x"):
        snell.load_file(DROPLET, res_x=[32])


def test_integrator_name_or_dict_overrides_the_scenes(droplet):
    scene_img = droplet.render(spp=2)
    assert scene_img.stats["integrator"] == "mnee"
    nee = droplet.render(spp=2, integrator="nee")
    assert nee.stats["integrator"] == "nee"
    biased = droplet.render(spp=2, integrator={"type": "mnee", "biased": True, "max_depth": 12})
    assert biased.stats["integrator"] == "mnee-biased"
    direct = droplet.render(spp=2, integrator={"type": "path", "max_depth": 1})
    deep = droplet.render(spp=2, integrator={"type": "path", "max_depth": 8})
    assert float(direct.mean()) < float(deep.mean())  # the parameter reached the integrator
    assert not np.array_equal(biased, nee)
    # The scene itself is unchanged by an override.
    assert np.array_equal(droplet.render(spp=2), scene_img)


def test_bdpt_strategies_and_dominance(droplet):
    img = droplet.render(spp=1, integrator="bdpt", strategies=True)
    layers = img.layers
    assert layers and all(k.count("_") == 2 for k in layers)
    for a in layers.values():
        assert a.shape == img.shape and a.dtype == np.float32 and a.base is img.film
    m = droplet.render(spp=4)
    d = m.dominance
    assert d["technique"].shape == (48, 64) and d["share"].shape == (48, 64)
    assert "pixels_dominated" in d or "pixels" in d
    assert d["techniques"] and int(d["technique"].max()) < len(d["techniques"])
    assert set(np.unique(d["technique"])) <= set(range(-1, len(d["techniques"])))
    assert np.all(d["samples"] == 4) and np.all(d["largest_y"] >= 0)
    lit = d["share"] > 1e-3
    # No clamp and no splats here: largest Y / share is the pixel's sample sum, over the count its
    # mean, which is the image pixel's luminance.
    y = np.asarray(m) @ np.array([0.2126, 0.7152, 0.0722])
    mean_y = d["largest_y"][lit] / d["share"][lit] / d["samples"][lit]
    assert np.allclose(mean_y, y[lit], rtol=2e-3, atol=1e-6)


def test_progress_is_called_throttled_and_ends_at_one(droplet):
    calls = []
    img = droplet.render(time=1.0, progress=lambda f, eta: calls.append((f, eta)))
    assert 2 <= len(calls) <= 1.0 / 0.2 + 3
    fractions = [f for f, _ in calls]
    assert fractions == sorted(fractions) and 0 <= fractions[0] and fractions[-1] == pytest.approx(1.0, abs=0.05)
    assert all(eta is None or eta >= 0 for _, eta in calls)
    assert calls[-1][1] == 0.0 and not img.interrupted


def test_a_raising_progress_callback_stops_the_render(droplet):
    def cb(f, eta):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here") as e:
        droplet.render(spp=4096, progress=cb)
    assert e.value.image.interrupted and e.value.image.shape == (48, 64, 3)


def test_stop_handle_returns_the_partial_image(droplet):
    import threading

    stop = snell.StopHandle()
    threading.Timer(0.5, stop.stop).start()
    img = droplet.render(spp=1 << 20, stop=stop)
    assert stop.stopped and img.interrupted and img.stats["interrupted"]
    assert img.stats["seconds"] < 20 and float(img.sum()) > 0


def test_a_progress_callback_may_not_render(droplet):
    def cb(f, eta):
        droplet.render(spp=1)

    with pytest.raises(RuntimeError, match="progress callback"):
        droplet.render(spp=64, progress=cb)
