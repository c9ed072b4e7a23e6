"""A mechanism's cycle (``Scene.cycle``) as NumPy arrays, and its pictures."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Union

import numpy as np


class Cycle:
    """The table ``qdot cycle`` prints, as arrays.

    ``columns`` are the names: the varied quantity first (``varied``: ``t``
    or a driven coordinate; an angle's column holds radians, ``degrees``
    says so), then every q, q', q'', each joint's reaction components, each
    drive's force and each friction force. ``values`` (rows, columns)
    holds them, NaN where the position determines no value (a row that
    sticks, a dead point); ``cycle["O_x"]`` is one column. ``notes`` is,
    per row, what is special about the position (``stick …``, a dead
    point) or ``None``; ``iterations`` the friction's passes per row.
    """

    def __init__(self, raw: Dict[str, Any], title: str) -> None:
        self.varied: str = raw["varied"]
        self.degrees: bool = bool(raw["degrees"])
        self.columns: List[str] = list(raw["columns"])
        rows = int(raw["rows"])
        self.values: np.ndarray = np.frombuffer(raw["data"], dtype="<f8").reshape(rows, len(self.columns))
        self.notes: List[Optional[str]] = list(raw["notes"])
        self.iterations: np.ndarray = np.asarray(raw["iterations"], dtype=np.int64)
        self.title = title
        self._table = raw["table"]

    def __getitem__(self, column: str) -> np.ndarray:
        """A column by name (the varied one for its name: it is also a
        coordinate's, and both hold the same values)."""
        try:
            return self.values[:, self.columns.index(column)]
        except ValueError:
            raise KeyError(f"no column {column!r}; the columns are {', '.join(self.columns)}") from None

    def __len__(self) -> int:
        return self.values.shape[0]

    def to_csv(self) -> str:
        """The CSV ``qdot cycle`` prints (``--output csv``), byte for byte."""
        return str(self._table.csv())

    def to_json(self) -> str:
        """The JSON ``qdot cycle --output json`` prints, byte for byte."""
        return str(self._table.json())

    def plot(self, path: Union[str, "os.PathLike[str]"], title: Optional[str] = None) -> None:
        """Write the reaction diagrams to ``path``, an SVG file (``cycle
        --plot``): each joint's components and each drive against the varied
        quantity, and the polar diagram of each pin force. ``title``:
        the scene's name (its first comment) by default, else the file's,
        as the CLI titles it."""
        _write(path, self._table.reaction_diagrams(self.title if title is None else title))

    def animate(self, path: Union[str, "os.PathLike[str]"], title: Optional[str] = None) -> None:
        """Write the mechanism moving through its cycle (``cycle
        --animate``): a self-contained HTML page, or an animated SVG when
        ``path`` ends in ``.svg``."""
        svg = os.fspath(path).endswith(".svg")
        _write(path, self._table.animation(self.title if title is None else title, svg))

    def __repr__(self) -> str:
        return (
            f"<qdot Cycle over {self.varied}: {len(self)} positions × {len(self.columns)} columns, "
            f"{sum(n is not None for n in self.notes)} noted>"
        )


def _write(path: Union[str, "os.PathLike[str]"], text: str) -> None:
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
