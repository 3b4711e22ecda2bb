"""Scenes: loading Mitsuba XML, rendering, and `snell compare`."""

from __future__ import annotations

import os
import tempfile
import warnings
from typing import Any, Callable, Dict, Iterable, Mapping, Optional, Sequence, Union

from . import _snell
from ._image import Image, RenderInterrupted, StopHandle

SceneError = _snell.SceneError
SceneError.__doc__ = """A malformed scene or a bad parameter (a ValueError). The message is the
command line's: "file:line: <element>: what"."""

IntegratorSpec = Union[None, str, Mapping[str, Any]]
Progress = Callable[[float, Optional[float]], Any]


def _define_text(name: str, value: Any) -> str:
    if isinstance(value, bool):  # XML's spelling, as -D would be written
        return "true" if value else "false"
    if isinstance(value, (int, float, str)):
        return str(value)
    raise TypeError(f"define {name}: expected a bool, int, float or str, got {type(value).__name__}")


def _defines(defines: Mapping[str, Any]) -> Dict[str, str]:
    return {k: _define_text(k, v) for k, v in defines.items()}


def _warn_notices(scene: "_snell.Scene") -> None:
    for n in scene.notices:  # what renders differently from Mitsuba (an SMS integrator as mnee, ...)
        warnings.warn(n, stacklevel=3)


class Scene:
    """A loaded scene: shapes and their BVH, lights, camera, film and the scene's integrator.

    Made by :func:`load_file` or :func:`load_string`. It is kept between renders, so a sweep
    over integrators, parameters, sample counts or seeds loads and builds it once.
    """

    def __init__(self, native: "_snell.Scene"):
        self._native = native

    @property
    def name(self) -> str:
        """The path, "builtin:NAME" or "<string>" it was loaded from."""
        return self._native.name

    @property
    def width(self) -> int:
        return self._native.width

    @property
    def height(self) -> int:
        return self._native.height

    @property
    def spp(self) -> int:
        """The scene's ``<sampler>`` sample_count: what ``render()`` uses without ``spp``."""
        return self._native.spp

    @property
    def seed(self) -> int:
        """The scene's ``<sampler>`` seed: what ``render()`` uses without ``seed``."""
        return self._native.seed

    @property
    def integrator(self) -> str:
        """The type of the scene's ``<integrator>`` ("" when it declares none)."""
        return self._native.integrator

    def __repr__(self) -> str:
        return f"<snell.Scene {self.name!r} {self.width}x{self.height}, integrator {self.integrator!r}>"

    def render(
        self,
        spp: Optional[int] = None,
        seed: Optional[int] = None,
        integrator: IntegratorSpec = None,
        time: Optional[float] = None,
        threads: Optional[int] = None,
        progress: Optional[Progress] = None,
        stop: Optional[StopHandle] = None,
        strategies: bool = False,
    ) -> Image:
        """Renders the scene and returns the image.

        Args:
            spp: samples per pixel. Default: the scene's ``<sampler>`` sample_count, or its
                integrator's ``timeout`` when it sets one, as ``snell render`` does.
            seed: sampler seed, an int in [0, 2**64). Default: the scene's ``<sampler>`` seed
                (0 when it sets none), as ``snell render`` does. The image is a pure function of
                (scene, integrator, spp, seed): bit for bit ``snell render --spp N --seed S``'s
                EXR, whatever ``threads``.
            integrator: None for the scene's ``<integrator>``; a type name ("nee", "mnee",
                "bdpt", ...) for that integrator with its defaults; or a dict of its parameters
                with its type, ``{'type': 'mnee', 'biased': True, 'max_depth': 8}``, as the
                scene's ``<integrator>`` element would give them (the scene's own parameters
                are not carried over). Unknown types and parameters raise SceneError.
            time: render for this many seconds instead of a sample count (equal-time
                comparisons); the image holds the passes that completed. Not with ``spp``.
            threads: worker threads (default or 0: every core this process may use).
            progress: called as ``progress(fraction, eta_seconds)`` on the calling thread, at
                most every 0.2 s and once at the end; ``eta_seconds`` is None until known. An
                exception it raises stops the render and is raised from ``render``.
            stop: a :class:`StopHandle`; ``stop.stop()`` from any thread ends the render at its
                next work item, and ``render`` returns what it has.
            strategies: fill the integrator's debug layers (BDPT's per-strategy images), read
                back as ``image.layers``.

        Returns:
            An :class:`Image`: float32, shape (height, width, 3), linear sRGB, viewing the
            film's memory (no copy). ``image.stats`` is the stats JSON of ``snell render`` as a
            dict.

        Raises:
            RenderInterrupted: (a KeyboardInterrupt) on Ctrl-C, within a pass, with the partial
                image in its ``image``.
            SceneError: a bad integrator type or parameter.
            ValueError: a bad spp, time, threads or seed.

        The GIL is released while the scene renders: other Python threads keep running. Renders
        in one process run one at a time (they share its statistics registry).
        """
        if seed is not None and not (isinstance(seed, int) and 0 <= seed < 2**64):
            raise ValueError(f"seed must be an int in [0, 2**64), got {seed!r}")
        if stop is not None and not isinstance(stop, StopHandle):
            raise TypeError(f"stop must be a snell.StopHandle, got {type(stop).__name__}")
        for name, v in (("spp", spp), ("threads", threads)):
            if v is not None and (isinstance(v, bool) or not isinstance(v, int)):
                raise TypeError(f"{name} must be an int, got {type(v).__name__}")
        film, exc = _snell.render(
            self._native,
            integrator,
            spp,
            seed,
            None if time is None else float(time),
            threads,
            progress,
            stop,
            bool(strategies),
        )
        image = Image._of(film)
        if exc is not None:
            if isinstance(exc, KeyboardInterrupt):
                raise RenderInterrupted(image) from exc
            exc.image = image  # what was rendered before the callback raised
            raise exc
        return image


