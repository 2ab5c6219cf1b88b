"""The page ``Model.view`` returns (the 3-D page of ``screwdyn view``) in a notebook or a file,
and ``SimResult.save``."""

from __future__ import annotations

import html as _html
import os
from typing import List, Tuple, Union

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


def save_run(result, path: Union[str, "os.PathLike[str]"]) -> None:
    """Writes the run as the file ``screwdyn simulate --output`` writes: CSV (``.csv``:
    columns ``t``, ``q.<joint>``, ``v.<joint>``, ``a.<joint>``, ``tau.<joint>``, the energies)
    or JSON (``.json``), by the library's writers, atomically. Recorded frame poses are not
    written."""
    _screwdyn._save_recording(os.fspath(path), result)
