"""``qdot.Scene``: a scene's text, and everything qdot derives from it."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

from . import _native
from ._results import (Equation, Equations, Expr, ExprMap, Intermediates, Matrix, Result,
                       _env, markdown_of_latex)
from ._cycle import Cycle
from ._simulation import Simulation, Sweep
from ._studies import Floquet, Response, _native_options

#: How ``derive`` and ``solve`` write their results: ``"auto"`` (through
#: named intermediates when the expanded results would be large: a chain of
#: bodies), ``"expanded"`` (the CLI's ``--expand``) or ``"structured"``
#: (``--structured``: through intermediates wherever the scene allows).
Structure = Literal["auto", "expanded", "structured"]

#: Values given as ``{"m": 1, "g": 9.81}`` or as the CLI writes them, ``"m=1,g=9.81"``.
Values = Union[Mapping[str, float], str, None]

#: The varied quantity of ``cycle``: as the CLI's ``--over``,
#: ``"phi=0:360deg:73"``, or ``{"phi": (0, "360deg", 73)}`` (from, to: numbers
#: in the scene's units, or text with ``deg`` or ``pi``).
Over = Union[str, Mapping[str, Sequence[Union[float, str]]]]


def _names(names: Sequence[str]) -> List[str]:
    """``keep=``'s names as a list (a single name may be given as a string)."""
    if isinstance(names, str):
        return [names]
    return [str(n) for n in names]


def _pairs(values: Values, kind: str) -> List[Tuple[str, float]]:
    """``set=``/``init=``/``guess=`` as (name, value) pairs: a number as it
    is, text (``"30deg"``, ``"2*pi"``) read by qdot's one evaluator of
    numeric values, as the CLI reads it; a value it refuses raises
    :class:`qdot.QdotError`."""
    if values is None:
        return []
    if isinstance(values, str):
        return _native.parse_values(values, kind)
    return [(str(k), _number(str(k), v, kind)) for k, v in values.items()]


