"""A finished simulation as NumPy arrays."""

from __future__ import annotations

from typing import Any, Dict, List, Optional

import numpy as np


class Simulation:
    """The rows qdot's ``simulate`` prints, as arrays.

    ``t`` (k,), ``q`` and ``qdot`` (k, n), ``energy`` (k,) or ``None`` when
    the scene does not conserve it; ``data`` (k, columns) holds every column
    in ``columns`` order (``sim["theta'"]`` is one). ``status`` is ``done``,
    ``event``, … as in ``--output json``; ``stats`` the integrator's counters.
    """

    def __init__(self, raw: Dict[str, Any]) -> None:
        self.columns: List[str] = list(raw["columns"])
        rows = int(raw["rows"])
        self.data: np.ndarray = np.frombuffer(raw["data"], dtype="<f8").reshape(rows, len(self.columns))
        self.coordinates: List[str] = list(raw["coordinates"])
        n = len(self.coordinates)
        self.t: np.ndarray = self.data[:, 0]
        self.q: np.ndarray = self.data[:, 1 : 1 + n]
        self.qdot: np.ndarray = self.data[:, 1 + n : 1 + 2 * n]
        self.energy: Optional[np.ndarray] = (
            self.data[:, self.columns.index("energy")] if "energy" in self.columns else None
        )
        self.status: str = raw["status"]
        self.method: str = raw["method"]
        self.evaluator: str = raw["evaluator"]
        self.stats: Dict[str, int] = dict(raw["stats"])
        self.seconds: float = raw["seconds"]
        self.compile_seconds: float = raw["compile_seconds"]
        self._csv: str = raw["csv"]

    def __getitem__(self, column: str) -> np.ndarray:
        try:
            return self.data[:, self.columns.index(column)]
        except ValueError:
            raise KeyError(f"no column {column!r}; the columns are {', '.join(self.columns)}") from None

    def __len__(self) -> int:
        return self.data.shape[0]

    def to_csv(self) -> str:
        """The CSV ``qdot simulate`` prints, byte for byte."""
        return self._csv

    def plot(self, ax: Any = None) -> Any:
        """q(t) with matplotlib, one line per coordinate; returns the axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots()
        for k, name in enumerate(self.coordinates):
            ax.plot(self.t, self.q[:, k], label=name)
        ax.set_xlabel("t")
        ax.legend()
        return ax

    def __repr__(self) -> str:
        return (
            f"<qdot Simulation: {len(self)} rows × {len(self.columns)} columns "
            f"({', '.join(self.columns)}), {self.method}, {self.status}>"
        )

    def _repr_markdown_(self) -> str:
        head = "| " + " | ".join(self.columns) + " |\n|" + "---|" * len(self.columns) + "\n"
        shown = list(range(min(len(self), 5)))
        if len(self) > 5:
            shown.append(len(self) - 1)
        body = ""
        for i in shown:
            if i == len(self) - 1 and len(self) > 5:
                body += "| " + " | ".join("⋮" for _ in self.columns) + " |\n"
            body += "| " + " | ".join(f"{x:.6g}" for x in self.data[i]) + " |\n"
        return (
            f"{len(self)} rows, {self.method}, {self.status} "
            f"({self.stats['steps']} steps, {self.seconds * 1e3:.3g} ms)\n\n" + head + body
        )


class Sweep:
    """Many runs of one scene (``Scene.sweep``), one summary per run.

    ``values`` (runs, varied names) in ``names`` order; ``t`` the last time
    reached; ``q`` and ``qdot`` (runs, n) the final state; ``max_abs_q``
    (runs, n) the largest |q| over the output times; ``energy_drift`` the
    largest |h(t) − h(0)| (NaN when the scene does not conserve energy);
    ``steps``; ``status`` a list (``done``, ``event``, or ``error: …``).
    """

    def __init__(self, raw: Dict[str, Any]) -> None:
        self.names: List[str] = list(raw["names"])
        self.coordinates: List[str] = list(raw["coordinates"])
        k, n, runs = len(self.names), len(self.coordinates), int(raw["runs"])
        width = k + 3 + 3 * n
        table = np.frombuffer(raw["summary"], dtype="<f8").reshape(runs, width)
        self.values: np.ndarray = table[:, :k]
        self.t: np.ndarray = table[:, k]
        self.q: np.ndarray = table[:, k + 1 : k + 1 + n]
        self.qdot: np.ndarray = table[:, k + 1 + n : k + 1 + 2 * n]
        self.max_abs_q: np.ndarray = table[:, k + 1 + 2 * n : k + 1 + 3 * n]
        self.energy_drift: np.ndarray = table[:, k + 1 + 3 * n]
        self.steps: np.ndarray = table[:, k + 2 + 3 * n]
        self.status: List[str] = list(raw["status"])
        self.seconds: float = raw["seconds"]
        self.threads: int = raw["threads"]
        self.compilations: int = raw["compilations"]

    def __len__(self) -> int:
        return self.values.shape[0]

    @property
    def runs_per_second(self) -> float:
        return len(self) / max(self.seconds, 1e-9)

    def __repr__(self) -> str:
        return (
            f"<qdot Sweep: {len(self)} runs over {', '.join(self.names)} on {self.threads} threads, "
            f"{self.runs_per_second:.0f} runs/s>"
        )
