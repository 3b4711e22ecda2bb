"""snell: a spectral renderer for caustics through refractive interfaces (MNEE).

The Python face of the command line (docs/python.md)::

    import snell
    scene = snell.load_file('scenes/droplet/droplet.xml')
    img = scene.render(spp=16)                     # numpy float32, H x W x 3, linear sRGB
    img.stats['seconds']                           # what `snell render --stats` writes
    ref = snell.read('reference.exr')
    snell.diff(img, ref)['rel_mse']                # `snell diff`'s metrics
    snell.write('out.png', img)

A loaded scene is kept: a sweep renders it again and again with other integrators, sample
counts or seeds without loading it again.
"""

import sys as _sys

try:
    import numpy as _numpy  # noqa: F401
except ImportError as _e:  # a python3 of its own (pyenv, conda) before Debian's on the PATH
    raise ImportError(
        f"snell needs numpy, which {_sys.executable} does not have: use the interpreter the module "
        "was built for (Debian's /usr/bin/python3 with python3-numpy unless CMake was told "
        "-DPython_EXECUTABLE=...), or install numpy into this one"
    ) from _e

from ._image import Film, Image, RenderInterrupted, StopHandle, diff, read, write
from ._scene import Scene, SceneError, compare, load_file, load_string

# The native types print as snell.X, where users find them.
for _t in (Film, StopHandle, SceneError):
    _t.__module__ = "snell"
del _t

__all__ = [
    "Film",
    "Image",
    "RenderInterrupted",
    "Scene",
    "SceneError",
    "StopHandle",
    "compare",
    "diff",
    "load_file",
    "load_string",
    "read",
    "write",
]
