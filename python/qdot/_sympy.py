"""qdot expressions as SymPy objects.

The native module writes an expression as calls of the builders below
(``N_`` a name with primes, ``R_`` a rational, ``A_`` a sum, ``M_`` a
product, ``P_`` a power, ``F_`` a function, ``V_`` a vector); this module
evaluates that text with SymPy, and nothing else in scope.
"""

from __future__ import annotations

from typing import Any, Dict, Iterable, Mapping, Optional

from . import _native

#: qdot's built-in functions that SymPy names differently.
_RENAMED = {"ln": "log"}

#: A name's SymPy assumptions by what qdot assumes of it (the kinds
#: ``_native.check_scene`` gives): a parameter is positive unless the scene
#: says ``assume NAME real``. Coordinates carry none, as SymPy's own
#: ``Symbol`` and ``dynamicsymbols`` make them: they are the unknowns user
#: code builds Symbols of (``lambdify``'s arguments, the q of
#: ``sympy.physics.mechanics``), and those must be the same objects.
ASSUMPTIONS: Dict[str, Dict[str, bool]] = {
    "parameter": {"positive": True},
    "real parameter": {"real": True},
}


def _require_sympy() -> Any:
    try:
        import sympy
    except ImportError as e:  # pragma: no cover - exercised without SymPy
        raise ImportError(
            "to_sympy() needs SymPy: pip install sympy (or pip install './python[sympy]')"
        ) from e
    return sympy


def builders(
    dynamic: Iterable[str] = (),
    symbols: Optional[Mapping[str, Any]] = None,
    bound: Optional[Mapping[str, Any]] = None,
    kinds: Optional[Mapping[str, str]] = None,
) -> Dict[str, Any]:
    """The names the SymPy source is evaluated with.

    ``dynamic``: the names that become functions of time
    (``sympy.physics.mechanics.dynamicsymbols``), whose primes are time
    derivatives; every other name is a ``Symbol`` (or what ``symbols`` maps
    it to, e.g. a Symbol of the user's own, or a number; a primed name such
    as ``"x'"`` may be mapped too). A primed name that is not dynamic is the
    Symbol ``x'``. ``kinds``: the scene's names by kind (``"parameter"``,
    …), whose Symbols carry the :data:`ASSUMPTIONS` of their kind.

    ``bound``: names (a result's intermediates) that stand for the SymPy
    objects it maps them to; read when a name is met, so the caller may
    add to it between evaluations.
    """
    sp = _require_sympy()
    dynamic = set(dynamic)
    symbols = dict(symbols or {})
    bound = bound if bound is not None else {}
    kinds = kinds or {}
    cache: Dict[str, Any] = {}
    t = symbols.get("t")
    if t is None:
        if dynamic:
            from sympy.physics.mechanics import dynamicsymbols

            t = dynamicsymbols._t
        else:
            t = sp.Symbol("t")

    def name(n: str, order: int) -> Any:
        if order == 0 and n in bound:
            return bound[n]
        if n == "t" and order == 0:
            return t
        if order and n + "'" * order in symbols:
            return symbols[n + "'" * order]
        if n == "pi" and n not in symbols:
            base: Any = sp.pi
        elif n in symbols:
            base = symbols[n]
        elif n in dynamic:
            if n not in cache:
                from sympy.physics.mechanics import dynamicsymbols

                cache[n] = dynamicsymbols(n)
            base = cache[n]
        else:
            if order and n + "'" * order not in cache:
                cache[n + "'" * order] = sp.Symbol(n + "'" * order)
            if order:
                return cache[n + "'" * order]
            if n not in cache:
                cache[n] = sp.Symbol(n, **ASSUMPTIONS.get(kinds.get(n, ""), {}))
            base = cache[n]
        return sp.diff(base, t, order) if order else base

    def function(f: str, *args: Any) -> Any:
        f = _RENAMED.get(f, f)
        fn = getattr(sp, f, None)
        if fn is None or not callable(fn):
            fn = sp.Function(f)
        return fn(*args)

    return {
        "N_": name,
        "R_": lambda p, q: sp.Rational(int(p), int(q)),
        "A_": lambda *xs: sp.Add(*xs),
        "M_": lambda *xs: sp.Mul(*xs),
        "P_": lambda b, e: sp.Pow(b, e),
        "F_": function,
        "V_": lambda *xs: sp.Matrix(xs),
        "D_": lambda x, k: sp.diff(x, t, k),
    }


def to_sympy(text: str, env: Dict[str, Any]) -> Any:
    """The SymPy object of ``text``, an expression in qdot's syntax."""
    source = _native.sympy_source(text)
    return eval(source, {"__builtins__": {}}, env)  # noqa: S307 - our own builders only