def load_file(path: Union[str, os.PathLike], search_paths: Sequence[str] = (), **defines: Any) -> Scene:
    """Loads a Mitsuba 2/3 XML scene file (or a built-in, "builtin:droplet").

    ``defines`` override the scene's ``<default>`` parameters, as ``-D name=value`` does:
    ``snell.load_file('pool.xml', spp=64, integrator='mnee')``. ``search_paths`` are folders
    tried for relative file names after the scene's own (the command line's ``-a``).

    Raises FileNotFoundError for a missing file and SceneError, with the command line's
    "file:line: <element>: what", for a malformed scene or a missing mesh or texture.
    """
    path = os.fspath(path)
    if not path.startswith("builtin:") and not os.path.isfile(path):
        raise FileNotFoundError(f"cannot open scene file '{path}'")
    native = _snell.load_file(path, _defines(defines), [os.fspath(p) for p in search_paths])
    _warn_notices(native)
    return Scene(native)


def load_string(xml: str, base_dir: Optional[Union[str, os.PathLike]] = None, **defines: Any) -> Scene:
    """Loads a scene from XML text; relative file names resolve against ``base_dir`` (default:
    the working directory). Errors name "<string>:line"."""
    native = _snell.load_string(xml, _defines(defines), os.fspath(base_dir) if base_dir else os.getcwd())
    _warn_notices(native)
    return Scene(native)


def compare(
    scene: Union[str, os.PathLike],
    integrators: Iterable[str],
    time: float,
    out_dir: Optional[Union[str, os.PathLike]] = None,
    reference: Optional[Union[str, os.PathLike]] = None,
    reference_integrator: str = "mnee",
    reference_spp: int = 0,
    reference_time: float = 0.0,
    reference_offset: Optional[Sequence[int]] = None,
    crops: Iterable[Sequence[int]] = (),
    threads: int = 0,
    seed: Optional[int] = None,
    exposure: float = 0.0,
    convergence_steps: int = 4,
    error_max: float = 1.0,
    quiet: bool = True,
    **defines: Any,
) -> Dict[str, Any]:
    """``snell compare``: renders ``scene`` with each integrator for ``time`` seconds, scores
    them against a reference and writes report.html and report.json into ``out_dir`` (default:
    a new temporary folder, named in the result's ``out_dir``).

    The reference is the EXR ``reference``, or rendered with ``reference_integrator`` for
    ``reference_spp`` samples or ``reference_time`` seconds. ``crops`` are (x, y, w, h)
    rectangles scored too; ``defines`` are the scene's ``<default>`` overrides. Integrator
    names are the command line's: pt, path, nee, bdpt, erpt, mnee, mnee-biased, mnee-paper,
    pssmlt(nee), pssmlt(mnee). Returns report.json as a dict (docs/compare.md). Ctrl-C raises
    KeyboardInterrupt after the report of what finished is written.
    """
    if not (time > 0):
        raise ValueError(f"compare: time must be positive, got {time!r}")
    if reference is None and reference_spp <= 0 and not (reference_time > 0):
        raise ValueError("compare needs a reference: reference='ref.exr', or reference_spp / reference_time")
    o = _snell.CompareOptions()
    o.scene = os.fspath(scene)
    o.integrators = list(integrators)
    o.time = float(time)
    o.out_dir = os.fspath(out_dir) if out_dir is not None else tempfile.mkdtemp(prefix="snell-compare-")
    if reference is not None:
        o.reference_file = os.fspath(reference)
    o.reference_integrator = reference_integrator
    o.reference_spp = int(reference_spp)
    o.reference_time = float(reference_time)
    if reference_offset is not None:
        o.reference_offset = ",".join(str(int(v)) for v in reference_offset)
    o.crops = [",".join(str(int(v)) for v in c) for c in crops]
    o.threads = int(threads)
    o.seed = seed
    o.exposure = float(exposure)
    o.convergence_steps = int(convergence_steps)
    o.error_max = float(error_max)
    o.quiet = bool(quiet)
    o.defines = [f"{k}={v}" for k, v in _defines(defines).items()]
    report, interrupted = _snell.compare(o)
    report["out_dir"] = o.out_dir
    if interrupted:
        raise KeyboardInterrupt(f"compare interrupted; the report of what finished is in {o.out_dir}")
    return report
