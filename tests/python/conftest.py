"""Shared set-up of the Python module's tests (ctest python.api runs them with the build tree's
package on PYTHONPATH and that build's `snell` in SNELL_BIN)."""

import os
import subprocess
import sys

import pytest

SOURCE_DIR = os.environ.get("SNELL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DROPLET = os.path.join(SOURCE_DIR, "scenes", "droplet", "droplet.xml")
# Small enough for a test: the droplet at 64 x 48.
SMALL = {"res_x": 64, "res_y": 48}


@pytest.fixture(scope="session")
def snell_bin():
    path = os.environ.get("SNELL_BIN")
    if not path or not os.path.exists(path):
        pytest.skip("SNELL_BIN (the build's snell command) is not set")
    return path


@pytest.fixture(scope="session")
def droplet():
    import snell

    return snell.load_file(DROPLET, **SMALL)


def run_python(code, timeout=120):
    """Runs `code` in a fresh interpreter (signals there do not reach pytest); returns it."""
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout, env=os.environ.copy()
    )
