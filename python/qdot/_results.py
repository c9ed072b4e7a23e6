"""What a scene's methods return: exact expressions, equations, matrices
and command results, each with its text, its LaTeX (typeset by Jupyter)
and, with SymPy installed, its SymPy object."""

from __future__ import annotations

import re
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple

from . import _sympy


class Expr:
    """An exact expression, in qdot's syntax (``str(e)`` re-parses in a scene).

    ``e.latex`` is its LaTeX in the scene's notation; ``e.to_sympy()`` its
    SymPy object. An expression of a result written through named
    intermediates may mention them (``M_11``, ``B2_13``): ``e.intermediates``
    are the result's, and ``to_sympy()`` substitutes them.
    """

    __slots__ = ("text", "_latex", "_scene", "_intermediates")

    def __init__(self, text: str, latex: Optional[str] = None, scene: Any = None,
                 intermediates: Optional["Intermediates"] = None) -> None:
        self.text = text
        self._latex = latex
        self._scene = scene
        # none when empty (the Intermediates being built has its texts already)
        self._intermediates = intermediates if intermediates is not None and intermediates._texts else None

    @property
    def latex(self) -> str:
        """The LaTeX of the expression (the scene's notation: θ, ẍ₁)."""
        if self._latex is None:
            names = self._intermediates.names if self._intermediates else ()
            self._latex = self._scene._latex_of([self.text], names)[0]
        return self._latex

    @property
    def intermediates(self) -> "Intermediates":
        """The named intermediates of the result the expression is part of
        (empty when the result is expanded)."""
        return self._intermediates or Intermediates([], self._scene)

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None,
                 keep_intermediates: bool = False) -> Any:
        """The SymPy expression.

        ``dynamic=True``: the coordinates become ``dynamicsymbols`` (functions
        of t) and q', q'' their derivatives, as in ``sympy.physics.mechanics``.
        ``symbols`` maps qdot names to SymPy objects of your own, or to
        numbers (then ``"q'"`` keys give the velocities).

        The named intermediates it mentions are substituted, in order (the
        expanded expression); ``keep_intermediates=True`` keeps them as
        Symbols of their names, defined by ``e.intermediates.to_sympy()``.
        """
        if self._intermediates and not keep_intermediates:
            return self._intermediates._expand(self.text, dynamic, symbols)
        return _sympy.to_sympy(self.text, _env(self._scene, dynamic, symbols))

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"Expr({self.text!r})"

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Expr):
            return self.text == other.text
        if isinstance(other, str):
            return self.text == other
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.text)

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.latex}$"


def _env(scene: Any, dynamic: bool, symbols: Optional[Mapping[str, Any]],
         bound: Optional[Dict[str, Any]] = None) -> Dict[str, Any]:
    """The SymPy builders for ``to_sympy``: the scene's parameters carry
    what qdot assumes of them; an expression without a scene has plain
    Symbols."""
    kinds = scene._kinds if scene is not None else {}
    coordinates = [n for n, k in kinds.items() if k == "coordinate"] if dynamic else []
    return _sympy.builders(coordinates, symbols, bound, kinds)


_IDENTIFIER = re.compile(r"[^\W\d]\w*")


class _Expansion:
    """The intermediates substituted in SymPy for one choice of
    ``to_sympy``'s options: each one's expanded value, built in order on
    first need (a name stands for the value already built)."""

    def __init__(self, inter: "Intermediates", dynamic: bool,
                 symbols: Optional[Mapping[str, Any]]) -> None:
        self.inter = inter
        self.bound: Dict[str, Any] = {}
        self.env = _env(inter._scene, dynamic, symbols, self.bound)

    def of(self, text: str) -> Any:
        for name in self.inter._needed(text):
            if name not in self.bound:
                self.bound[name] = _sympy.to_sympy(self.inter._texts[name], self.env)
        return _sympy.to_sympy(text, self.env)


