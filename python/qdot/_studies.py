"""The frequency response (``Scene.response``) and Floquet's stability
(``Scene.floquet``) as NumPy tables and SymPy expressions; ``run_command``,
any command of the one table the CLI, the REPL and Python share."""

from __future__ import annotations

import json
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _native

#: Every command of qdot's application layer, each with the formats it
#: writes, in the order the CLI's help lists them (``app::Command::ALL``).
COMMANDS: Dict[str, Tuple[str, ...]] = {name: tuple(formats) for name, formats in _native.commands()}


class _Study:
    """What ``response`` and ``floquet`` share: the CLI's outputs, kept."""

    _command = ""

    def __init__(self, scene: Any, outputs: Dict[str, str], options: Dict[str, Any]) -> None:
        self._scene = scene
        self._outputs = outputs
        self._options = options
        self.data: Dict[str, Any] = json.loads(outputs["json"])

    def to_json(self) -> str:
        """The JSON the CLI prints (``--output json``), byte for byte."""
        return self._outputs["json"]

    def to_text(self) -> str:
        """The text the CLI prints (``--output text``)."""
        return self._outputs["text"]

    def to_csv(self) -> str:
        """The CSV the CLI prints (``--output csv``), every digit; a
        :class:`qdot.QdotError` where the command writes no table."""
        if "csv" not in self._outputs:
            (self._outputs["csv"],), _ = _native.run_report(
                self._command, self._scene.source, ["csv"], **self._options)
        return self._outputs["csv"]

    def __str__(self) -> str:
        return self.to_text()


class Response(_Study):
    """``qdot response``: the steady response to the scene's harmonic load.

    Exact (no ``over``): ``coordinates``, ``frequency``, and each of
    ``real``, ``imag``, ``amplitude_squared``, ``tan_phase``,
    ``omega_squared``, ``load_cos``, ``load_sin`` as a list of
    :class:`qdot.Expr` (one per coordinate; ``.to_sympy()`` each, or
    :meth:`to_sympy` for all) in the forcing frequency ``Omega``;
    ``antiresonances`` per coordinate; ``single`` (one degree of freedom:
    the peak, the bandwidth, …) as the JSON gives it. ``columns`` is empty.

    Swept (``over="Omega=FROM:TO:COUNT"``): ``columns`` (``Omega``, then
    ``amp_q`` and ``phase_q`` per coordinate) and ``values`` (rows ×
    columns, NumPy), ``natural_frequencies``, ``peaks``.
    """

    _command = "response"
    #: The exact results' keys whose values are lists of expressions.
    EXACT = ("omega_squared", "load_cos", "load_sin", "real", "imag", "amplitude_squared", "tan_phase")

    def __init__(self, scene: Any, outputs: Dict[str, str], options: Dict[str, Any]) -> None:
        super().__init__(scene, outputs, options)
        d = self.data
        self.coordinates: List[str] = list(d["coordinates"])
        self.swept = "rows" in d
        if self.swept:
            self.columns: List[str] = list(d["columns"])
            self.values: np.ndarray = np.asarray(d["rows"], dtype=float).reshape(-1, len(self.columns))
            self.natural_frequencies: np.ndarray = np.asarray(d["natural_frequencies"], dtype=float)
            self.peaks: Dict[str, List[Tuple[float, float]]] = {
                q: [tuple(p) for p in ps] for q, ps in (d.get("peaks") or {}).items()}
        else:
            from ._results import Expr

            self.columns = []
            self.values = np.empty((0, 0))
            self.frequency: str = d["frequency"]
            for key in self.EXACT:
                setattr(self, key, [Expr(t, None, scene) for t in d[key]])
            self.antiresonances = [[Expr(t, None, scene) for t in a] for a in d["antiresonances"]]
            self.single: Optional[Dict[str, Any]] = d.get("single")

    def __getitem__(self, column: str) -> np.ndarray:
        """A column of the swept table by name (``"Omega"``, ``"amp_x1"``)."""
        try:
            return self.values[:, self.columns.index(column)]
        except ValueError:
            raise KeyError(f"no column {column!r}; the columns are {', '.join(self.columns)}") from None

    def to_sympy(self) -> Dict[str, List[Any]]:
        """The exact results as SymPy expressions, key → one per coordinate."""
        if self.swept:
            raise ValueError("a swept response is numbers: .values")
        return {key: [e.to_sympy() for e in getattr(self, key)] for key in self.EXACT}

    def plot(self, ax: Any = None) -> Any:
        """Amplitude (log-log) and phase against Ω with matplotlib, the
        natural frequencies marked; the axes (two when ``ax`` is None)."""
        if not self.swept:
            raise ValueError("plot() draws a swept response: Scene.response(over='Omega=FROM:TO:COUNT')")
        import matplotlib.pyplot as plt

        if ax is None:
            _, (ax, phase_ax) = plt.subplots(2, 1, sharex=True)
        else:
            phase_ax = None
        omega = self["Omega"]
        for q in self.coordinates:
            ax.loglog(omega, self[f"amp_{q}"], label=q)
            if phase_ax is not None:
                phase_ax.plot(omega, self[f"phase_{q}"], label=q)
        for w in self.natural_frequencies:
            ax.axvline(w, color="grey", linestyle=":")
        ax.set_ylabel("amplitude")
        ax.legend()
        if phase_ax is not None:
            phase_ax.set_xlabel("Ω")
            phase_ax.set_ylabel("phase")
            return ax, phase_ax
        return ax

    def __repr__(self) -> str:
        if self.swept:
            return f"<qdot Response of {', '.join(self.coordinates)}: {len(self.values)} frequencies>"
        return f"<qdot Response of {', '.join(self.coordinates)}: exact in Omega>"


