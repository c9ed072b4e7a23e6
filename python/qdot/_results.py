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
    SymPy object.
    """

    __slots__ = ("text", "_latex", "_scene")

    def __init__(self, text: str, latex: Optional[str] = None, scene: Any = None) -> None:
        self.text = text
        self._latex = latex
        self._scene = scene

    @property
    def latex(self) -> str:
        """The LaTeX of the expression (the scene's notation: θ, ẍ₁)."""
        if self._latex is None:
            self._latex = self._scene._latex_of([self.text])[0]
        return self._latex

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None) -> Any:
        """The SymPy expression.

        ``dynamic=True``: the coordinates become ``dynamicsymbols`` (functions
        of t) and q', q'' their derivatives, as in ``sympy.physics.mechanics``.
        ``symbols`` maps qdot names to SymPy objects of your own.
        """
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


def _env(scene: Any, dynamic: bool, symbols: Optional[Mapping[str, Any]]) -> Dict[str, Any]:
    coordinates = scene.coordinates if (dynamic and scene is not None) else []
    return _sympy.builders(coordinates, symbols)


class Equation:
    """One of Lagrange's equations: ``lhs = rhs``, for ``coordinate``."""

    __slots__ = ("coordinate", "lhs", "rhs")

    def __init__(self, coordinate: str, lhs: Expr, rhs: Expr) -> None:
        self.coordinate = coordinate
        self.lhs = lhs
        self.rhs = rhs

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None) -> Any:
        """``sympy.Eq(lhs, rhs)``."""
        import sympy

        return sympy.Eq(
            self.lhs.to_sympy(dynamic, symbols), self.rhs.to_sympy(dynamic, symbols), evaluate=False
        )

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

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None) -> List[Any]:
        """A list of ``sympy.Eq``."""
        return [e.to_sympy(dynamic, symbols) for e in self._items]

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

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None) -> Any:
        """The ``sympy.Matrix``."""
        import sympy

        return sympy.Matrix([[x.to_sympy(dynamic, symbols) for x in r] for r in self.rows])

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

    def to_sympy(self, dynamic: bool = False, symbols: Optional[Mapping[str, Any]] = None) -> Dict[str, Any]:
        """A dict from the coordinate's name to the SymPy expression."""
        return {k: v.to_sympy(dynamic, symbols) for k, v in self._items.items()}

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

    def expr(self, text: str) -> Expr:
        """One of ``data``'s expression strings as an :class:`Expr`."""
        return Expr(text, scene=self._scene)

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"<qdot {self.command} result: {', '.join(self.data.keys())}>"

    def _repr_markdown_(self) -> str:
        return markdown_of_latex(self.latex)