class Intermediates(Mapping[str, Expr]):
    """The named intermediates a result is written through, in evaluation
    order: ``name → Expr`` (``B2_13``, ``P1_x_dot``, ``M_11``). Each value
    mentions only the names before it, the coordinates, velocities,
    parameters and t. Empty when the result is expanded.

    ``to_sympy()`` is the list of ``(Symbol, value)`` pairs in order, as
    ``sympy.cse`` gives its replacements; the result's expressions with
    ``to_sympy(keep_intermediates=True)`` are the reduced expressions.
    """

    def __init__(self, pairs: Sequence[Tuple[str, str]], scene: Any) -> None:
        self._texts: Dict[str, str] = dict(pairs)
        self._scene = scene
        self._items = {n: Expr(v, scene=scene, intermediates=self) for n, v in pairs}
        self._deps: Dict[str, List[str]] = {}
        self._expansions: Dict[Any, _Expansion] = {}
        self._latex: Optional[List[str]] = None

    @classmethod
    def of_json(cls, data: Mapping[str, Any], scene: Any) -> "Intermediates":
        """The ``"intermediates"`` of a command's JSON (none when absent).
        A ``solve`` written through intermediates lists its solutions in
        solving order, each may use the ones before it: they join the
        intermediates, so a solution's ``to_sympy()`` substitutes them."""
        pairs = [(i["name"], i["value"]) for i in data.get("intermediates", [])]
        if pairs:
            pairs += list(data.get("solutions", {}).items())
        return cls(pairs, scene)

    @property
    def names(self) -> List[str]:
        """The names, in order."""
        return list(self._texts)

    def __getitem__(self, name: str) -> Expr:
        return self._items[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def to_sympy(self, dynamic: bool = False,
                 symbols: Optional[Mapping[str, Any]] = None) -> List[Tuple[Any, Any]]:
        """``[(Symbol, value), …]`` in order, each value written in the
        Symbols before it (``dynamic`` and ``symbols`` as for
        :meth:`Expr.to_sympy`)."""
        env = _env(self._scene, dynamic, symbols)
        return [(env["N_"](n, 0), _sympy.to_sympy(v, env)) for n, v in self._texts.items()]

    def _needed(self, text: str) -> List[str]:
        """The intermediates ``text`` depends on, in order."""
        seen = set()
        stack = [n for n in _IDENTIFIER.findall(text) if n in self._texts]
        while stack:
            n = stack.pop()
            if n not in seen:
                seen.add(n)
                stack.extend(self._depends(n))
        return [n for n in self._texts if n in seen]

    def _depends(self, name: str) -> List[str]:
        if name not in self._deps:
            found = _IDENTIFIER.findall(self._texts[name])
            self._deps[name] = [n for n in found if n in self._texts and n != name]
        return self._deps[name]

    def _expand(self, text: str, dynamic: bool, symbols: Optional[Mapping[str, Any]]) -> Any:
        try:
            key: Any = (dynamic, tuple(sorted((symbols or {}).items())))
            hash(key)
        except TypeError:
            return _Expansion(self, dynamic, symbols).of(text)
        if key not in self._expansions:
            if len(self._expansions) >= 8:
                self._expansions.pop(next(iter(self._expansions)))
            self._expansions[key] = _Expansion(self, dynamic, symbols)
        return self._expansions[key].of(text)

    def _latex_rows(self) -> List[str]:
        if self._latex is None:
            names = self.names
            self._latex = self._scene._latex_of(names + list(self._texts.values()), names)
        return self._latex

    def __str__(self) -> str:
        return "\n".join(f"{n} = {v}" for n, v in self._texts.items())

    def __repr__(self) -> str:
        return "Intermediates({" + ", ".join(f"{n!r}: {v!r}" for n, v in self._texts.items()) + "})"

    def _repr_latex_(self) -> str:
        tex = self._latex_rows()
        n = len(self._texts)
        rows = " \\\\ ".join(f"{tex[i]} &= {tex[n + i]}" for i in range(n))
        return f"$$\\begin{{aligned}} {rows} \\end{{aligned}}$$"


class Equation:
    """One of Lagrange's equations: ``lhs = rhs``, for ``coordinate``."""

    __slots__ = ("coordinate", "lhs", "rhs")

    def __init__(self, coordinate: str, lhs: Expr, rhs: Expr) -> None:
        self.coordinate = coordinate
        self.lhs = lhs
        self.rhs = rhs

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None,
                 keep_intermediates: bool = False) -> Any:
        """``sympy.Eq(lhs, rhs)`` (the options as for :meth:`Expr.to_sympy`)."""
        import sympy

        return sympy.Eq(
            self.lhs.to_sympy(dynamic, symbols, keep_intermediates),
            self.rhs.to_sympy(dynamic, symbols, keep_intermediates),
            evaluate=False,
        )

    @property
    def intermediates(self) -> "Intermediates":
        """The named intermediates the equation is written through."""
        return self.lhs.intermediates

    def __str__(self) -> str:
        return f"{self.lhs} = {self.rhs}"

    def __repr__(self) -> str:
        return f"Equation({self.coordinate!r}: {self})"

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.lhs.latex} = {self.rhs.latex}$"