def _number(name: str, value: Any, kind: str) -> float:
    """One value of ``set=``/``init=``/``vary=``: a real number as a float,
    anything else read as the CLI reads ``name=value`` (text) or refused
    there (a QdotError)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    if not isinstance(value, str):
        try:
            return float(value)  # NumPy's scalars, Fraction, Decimal
        except (TypeError, ValueError):
            value = repr(value)
    pairs = _native.parse_values(f"{name}={value}", kind)
    if len(pairs) != 1:
        raise _native.QdotError(f"`{name}={value}`: one value for {name}, not {len(pairs)}")
    return pairs[0][1]


def _over(over: Over) -> str:
    """``cycle``'s ``over`` as the CLI's ``--over`` text (floats by ``repr``,
    which reads back as the same double)."""
    if isinstance(over, str):
        return over
    if len(over) != 1:
        raise ValueError("over: one varied quantity, {name: (from, to, count)}")
    ((name, r),) = over.items()
    r = tuple(r)
    if len(r) != 3:
        raise ValueError(f"over[{name!r}]: (from, to, count)")
    ends = [x if isinstance(x, str) else repr(float(x)) for x in r[:2]]
    return f"{name}={ends[0]}:{ends[1]}:{int(r[2])}"


def _over_any(over: Over) -> str:
    """``over`` of ``response`` and ``floquet`` as the CLI's ``--over``: text,
    or ``{name: (from, to, count), …}`` (floquet: one or two names)."""
    if isinstance(over, str):
        return over
    return ",".join(_over({name: r}) for name, r in over.items())


def _exact(values: Union[Mapping[str, Any], str, None]) -> Optional[str]:
    """``--at``/``--init`` of ``modes``: exact values, as text (``th=pi``)."""
    if values is None or isinstance(values, str):
        return values
    return ",".join(f"{k}={v}" for k, v in values.items())


class Scene:
    """A scene: ``Scene(text)`` or ``Scene.load(path)``.

    A scene with an error raises :class:`qdot.QdotError` here, with qdot's
    positioned diagnostic. Results are computed on first use and kept.
    A Scene pickles as its text (``dask.distributed`` ships it to workers
    that rebuild it in microseconds).
    """

    def __init__(self, text: str, *, name: str = "<scene>", max_terms: int = 0) -> None:
        self.source = text
        self.name = name
        self.max_terms = max_terms
        # the coordinates and parameters, each with what qdot assumes of it
        self._kinds: Dict[str, str] = dict(_native.check_scene(text, name, max_terms=max_terms))
        self._cache: Dict[Any, Any] = {}
        # a warning is about the scene: said once, though a result's JSON,
        # text and LaTeX are each a run of the command
        self._warned: set = set()

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"], *, max_terms: int = 0) -> "Scene":
        """Read a ``.qd`` file."""
        with open(path, encoding="utf-8") as f:
            return cls(f.read(), name=os.fspath(path), max_terms=max_terms)

    def __reduce__(self) -> Any:
        return (_rebuild, (self.source, self.name, self.max_terms))

    def __repr__(self) -> str:
        return f"<qdot Scene {self.name}: coordinates {', '.join(self.coordinates)}>"

    # -- the native calls --------------------------------------------------

    def _run(self, command: str, fmt: str, set: Values = None, at: Any = None,
             init: Any = None, steps: bool = False, standalone: bool = False,
             title: Optional[str] = None, structure: Structure = "auto",
             keep: Sequence[str] = (), steady: Sequence[str] = ()) -> str:
        keep = _names(keep)
        steady_list = ",".join(_names(steady)) or None
        key = (command, fmt, repr(_pairs(set, "set")), _exact(at), _exact(init), steps, standalone,
               title, structure, tuple(keep), steady_list)
        if key not in self._cache:
            out, warnings = _native.run_command(
                command, self.source, fmt, file=self.name, set=_pairs(set, "set"),
                at=_exact(at), init=_exact(init), steady=steady_list, steps=steps,
                standalone=standalone,
                title=title if title is not None else os.path.splitext(os.path.basename(self.name))[0],
                max_terms=self.max_terms, structure=structure, keep=keep,
            )
            fresh = [text for text in warnings if text not in self._warned]
            if fresh:
                import warnings as w

                for text in fresh:
                    self._warned.add(text)
                    w.warn(text, QdotWarning, stacklevel=3)
            self._cache[key] = out
        return self._cache[key]

    def _report(self, command: str, formats: List[str], **options: Any) -> Tuple[List[str], List[str]]:
        """``command`` run once and written in each of ``formats`` (any
        command of the application's table, the CLI's options)."""
        native = _native_options(self, options)
        outs, warnings = _native.run_report(command, self.source, formats, **native)
        self._warn(warnings)
        return outs, warnings

    def _warn(self, warnings: Sequence[str]) -> None:
        fresh = [text for text in warnings if text not in self._warned]
        if fresh:
            import warnings as w

            for text in fresh:
                self._warned.add(text)
                w.warn(text, QdotWarning, stacklevel=4)

    def _json(self, command: str, **options: Any) -> Dict[str, Any]:
        return json.loads(self._run(command, "json", **options))

    def _latex_of(self, texts: List[str], intermediates: Sequence[str] = ()) -> List[str]:
        return _native.latex_exprs(self.source, texts, file=self.name, max_terms=self.max_terms,
                                   intermediates=list(intermediates))

    def _exprs(self, texts: Sequence[str], intermediates: Optional[Intermediates] = None) -> List[Expr]:
        names = intermediates.names if intermediates else []
        latex = self._latex_of(list(texts), names)
        return [Expr(t, l, self, intermediates) for t, l in zip(texts, latex)]

    def _derived(self, command: str, structure: Structure,
                 keep: Sequence[str] = ()) -> Tuple[Dict[str, Any], Intermediates]:
        """The JSON of ``derive`` or ``solve`` and the intermediates it is
        written through."""
        data = self._json(command, structure=structure, keep=keep)
        return data, Intermediates.of_json(data, self)

    # -- the derivation ----------------------------------------------------

    @property
    def coordinates(self) -> List[str]:
        """The generalized coordinates, in the scene's order."""
        return list(self._json("derive")["coordinates"])

    def equations(self, structure: Structure = "auto", keep: Sequence[str] = ()) -> Equations:
        """Lagrange's equations, d/dt ∂E/∂q̇ₖ − ∂E/∂qₖ = Qₖ, collected in q̈
        (``structure``: see :meth:`derive`)."""
        data, inter = self._derived("derive", structure, keep)
        eqs = data["equations"]
        lhs = self._exprs([e["lhs"] for e in eqs], inter)
        rhs = self._exprs([e["rhs"] for e in eqs], inter)
        return Equations([Equation(e["coordinate"], l, r) for e, l, r in zip(eqs, lhs, rhs)])

    def mass_matrix(self, structure: Structure = "auto", keep: Sequence[str] = ()) -> Matrix:
        """M of M(q, t)·q̈ = f(q, q̇, t) (``structure``: see :meth:`derive`)."""
        data, inter = self._derived("derive", structure, keep)
        rows = data["mass_matrix"]
        n = len(rows)
        flat = self._exprs([x for r in rows for x in r], inter)
        return Matrix([flat[i * n : (i + 1) * n] for i in range(n)], "M")

    def forcing(self, structure: Structure = "auto", keep: Sequence[str] = ()) -> Matrix:
        """f of M(q, t)·q̈ = f(q, q̇, t), a column (``structure``: see :meth:`derive`)."""
        data, inter = self._derived("derive", structure, keep)
        return Matrix([[x] for x in self._exprs(data["forcing"], inter)], "f")

    def accelerations(self, structure: Structure = "auto", keep: Sequence[str] = ()) -> ExprMap:
        """The exact accelerations q̈ = M⁻¹f, in lowest terms (``structure``:
        see :meth:`derive`; through intermediates, the solution of M·q̈ = f
        by elimination, written in them)."""
        data, inter = self._derived("solve", structure, keep)
        acc = data["accelerations"]
        names = list(acc)
        lhs = self._latex_of([f"{q}''" for q in names])
        return ExprMap(dict(zip(names, self._exprs([acc[q] for q in names], inter))),
                       dict(zip(names, lhs)), "{}''")

    def forces(self) -> ExprMap:
        """The generalized forces Qₖ (virtual work δL = Σ Qₖ·δqₖ)."""
        q = self._json("forces")["generalized_forces"]
        names = list(q)
        lhs = [f"Q_{{{self._latex_of([n])[0]}}}" for n in names]
        return ExprMap(dict(zip(names, self._exprs([q[n] for n in names]))),
                       dict(zip(names, lhs)), "Q_{}")

    def sympy_symbols(self, dynamic: bool = False) -> Dict[str, Any]:
        """The coordinates and parameters as ``.to_sympy()`` makes them, by
        name: a parameter is ``Symbol(name, positive=True)`` (``real=True``
        when the scene says ``assume name real``), so ``sqrt(m**2)`` is
        ``m``; a coordinate a plain ``Symbol``, or with ``dynamic=True`` a
        ``dynamicsymbols``. Substitute and ``lambdify`` with these: a
        ``Symbol("m")`` without the assumption is another symbol."""
        env = _env(self, dynamic, None)
        return {n: env["N_"](n, 0) for n in self._kinds}

    def derive(self, structure: Structure = "auto", keep: Sequence[str] = ()) -> Result:
        """``qdot derive``: the equations, M and f. ``structure`` is how they
        are written: ``"auto"`` (through named intermediates when expanded
        they would be large: a chain of bodies; expanded otherwise),
        ``"expanded"`` or ``"structured"`` (through intermediates wherever
        the scene allows). ``keep`` names definitions of the scene to keep
        as intermediates (the CLI's ``--keep``; the results are then
        structured). ``result.intermediates`` are the names."""
        return Result("derive", self, {"structure": structure, "keep": _names(keep)})

    def solve(self, structure: Structure = "auto", keep: Sequence[str] = ()) -> Result:
        """``qdot solve``: the accelerations and the scene's ``solve`` blocks
        (``structure`` and ``keep``: see :meth:`derive`)."""
        return Result("solve", self, {"structure": structure, "keep": _names(keep)})

    def equilibria(self, set: Values = None, steady: Sequence[str] = ()) -> Result:
        """The positions of equilibrium at rest and their stability
        (``set``: parameter values that decide signs); with ``steady``
        (cyclic coordinates, ``["phi"]``), the steady motions in which they
        turn at constant rates."""
        return Result("equilibrium", self, {"set": set, "steady": steady})

    def modes(self, set: Values = None, at: Any = None, init: Any = None,
              steady: Sequence[str] = ()) -> Result:
        """Small oscillations about ``at`` (default every q = 0): M, C, K,
        the natural frequencies in closed form, the modes, the response to
        ``init``; numbers under ``set``. With ``steady`` (cyclic coordinates,
        ``["phi"]``), about a steady motion in which they turn at constant
        rates (``at`` may give the rates: ``"theta=pi/3,phi'=2"``)."""
        return Result("modes", self, {"set": set, "at": at, "init": init, "steady": steady})

    def hamilton(self) -> Result:
        """The momenta, H(q, p, t) and Hamilton's equations."""
        return Result("hamilton", self, {})

    def integrals(self) -> Result:
        """Cyclic coordinates, the energy integral, Routh's reduction."""
        return Result("integrals", self, {})

    def check(self) -> Result:
        """The dimension of every name and result."""
        return Result("check", self, {})

    def latex(self, steps: bool = False, standalone: bool = False, title: Optional[str] = None) -> str:
        """``qdot latex``: the equations and the solution, amsmath LaTeX
        (``steps``: the derivation line by line; ``standalone``: a whole
        document)."""
        return self._run("latex", "latex", steps=steps, standalone=standalone, title=title)

    def _repr_markdown_(self) -> str:
        return markdown_of_latex(self._run("derive", "latex"))

    # -- numbers -----------------------------------------------------------

    def simulate(self, set: Values, init: Values, t_end: float, method: str = "dop853",
                 rtol: float = 1e-8, atol: float = 1e-10, dt: Optional[float] = None,
                 points: int = 101, max_steps: Optional[int] = None,
                 stop_when: Optional[str] = None, functions: Sequence[str] = (),
                 baumgarte: float = 1.0) -> Simulation:
        """Integrate the equations from t = 0 to ``t_end`` (``qdot simulate``):
        ``set`` every parameter, ``init`` every q (a velocity q' not given is 0, as on the command line)."""
        extra = {} if max_steps is None else {"max_steps": max_steps}
        raw = _native.simulate(
            self.source, _pairs(set, "set"), _pairs(init, "init"), float(t_end),
            method=method, rtol=rtol, atol=atol, dt=dt, points=points,
            stop_when=stop_when, functions=list(functions), baumgarte=baumgarte,
            file=self.name, max_terms=self.max_terms, **extra,
        )
        return Simulation(raw)

    def response(self, set: Values = None, at: Any = None, over: Optional[Over] = None) -> Response:
        """The steady response to the scene's harmonic load (``qdot
        response``): exact in the forcing frequency ``Omega`` (SymPy through
        ``.to_sympy()``), or with ``over`` (``"Omega=0.5:1.5:101"`` or
        ``{"Omega": (0.5, 1.5, 101)}``; ``set`` then every parameter) the
        amplitude and phase swept numerically, a NumPy table. ``at``: the
        equilibrium linearized about (every q = 0 by default)."""
        options: Dict[str, Any] = {"set": set, "at": at, "over": over}
        formats = ["json", "text"] + (["csv"] if over is not None else [])
        outs, _ = self._report("response", formats, **options)
        return Response(self, dict(zip(formats, outs)), _native_options(self, options))

    def floquet(self, set: Values = None, at: Any = None, over: Optional[Over] = None,
                functions: Sequence[str] = (), period: Optional[float] = None,
                max_steps: Optional[int] = None, threads: int = 0) -> Floquet:
        """Floquet's stability about a motion (``qdot floquet``): the
        monodromy matrix over one period of the coefficients, the
        multipliers, the verdict; at the ``set`` values, or over one or two
        parameters (``over``: ``"delta=-1:3:81,eps=0:2:41"`` or
        ``{"delta": (-1, 3, 81), "eps": (0, 2, 41)}``). ``at``: the
        reference motion; ``functions``: ``"s=EXPR"`` per given function
        of time; ``period`` when it is not found; ``max_steps`` per
        integration; ``threads`` for the grid's points (0: one per core; the
        result is the same for any number)."""
        options: Dict[str, Any] = {"set": set, "at": at, "over": over,
                                   "functions": list(functions) or None,
                                   "period": period, "max_steps": max_steps,
                                   "threads": threads or None}
        formats = ["json", "text", "csv"]
        outs, _ = self._report("floquet", formats, **options)
        return Floquet(self, dict(zip(formats, outs)), _native_options(self, options))

    def cycle(self, over: Over, set: Values, guess: Values = None,
              columns: Optional[Sequence[str]] = None) -> Cycle:
        """A planar mechanism over its cycle (``qdot cycle``): at each value
        of ``over`` (``"phi=0:360deg:73"``: ``t`` or a driven coordinate,
        from, to, and the number of positions), the positions, velocities
        and accelerations, every joint's reaction and every drive's force.
        ``set`` every parameter; ``guess`` coordinates of an assembly near
        the first position (the others start from 0; as text, angles may be
        written ``30deg``). ``columns``: only these after the varied one
        (``--columns``; the pictures still draw every column)."""
        raw = _native.cycle(
            self.source, _over(over), _pairs(set, "set"), _pairs(guess, "guess"),
            file=self.name, max_terms=self.max_terms,
            columns=None if columns is None else _names(columns),
        )
        # the pictures' title, as the command line's: the scene's name
        title = _native.scene_title(self.source) or os.path.splitext(os.path.basename(self.name))[0]
        return Cycle(raw, title)

    def sweep(self, set: Values, init: Values, vary: Mapping[str, Sequence[float]], t_end: float,
              samples: Optional[int] = None, seed: int = 0, threads: int = 0,
              method: str = "dop853", rtol: float = 1e-8, atol: float = 1e-10,
              dt: Optional[float] = None, points: int = 101,
              stop_when: Optional[str] = None) -> Sweep:
        """Many runs on every core (``qdot sweep``): ``vary`` maps a parameter,
        coordinate or velocity to ``(from, to, count)`` (a grid, the first
        name varying slowest) or, with ``samples``, ``(from, to)`` (random
        points, reproducible by ``seed``). Derived once; compiled once when
        only initial values vary."""
        axes = []
        for name, r in vary.items():
            r = tuple(r)
            if len(r) not in (2, 3):
                raise ValueError(f"vary[{name!r}]: (from, to, count) or (from, to)")
            ends = [_number(str(name), x, "init") for x in r[:2]]
            axes.append((str(name), ends[0], ends[1], int(r[2]) if len(r) == 3 else 0))
        raw = _native.sweep(
            self.source, _pairs(set, "set"), _pairs(init, "init"), axes, float(t_end),
            samples=samples, seed=seed, threads=threads, method=method, rtol=rtol, atol=atol,
            dt=dt, points=points, stop_when=stop_when, file=self.name, max_terms=self.max_terms,
        )
        return Sweep(raw)


class QdotWarning(UserWarning):
    """A warning of qdot's (a parameter named like a matrix, …)."""


def _rebuild(source: str, name: str, max_terms: int) -> Scene:
    return Scene(source, name=name, max_terms=max_terms)
