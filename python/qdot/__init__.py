"""qdot: exact analytical mechanics from Python.

    >>> import qdot
    >>> s = qdot.Scene('''
    ...     coordinates x
    ...     parameters m, k
    ...     kinetic E = 1/2*m*x'^2
    ...     potential V = 1/2*k*x^2
    ... ''')
    >>> s.accelerations()["x"]
    Expr('-k*x/m')

Results are exact (qdot's own arithmetic), printed in qdot's syntax, typeset
in a notebook, and ``.to_sympy()`` gives SymPy objects. Large scenes (a
chain of bodies) are written through named intermediates
(:class:`Intermediates`), which ``.to_sympy()`` substitutes.
"""

from ._native import QdotError, version as _version
from ._cycle import Cycle
from ._results import Equation, Equations, Expr, ExprMap, Intermediates, Matrix, Result
from ._scene import QdotWarning, Scene
from ._simulation import Simulation, Sweep
from ._studies import COMMANDS, Floquet, Response, run_command

__version__ = _version()

__all__ = [
    "COMMANDS",
    "Cycle",
    "Equation",
    "Equations",
    "Expr",
    "ExprMap",
    "Floquet",
    "Intermediates",
    "Matrix",
    "QdotError",
    "QdotWarning",
    "Response",
    "Result",
    "Scene",
    "Simulation",
    "Sweep",
    "run_command",
]