class Equations(Sequence[Equation]):
    """Lagrange's equations, one per coordinate, in the scene's order."""

    def __init__(self, items: List[Equation]) -> None:
        self._items = items

    def __getitem__(self, i: Any) -> Any:
        if isinstance(i, str):
            for e in self._items:
                if e.coordinate == i:
                    return e
            raise KeyError(i)
        return self._items[i]

    def __len__(self) -> int:
        return len(self._items)

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None,
                 keep_intermediates: bool = False) -> List[Any]:
        """A list of ``sympy.Eq``."""
        return [e.to_sympy(dynamic, symbols, keep_intermediates) for e in self._items]

    @property
    def intermediates(self) -> "Intermediates":
        """The named intermediates the equations are written through."""
        return self._items[0].intermediates if self._items else Intermediates([], None)

    def __str__(self) -> str:
        return "\n".join(str(e) for e in self._items)

    def __repr__(self) -> str:
        return f"Equations([{', '.join(repr(str(e)) for e in self._items)}])"

    def _repr_latex_(self) -> str:
        rows = " \\\\ ".join(f"{e.lhs.latex} &= {e.rhs.latex}" for e in self._items)
        return f"$$\\begin{{aligned}} {rows} \\end{{aligned}}$$"


class Matrix:
    """An exact matrix (the mass matrix M) or column (the forcing f)."""

    def __init__(self, rows: List[List[Expr]], name: str = "") -> None:
        self.rows = rows
        self.name = name

    @property
    def shape(self) -> Tuple[int, int]:
        return (len(self.rows), len(self.rows[0]) if self.rows else 0)

    def __getitem__(self, ij: Any) -> Any:
        if isinstance(ij, tuple):
            i, j = ij
            return self.rows[i][j]
        if self.shape[1] == 1:
            return self.rows[ij][0]
        return self.rows[ij]

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self) -> Iterator[Any]:
        if self.shape[1] == 1:
            return iter([r[0] for r in self.rows])
        return iter(self.rows)

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None,
                 keep_intermediates: bool = False) -> Any:
        """The ``sympy.Matrix``."""
        import sympy

        return sympy.Matrix(
            [[x.to_sympy(dynamic, symbols, keep_intermediates) for x in r] for r in self.rows]
        )

    @property
    def intermediates(self) -> "Intermediates":
        """The named intermediates the entries are written through."""
        return self.rows[0][0].intermediates if self.rows and self.rows[0] else Intermediates([], None)

    def __str__(self) -> str:
        return "[" + ", ".join("[" + ", ".join(x.text for x in r) + "]" for r in self.rows) + "]"

    def __repr__(self) -> str:
        return f"Matrix({self})"

    def _repr_latex_(self) -> str:
        body = " \\\\ ".join(" & ".join(x.latex for x in r) for r in self.rows)
        lhs = f"{self.name} = " if self.name else ""
        return f"$${lhs}\\begin{{pmatrix}} {body} \\end{{pmatrix}}$$"


