"""The package is typed: py.typed and the native module's stubs are
installed, and every public name is in them."""

import importlib.resources
import inspect

import qdot
from qdot import _native


def test_stubs_are_installed_and_complete():
    files = importlib.resources.files("qdot")
    assert (files / "py.typed").is_file()
    stub = (files / "_native.pyi").read_text()
    for name, obj in vars(_native).items():
        if not name.startswith("_") and (inspect.isbuiltin(obj) or inspect.isclass(obj)):
            declared = (f"def {name}(", f"class {name}(", f"class {name}:")
            assert any(d in stub for d in declared), name


def test_public_api_is_annotated():
    for cls in (qdot.Scene, qdot.Simulation, qdot.Sweep, qdot.Cycle, qdot.Expr, qdot.Result):
        for name, fn in vars(cls).items():
            if callable(fn) and not name.startswith("_"):
                sig = inspect.signature(fn)
                assert sig.return_annotation is not inspect.Signature.empty, f"{cls.__name__}.{name}"