class Floquet(_Study):
    """``qdot floquet``: the Floquet multipliers about a motion, at a point
    or over a grid of parameters.

    ``parameters`` are the varied names; ``columns`` (the varied values,
    ``period``, ``max_abs_multiplier``, ``trace``, ``error``) and
    ``values`` (points × columns, NumPy; NaN where a point failed) the
    table; per point ``verdicts``, ``notes``, ``multipliers`` (complex
    arrays) and ``monodromy`` (matrices; None where a point failed).
    ``equations`` are the linearized equations as :class:`qdot.Expr`.
    """

    _command = "floquet"
    _NUMBERS = ("period", "max_abs_multiplier", "trace", "error")

    def __init__(self, scene: Any, outputs: Dict[str, str], options: Dict[str, Any]) -> None:
        super().__init__(scene, outputs, options)
        from ._results import Expr

        d = self.data
        self.coordinates: List[str] = list(d["coordinates"])
        self.parameters: List[str] = list(d["parameters"])
        self.frequency: Optional[str] = d.get("frequency")
        self.equations = [Expr(t, None, scene) for t in d["equations"]]
        self.columns: List[str] = self.parameters + list(self._NUMBERS)
        rows = []
        self.verdicts: List[Optional[str]] = []
        self.notes: List[Optional[str]] = []
        self.multipliers: List[Optional[np.ndarray]] = []
        self.monodromy: List[Optional[np.ndarray]] = []
        for p in d["points"]:
            rows.append(list(p["values"]) + [_number(p.get(k)) for k in self._NUMBERS])
            self.verdicts.append(p.get("verdict"))
            self.notes.append(p.get("note"))
            m = p.get("multipliers")
            self.multipliers.append(None if m is None else np.array([complex(x["re"], x["im"]) for x in m]))
            mono = p.get("monodromy")
            self.monodromy.append(None if mono is None else np.asarray(mono, dtype=float))
        self.values: np.ndarray = np.asarray(rows, dtype=float).reshape(-1, len(self.columns))

    def __getitem__(self, column: str) -> np.ndarray:
        """A column by name (a varied parameter, ``"max_abs_multiplier"``, …)."""
        try:
            return self.values[:, self.columns.index(column)]
        except ValueError:
            raise KeyError(f"no column {column!r}; the columns are {', '.join(self.columns)}") from None

    def plot(self, ax: Any = None) -> Any:
        """With matplotlib: the multipliers against the unit circle (one
        point), the largest |μ| against the parameter (one), or the
        stability chart (two: stable points filled); the axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots()
        if not self.parameters:
            s = np.linspace(0, 2 * np.pi, 200)
            ax.plot(np.cos(s), np.sin(s), color="grey")
            mu = self.multipliers[0]
            if mu is not None:
                ax.plot(mu.real, mu.imag, "o")
            ax.set_aspect("equal")
            ax.set_xlabel("Re μ")
            ax.set_ylabel("Im μ")
        elif len(self.parameters) == 1:
            ax.semilogy(self[self.parameters[0]], self["max_abs_multiplier"])
            ax.axhline(1.0, color="grey", linestyle=":")
            ax.set_xlabel(self.parameters[0])
            ax.set_ylabel("max |μ|")
        else:
            x, y = self[self.parameters[0]], self[self.parameters[1]]
            stable = np.array([v == "stable" for v in self.verdicts])
            ax.scatter(x[stable], y[stable], marker="s", label="stable")
            ax.scatter(x[~stable], y[~stable], marker="s", facecolors="none", edgecolors="C3", label="unstable")
            ax.set_xlabel(self.parameters[0])
            ax.set_ylabel(self.parameters[1])
            ax.legend()
        return ax

    def __repr__(self) -> str:
        if not self.parameters:
            return f"<qdot Floquet about {', '.join(self.coordinates)}: {self.verdicts[0]}>"
        return f"<qdot Floquet over {', '.join(self.parameters)}: {len(self.values)} points>"


def _number(x: Any) -> float:
    return float("nan") if x is None else float(x)


def run_command(name: str, scene: Any, format: str = "text", **options: Any) -> str:
    """Any command of :data:`COMMANDS` on ``scene`` (a :class:`qdot.Scene`)
    with the CLI's options as keywords (``set``, ``at``, ``init``,
    ``steady``, ``over``, ``guess``, ``columns``, ``functions``,
    ``period``, ``max_steps``, ``steps``, ``standalone``, ``structure``,
    ``keep``): what ``qdot NAME FILE --format/--output FORMAT`` prints.
    Warnings go to Python's ``warnings``."""
    if name not in COMMANDS:
        import difflib

        near = difflib.get_close_matches(name, list(COMMANDS), n=1)
        hint = f"; did you mean {near[0]!r}?" if near else ""
        raise ValueError(f"unknown command {name!r}{hint} The commands are {', '.join(COMMANDS)}")
    if format not in COMMANDS[name]:
        raise ValueError(f"{name!r} writes {', '.join(COMMANDS[name])}, not {format!r}")
    (out,), _ = scene._report(name, [format], **options)
    return out


def _native_options(scene: Any, options: Dict[str, Any]) -> Dict[str, Any]:
    """Keyword options (Python values) as the native call's."""
    from ._scene import _exact, _names, _over_any, _pairs

    out: Dict[str, Any] = {"file": scene.name, "max_terms": scene.max_terms}
    for key, value in options.items():
        if value is None:
            continue
        if key == "set":
            out["set"] = _pairs(value, "set")
        elif key == "guess":
            out["guess"] = _pairs(value, "guess")
        elif key in ("at", "init"):
            out[key] = _exact(value)
        elif key == "steady":
            out["steady"] = ",".join(_names(value)) or None
        elif key == "over":
            out["over"] = _over_any(value)
        elif key in ("columns", "functions", "keep"):
            out[key] = _names(value)
        elif key in ("period",):
            out[key] = float(value)
        elif key in ("max_steps", "threads"):
            out[key] = int(value)
        elif key in ("steps", "standalone", "title", "structure"):
            out[key] = value
        else:
            raise TypeError(f"unknown option {key!r}")
    return out
