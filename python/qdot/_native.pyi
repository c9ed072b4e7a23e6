"""Type stubs of the native module (python/src/lib.rs)."""

from typing import Any, Dict, List, Optional, Sequence, Tuple

class QdotError(Exception):
    """qdot's diagnostic: ``str(e)`` as the command line prints it."""

    message: str
    hint: Optional[str]
    line: int
    column: int

def run_command(
    command: str,
    source: str,
    format: str,
    file: str = ...,
    set: Sequence[Tuple[str, float]] = ...,
    at: Optional[str] = ...,
    init: Optional[str] = ...,
    steady: Optional[str] = ...,
    steps: bool = ...,
    standalone: bool = ...,
    title: str = ...,
    max_terms: int = ...,
    structure: str = ...,
    keep: Sequence[str] = ...,
) -> Tuple[str, List[str]]: ...
def check_scene(source: str, file: str = ..., max_terms: int = ...) -> List[Tuple[str, str]]: ...
def parse_values(text: str, kind: str) -> List[Tuple[str, float]]: ...
def simulate(
    source: str,
    set: Sequence[Tuple[str, float]],
    init: Sequence[Tuple[str, float]],
    t_end: float,
    method: str = ...,
    rtol: float = ...,
    atol: float = ...,
    dt: Optional[float] = ...,
    points: int = ...,
    max_steps: int = ...,
    stop_when: Optional[str] = ...,
    functions: Sequence[str] = ...,
    baumgarte: float = ...,
    file: str = ...,
    max_terms: int = ...,
) -> Dict[str, Any]: ...
def sweep(
    source: str,
    set: Sequence[Tuple[str, float]],
    init: Sequence[Tuple[str, float]],
    axes: Sequence[Tuple[str, float, float, int]],
    t_end: float,
    samples: Optional[int] = ...,
    seed: int = ...,
    threads: int = ...,
    method: str = ...,
    rtol: float = ...,
    atol: float = ...,
    dt: Optional[float] = ...,
    points: int = ...,
    stop_when: Optional[str] = ...,
    file: str = ...,
    max_terms: int = ...,
) -> Dict[str, Any]: ...
def cycle(
    source: str,
    over: str,
    set: Sequence[Tuple[str, float]],
    guess: Sequence[Tuple[str, float]] = ...,
    file: str = ...,
    max_terms: int = ...,
    columns: Optional[Sequence[str]] = ...,
) -> Dict[str, Any]: ...

def commands() -> List[Tuple[str, List[str]]]:
    """Every command of the application layer with the formats it writes."""
    ...

def run_report(
    command: str,
    source: str,
    formats: Sequence[str],
    file: str = ...,
    set: Sequence[Tuple[str, float]] = ...,
    at: Optional[str] = ...,
    init: Optional[str] = ...,
    steady: Optional[str] = ...,
    steps: bool = ...,
    standalone: bool = ...,
    title: str = ...,
    max_terms: int = ...,
    structure: str = ...,
    keep: Sequence[str] = ...,
    over: Optional[str] = ...,
    guess: Sequence[Tuple[str, float]] = ...,
    columns: Optional[Sequence[str]] = ...,
    functions: Sequence[str] = ...,
    period: Optional[float] = ...,
    max_steps: Optional[int] = ...,
    threads: int = ...,
) -> Tuple[List[str], List[str]]:
    """A command run once, written in each format: (outputs, warnings)."""
    ...

class CycleTable:
    """A mechanism's cycle, kept for its pictures (``Scene.cycle``)."""

    def reaction_diagrams(self, title: str) -> str: ...
    def animation(self, title: str, svg: bool) -> str: ...
    def csv(self) -> str: ...
    def json(self) -> str: ...

def latex_exprs(
    source: str,
    exprs: Sequence[str],
    file: str = ...,
    max_terms: int = ...,
    intermediates: Sequence[str] = ...,
) -> List[str]: ...
def scene_title(source: str) -> Optional[str]: ...
def sympy_source(expr: str) -> str: ...
def version() -> str: ...
