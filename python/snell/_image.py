"""Images: what a render returns, and the image files and metrics of the command line."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _snell

Film = _snell.Film
Film.__doc__ = """The film a render leaves: its samples and its image buffers.

A rendered :class:`Image` views the film's buffer (``image.base is image.film``), so no pixel
is copied. ``stats`` is the stats JSON of ``snell render --stats`` as a dict; ``layer(k)`` is
debug layer k >= 1 (BDPT's per-strategy images, rendered with ``strategies=True``), named by
``layer_names[k - 1]``; ``technique_map()`` gives per pixel the index into ``technique_names``
of the technique that delivered its largest sample (-1: none), ``sample_share_map()`` the share
of the pixel's light that sample carries."""

StopHandle = _snell.StopHandle
StopHandle.__doc__ = """Stops a render from another thread or a progress callback.

    stop = snell.StopHandle()
    threading.Timer(10, stop.stop).start()
    img = scene.render(spp=4096, stop=stop)   # returns after about 10 s with what it has

A stopped render returns normally; ``img.stats['interrupted']`` is True and the pixels hold
the samples of the passes that completed, as ``snell render`` interrupted by Ctrl-C writes."""

ImageLike = Union["Image", np.ndarray, str, os.PathLike]


class Image(np.ndarray):
    """A rendered image: a numpy float32 array of shape (height, width, 3), linear sRGB.

    It views the film's memory (``base`` is the :class:`Film`); ``stats``, ``layers`` and
    ``dominance`` come from that film. Slices keep them; arithmetic gives plain numpy arrays.
    """

    @staticmethod
    def _of(film: Film) -> "Image":
        return np.ndarray.__new__(Image, (film.height, film.width, 3), np.float32, buffer=film)

    def __array_wrap__(self, out, context=None, *args):  # ufunc results are plain arrays
        return np.asarray(out) if out.ndim else out[()]

    @property
    def film(self) -> Optional[Film]:
        """The film this image views (None for an array that is not a render's)."""
        b = self.base
        while b is not None and not isinstance(b, Film):
            b = getattr(b, "base", None)
        return b

    @property
    def stats(self) -> Dict[str, Any]:
        """The render's statistics: the fields of ``snell render --stats`` (seconds, spp_reached,
        paths_per_second, discarded samples, ``dominance``, ``counters``, MNEE's ``extra``)."""
        f = self.film
        return f.stats if f is not None else {}

    @property
    def interrupted(self) -> bool:
        """True when the render was stopped (Ctrl-C, a StopHandle) before its budget."""
        f = self.film
        return bool(f is not None and f.interrupted)

    @property
    def layers(self) -> Dict[str, np.ndarray]:
        """The film's debug layers by name, each H x W x 3 (no copy): BDPT's per-strategy
        images ``d_s_t``, rendered with ``strategies=True``. Empty otherwise."""
        f = self.film
        if f is None:
            return {}
        return {name: f.layer(k + 1) for k, name in enumerate(f.layer_names)}

    @property
    def dominance(self) -> Dict[str, Any]:
        """Which technique delivers each pixel's largest sample, and how much of it.

        ``technique``: int8 H x W, an index into ``techniques`` (-1: none, or an integrator
        that does not name its techniques); ``share``: float32 H x W, that sample's share of the
        pixel; ``largest_y``: float32 H x W, that sample's luminance (Y, filter-weighted, before
        any clamp); ``samples``: uint64 H x W, the pixel's sample count; the rest is the stats'
        ``dominance`` (pixels dominated by one sample, by technique name)."""
        f = self.film
        if f is None:
            return {}
        d = dict(self.stats.get("dominance", {}))
        d.update(technique=f.technique_map(), share=f.sample_share_map(), largest_y=f.largest_sample_map(),
                 samples=f.samples_map(), techniques=list(f.technique_names))
        return d


class RenderInterrupted(KeyboardInterrupt):
    """Ctrl-C during a render: raised within a pass, with what was rendered so far in ``image``
    (its ``stats['interrupted']`` is True)."""

    def __init__(self, image: Image):
        super().__init__("render interrupted; the partial image is in .image")
        self.image = image


def _array(image: ImageLike, what: str) -> np.ndarray:
    if isinstance(image, (str, os.PathLike)):
        return read(image)
    a = np.asarray(image)
    if a.ndim != 3 or a.shape[2] != 3:
        raise ValueError(f"{what}: expected an H x W x 3 array, got shape {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)


def read(path: Union[str, os.PathLike]) -> np.ndarray:
    """Reads an image file as a float32 H x W x 3 array of linear values.

    OpenEXR and Radiance HDR as stored; PNG, JPEG, TIFF and what else OpenImageIO reads are
    decoded from sRGB where the file is sRGB-encoded (8- and 16-bit files). Raises
    FileNotFoundError for a missing file, RuntimeError naming the path for a bad one."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(f"cannot open image '{path}'")
    return _snell.read(path)


def write(path: Union[str, os.PathLike], image: ImageLike, exposure: float = 0.0) -> None:
    """Writes an H x W x 3 image: ``.exr`` as linear 32-bit float (bit for bit what ``snell
    render`` writes), ``.png`` as 8-bit sRGB after multiplying by 2**exposure. Any other
    extension raises ValueError."""
    _snell.write(os.fspath(path), _array(image, "write"), float(exposure))


def diff(
    image: ImageLike,
    reference: ImageLike,
    crop: Optional[Sequence[int]] = None,
    normalise_by: Optional[ImageLike] = None,
) -> Dict[str, Any]:
    """The metrics of ``snell diff --json`` of ``image`` against ``reference``.

    Arrays or file names. ``crop`` (x, y, w, h) limits them to that rectangle;
    ``normalise_by`` gives relMSE the denominators of another (converged) image. Returns
    ``rel_mse``, ``rmse``, ``psnr`` (inf for identical images), ``smape``, ``mean``,
    ``mean_reference``, ``median_rel_error``, ``median_rel_error_rgb`` and ``region``."""
    norm = None if normalise_by is None else _array(normalise_by, "diff: normalise_by")
    c: Optional[List[int]] = None if crop is None else [int(v) for v in crop]
    return _snell.diff(_array(image, "diff: image"), _array(reference, "diff: reference"), c, norm)
