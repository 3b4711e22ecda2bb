"""Every kind of error raises a Python exception with the command line's message."""

import subprocess

import pytest

import snell
from conftest import DROPLET


def test_missing_file():
    with pytest.raises(FileNotFoundError, match="cannot open scene file '/no/such/scene.xml'"):
        snell.load_file("/no/such/scene.xml")


def test_malformed_scene_names_file_line_like_the_cli(tmp_path, snell_bin):
    bad = tmp_path / "bad.xml"
    bad.write_text('<scene version="3.0.0">\n  <bsdf type="nosuch"/>\n</scene>\n')
    with pytest.raises(snell.SceneError) as e:
        snell.load_file(bad)
    msg = str(e.value)
    assert msg.startswith(f"{bad}:2: <bsdf>: unknown BSDF type 'nosuch'")
    cli = subprocess.run([snell_bin, "render", str(bad), "-o", str(tmp_path / "x.exr")], capture_output=True, text=True)
    assert cli.returncode == 1 and f"snell: error: {msg}" in cli.stderr
    assert isinstance(e.value, ValueError)


def test_unclosed_xml_and_string_scenes():
    with pytest.raises(snell.SceneError, match=r"<string>:\d+"):
        snell.load_string('<scene version="3.0.0">\n<shape type="sphere">\n</scene>')


def test_missing_mesh_names_the_path(tmp_path):
    s = tmp_path / "mesh.xml"
    s.write_text('<scene version="3.0.0">\n<shape type="obj">\n<string name="filename" value="gone.obj"/>\n</shape>\n</scene>\n')
    with pytest.raises(snell.SceneError, match="gone.obj"):
        snell.load_file(s)


def test_unknown_define_value_is_the_loaders_error():
    with pytest.raises(snell.SceneError, match=r"droplet.xml:\d+: <integer>: .wide. is not an integer"):
        snell.load_file(DROPLET, res_x="wide")


def test_bad_integrator_type_and_parameter(droplet):
    with pytest.raises(snell.SceneError, match="nosuch"):
        droplet.render(spp=1, integrator="nosuch")
    with pytest.raises(snell.SceneError, match="'bogus'"):
        droplet.render(spp=1, integrator={"type": "mnee", "bogus": 3})
    with pytest.raises(snell.SceneError, match="needs a 'type'"):
        droplet.render(spp=1, integrator={"biased": True})
    with pytest.raises(snell.SceneError, match="expected a bool, int, float or str"):
        droplet.render(spp=1, integrator={"type": "mnee", "biased": [1]})
    with pytest.raises(TypeError, match="integrator"):
        droplet.render(spp=1, integrator=3)


@pytest.mark.parametrize(
    "kwargs, exc, match",
    [
        ({"spp": 0}, ValueError, "spp must be in"),
        ({"spp": 1.5}, TypeError, "spp must be an int"),
        ({"seed": -1}, ValueError, "seed must be an int"),
        ({"seed": 2**64}, ValueError, "seed must be an int"),
        ({"time": float("nan")}, ValueError, "time must be"),
        ({"time": -1.0}, ValueError, "time must be"),
        ({"threads": -2}, ValueError, "threads must be"),
        ({"spp": 4, "time": 1.0}, ValueError, "not both"),
        ({"progress": 5}, TypeError, "progress"),
        ({"stop": True}, TypeError, "StopHandle"),
    ],
)
def test_bad_render_arguments(droplet, kwargs, exc, match):
    with pytest.raises(exc, match=match):
        droplet.render(**kwargs)


def test_image_file_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.exr"):
        snell.read(tmp_path / "nope.exr")
    junk = tmp_path / "junk.exr"
    junk.write_bytes(b"not an exr")
    with pytest.raises(RuntimeError, match="junk.exr"):
        snell.read(junk)
    import numpy as np

    with pytest.raises(ValueError, match=r"\.exr.*\.png"):
        snell.write(tmp_path / "x.tga", np.zeros((2, 2, 3), np.float32))
    with pytest.raises(ValueError, match="H x W x 3"):
        snell.write(tmp_path / "x.exr", np.zeros((2, 2), np.float32))