class ExprMap(Mapping[str, Expr]):
    """Expressions by coordinate: the accelerations q̈ₖ, the generalized
    forces Qₖ. ``symbol(name)`` is the left-hand side's LaTeX."""

    def __init__(self, items: Dict[str, Expr], lhs_latex: Dict[str, str], lhs_text: str) -> None:
        self._items = items
        self._lhs_latex = lhs_latex
        self._lhs_text = lhs_text

    def __getitem__(self, k: str) -> Expr:
        return self._items[k]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None,
                 keep_intermediates: bool = False) -> Dict[str, Any]:
        """A dict from the coordinate's name to the SymPy expression."""
        return {k: v.to_sympy(dynamic, symbols, keep_intermediates) for k, v in self._items.items()}

    @property
    def intermediates(self) -> "Intermediates":
        """The named intermediates the expressions are written through."""
        for v in self._items.values():
            return v.intermediates
        return Intermediates([], None)

    def __str__(self) -> str:
        return "\n".join(f"{self._lhs_text.format(k)} = {v}" for k, v in self._items.items())

    def __repr__(self) -> str:
        return "{" + ", ".join(f"{k!r}: {v.text!r}" for k, v in self._items.items()) + "}"

    def _repr_latex_(self) -> str:
        rows = " \\\\ ".join(f"{self._lhs_latex[k]} &= {v.latex}" for k, v in self._items.items())
        return f"$$\\begin{{aligned}} {rows} \\end{{aligned}}$$"


_ITEM = re.compile(r"^\s*\\item\s+")


def markdown_of_latex(fragment: str) -> str:
    """qdot's LaTeX fragment as Markdown a notebook typesets: prose with
    ``$…$`` and display environments stays, ``enumerate`` becomes a list,
    ``\\paragraph{…}`` bold."""
    out: List[str] = []
    for line in fragment.splitlines():
        if line.strip() in ("\\begin{enumerate}", "\\end{enumerate}"):
            continue
        m = _ITEM.match(line)
        if m:
            out.append("1. " + line[m.end():])
            continue
        out.append(re.sub(r"\\paragraph\{([^}]*)\}", r"**\1** ", line))
    return "\n".join(out) + "\n"


class Result:
    """The result of a command (``equilibria``, ``modes``, ``forces``…):
    ``data`` is its JSON (the CLI's ``--format json``, a public contract),
    ``text`` what the CLI prints, ``latex`` its LaTeX fragment. A notebook
    shows it typeset."""

    def __init__(self, command: str, scene: Any, options: Dict[str, Any]) -> None:
        self.command = command
        self._scene = scene
        self._options = options
        self.data: Dict[str, Any] = scene._json(command, **options)
        self._text: Optional[str] = None
        self._latex: Optional[str] = None
        self._intermediates: Optional[Intermediates] = None

    @property
    def text(self) -> str:
        if self._text is None:
            self._text = self._scene._run(self.command, "text", **self._options)
        return self._text

    @property
    def latex(self) -> str:
        if self._latex is None:
            self._latex = self._scene._run(self.command, "latex", **self._options)
        return self._latex

    def __getitem__(self, key: str) -> Any:
        return self.data[key]

    def keys(self) -> Any:
        return self.data.keys()

    @property
    def intermediates(self) -> Intermediates:
        """The named intermediates ``data``'s expressions may mention
        (``data["intermediates"]`` of ``derive`` and ``solve`` written
        through them), in order; empty when the result is expanded."""
        if self._intermediates is None:
            self._intermediates = Intermediates.of_json(self.data, self._scene)
        return self._intermediates

    def expr(self, text: str) -> Expr:
        """One of ``data``'s expression strings as an :class:`Expr` (whose
        ``to_sympy()`` substitutes the result's intermediates)."""
        return Expr(text, scene=self._scene, intermediates=self.intermediates)

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"<qdot {self.command} result: {', '.join(self.data.keys())}>"

    def _repr_markdown_(self) -> str:
        return markdown_of_latex(self.latex)
