"""``Model.view``: the 3-D page of ``screwdyn view`` in a notebook or a file."""

from __future__ import annotations

import html as _html
import os
from typing import List, Optional, Tuple, Union

from . import _screwdyn


class View:
    """A self-contained HTML page showing a model (and a run) in 3-D — the page ``screwdyn
    view`` writes (WebGL, no server, no network).

    Displays inline in Jupyter (``_repr_html_``: an ``<iframe srcdoc=…>`` of ``width`` ×
    ``height``); ``save(path)`` writes the page; ``html`` is its text. ``warnings`` lists the
    problems that did not stop the page (a missing or unreadable mesh drawn as a stand-in box,
    meshes decimated to the triangle cap) as one sentence each; ``warning_kinds`` names their
    kinds (``mesh-missing``, ``mesh-unreadable``, ``decimated``). ``triangles`` and ``samples``
    count the embedded mesh triangles and run samples.
    """

    def __init__(self, data, width: Union[int, str] = "100%", height: Union[int, str] = 600):
        self.html: str = data["html"]
        pairs: List[Tuple[str, str]] = [tuple(w) for w in data["warnings"]]
        self.warnings: List[str] = [m for _, m in pairs]
        self.warning_kinds: List[str] = [k for k, _ in pairs]
        self.triangles: int = int(data["triangles"])
        self.samples: int = int(data["samples"])
        self.width = width
        self.height = height

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the page to ``path`` atomically (a temporary file beside it, then a rename),
        so a browser never loads a half-written page. Raises ``OSError`` when it cannot."""
        _screwdyn._write_text_atomically(os.fspath(path), self.html)

    @staticmethod
    def _css(x: Union[int, str]) -> str:
        return f"{x}px" if isinstance(x, (int, float)) else str(x)

    def _repr_html_(self) -> str:
        # srcdoc holds the whole page as an attribute value: html.escape(quote=True) escapes
        # & < > " ' so no character of the page can end the attribute.
        return (f'<iframe srcdoc="{_html.escape(self.html, quote=True)}" '
                f'style="width: {self._css(self.width)}; height: {self._css(self.height)}; '
                f'border: 1px solid #ccc;" sandbox="allow-scripts" '
                f'title="screwdyn view"></iframe>')

    def __repr__(self) -> str:
        extra = f", {self.samples} run samples" if self.samples else ""
        warn = f", {len(self.warnings)} warnings" if self.warnings else ""
        return f"View({len(self.html) / 1e6:.2f} MB page, {self.triangles} triangles{extra}{warn})"


def _recording_spec(run):
    """A SimResult / TorqueProfile as the tuple the native module turns into a library
    Recording."""
    samples = getattr(run, "samples", run)  # a TorqueProfile's samples are a SimResult
    return (list(samples.joint_names), samples.t, samples.q, samples.v, samples.a, samples.tau,
            samples.kinetic_energy, samples.potential_energy, samples.total_energy)


def view(self, q=None, run=None, *, urdf=None, package_path=(),
         max_triangles: int = _screwdyn.VIEW_DEFAULT_MAX_TRIANGLES,
         max_samples: int = _screwdyn.VIEW_DEFAULT_MAX_SAMPLES, title: Optional[str] = None,
         width: Union[int, str] = "100%", height: Union[int, str] = 600) -> View:
    """The robot in 3-D (the page of ``screwdyn view``), displayed inline in Jupyter: orbit,
    zoom and pan, a floor grid, the base frame, and toggleable overlays (link frames ``{i}``,
    joint screw axes, centres of mass, the end-effector path of a run).

    q: the configuration shown (``(nq,)``; zeros by default). Not combined with ``run``.
    run: a run to animate (play/pause, time slider, speed, synchronised plot of ``q``, ``τ``
        and the energies, joints past a limit highlighted): a :class:`SimResult` from
        :meth:`simulate`, a :class:`TorqueProfile`, or the path of a run ``.csv``/``.json``
        file as written by ``screwdyn simulate --output`` or :meth:`SimResult.save`.
    urdf: the URDF whose ``<visual>`` elements are drawn (default: the file the model was
        loaded from, when it is a URDF file; otherwise the skeleton from the screw axes).
    package_path: folders searched for ``package://`` meshes before ``ROS_PACKAGE_PATH``
        (``--package-path``).
    max_triangles: cap on the embedded mesh triangles (``--max-triangles``; larger meshes are
        decimated, with a warning). max_samples: cap on the run samples embedded
        (``--max-samples``; evenly strided, limit violations of dropped samples kept).
    title: the page title (default: the model's name). width, height: the notebook frame's
        size (pixels or a CSS length).

    Returns a :class:`View` (``.html``, ``.save(path)``, ``.warnings``). Raises ValueError with
    the library's sentence for a run whose joints are not the model's, a bad ``q``, a
    non-finite value; FileNotFoundError for a missing run file.
    """
    if run is not None and not isinstance(run, (str, bytes, os.PathLike)):
        if not hasattr(run, "joint_names"):
            raise TypeError("run is a path to a run .csv/.json file, a SimResult or a "
                            "TorqueProfile")
        run = _recording_spec(run)
    elif run is not None:
        run = os.fspath(run)
    if isinstance(package_path, (str, os.PathLike)):
        package_path = [package_path]
    data = _screwdyn._view(self, q, run, None if urdf is None else os.fspath(urdf),
                           [os.fspath(p) for p in package_path], int(max_triangles),
                           int(max_samples), title)
    return View(data, width=width, height=height)


def save_run(result, path: Union[str, "os.PathLike[str]"]) -> None:
    """Writes the run as the file ``screwdyn simulate --output`` writes: CSV (``.csv``:
    columns ``t``, ``q.<joint>``, ``v.<joint>``, ``a.<joint>``, ``tau.<joint>``, the energies)
    or JSON (``.json``), by the library's writers, atomically. Recorded frame poses are not
    written."""
    _screwdyn._save_recording(os.fspath(path), _recording_spec(result))
