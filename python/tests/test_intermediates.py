"""Results written through named intermediates (a chain of bodies): the
intermediates in order, to_sympy() substituting them (or keeping them,
cse-like), and structure= choosing how derive and solve write."""

import json
import re

import numpy as np
import pytest
import sympy as sp

import qdot
from conftest import ROOT

# the chain's scenes leave the inertias' triangle inequality undecided (a warning)
pytestmark = pytest.mark.filterwarnings("ignore::qdot.QdotWarning")

FIXTURE = json.loads((ROOT / "tests" / "fixtures" / "pinocchio_chain3d.json").read_text())
PARAMS = ["m", "A", "C", "l", "g"]


def chain_text(n):
    """The 3D chain of n rods (scripts/anchor_frames.py's scene_text)."""
    lines = ["coordinates " + ", ".join(f"q{k}" for k in range(1, n + 1)),
             "parameters m, A, C, l, g", "frame B1 = rot(x, q1)"]
    for k in range(2, n + 1):
        lines.append(f"frame B{k} = B{k - 1} * rot({'x' if k % 2 else 'y'}, q{k})")
    for k in range(1, n + 1):
        base = "" if k == 1 else f"P{k - 1} "
        lead = "-" if k == 1 else "- "
        lines.append(f"body b{k}: mass m, inertia [A, A, C], frame B{k}, at {base}{lead}l/2*axis(B{k}, 3)")
        if k < n:
            lines.append(f"P{k} = {base}{lead}l*axis(B{k}, 3)")
    lines.append("gravity [0, 0, -g]")
    return "\n".join(lines) + "\n"


def identifiers(text):
    return set(re.findall(r"[^\W\d]\w*", text))


def test_chain_of_five_rods_is_solved_through_intermediates_in_order():
    scene = qdot.Scene(chain_text(5))
    result = scene.solve()
    inter = result.intermediates
    assert [i["name"] for i in result.data["intermediates"]] == inter.names
    assert len(inter) == len(result.data["intermediates"]) > 100
    assert inter.names[:2] == ["B2_21", "B2_23"]
    assert str(inter["B2_21"]) == "sin(q1)*sin(q2)"
    assert result.data["accelerations"]["q5"] == "z_5"
    # each value uses only the names before it (and the scene's own names)
    scene_names = {"q1", "q2", "q3", "q4", "q5", "t", *PARAMS, "sin", "cos"}
    for k, name in enumerate(inter.names):
        assert identifiers(inter[name].text) <= scene_names | set(inter.names[:k]), name
    # the cse-like form: (Symbol, value) pairs in order, values in the Symbols before them
    pairs = inter.to_sympy()
    assert [str(s) for s, _ in pairs] == inter.names
    q1, q2 = sp.symbols("q1 q2")
    assert pairs[0] == (sp.Symbol("B2_21"), sp.sin(q1) * sp.sin(q2))
    # the scene's accelerations are written through the same names, typeset as qdot does
    acc = scene.accelerations()
    assert acc["q5"] == "z_5" and acc["q5"].latex == "z_{5}"
    assert acc.intermediates.names == inter.names
    assert acc.to_sympy(keep_intermediates=True)["q5"] == sp.Symbol("z_5")
    assert scene.mass_matrix()[0, 0] == "M_11"
    assert scene.mass_matrix().intermediates.names[0] == "B2_21"


@pytest.mark.parametrize("case", [c for c in FIXTURE["cases"] if c["n"] == 4],
                         ids=lambda c: f"seed{c['seed']}")
def test_chain_of_four_accelerations_equal_pinocchios(case):
    scene = qdot.Scene(FIXTURE["scenes"]["4"])
    acc = scene.accelerations()
    assert len(acc.intermediates) > 100
    qs = [f"q{k}" for k in range(1, 5)]
    want = np.array(case["qdd"])
    values = [case["params"][p] for p in PARAMS] + case["q"] + case["qd"]
    names = PARAMS + qs + [q + "'" for q in qs]
    # expanded through the intermediates, then evaluated by NumPy
    expanded = acc.to_sympy()
    assert not {str(s) for e in expanded.values() for s in e.free_symbols} & set(acc.intermediates)
    symbols = scene.sympy_symbols()
    symbols.update({q + "'": sp.Symbol(q + "'") for q in qs})
    f = sp.lambdify([symbols[n] for n in names], [expanded[q] for q in qs], "numpy", cse=True)
    assert np.allclose(np.array(f(*values), dtype=float), want, rtol=0, atol=1e-9)
    # numbers for the names: evaluated through the intermediates in order
    at = acc.to_sympy(symbols={n: sp.Float(v) for n, v in zip(names, values)})
    assert np.allclose([float(at[q]) for q in qs], want, rtol=0, atol=1e-9)
    # the cse-like form: the pairs evaluated in order, then the reduced expressions
    state = {symbols[n]: v for n, v in zip(names, values)}
    for symbol, value in acc.intermediates.to_sympy():
        state[symbol] = value.xreplace(state).evalf()
    reduced = acc.to_sympy(keep_intermediates=True)
    assert np.allclose([float(reduced[q].xreplace(state)) for q in qs], want, rtol=0, atol=1e-9)


def test_small_scene_has_no_intermediates():
    scene = qdot.Scene.load(ROOT / "examples" / "pendulum.qd")
    result = scene.solve()
    assert "intermediates" not in result.data
    assert len(result.intermediates) == 0 and result.intermediates.to_sympy() == []
    acc = scene.accelerations()
    assert len(acc.intermediates) == 0
    assert acc.to_sympy() == acc.to_sympy(keep_intermediates=True)
    g, l, theta = (scene.sympy_symbols()[n] for n in ("g", "l", "theta"))
    assert acc.to_sympy()["theta"] == -g * sp.sin(theta) / l
    assert (g.is_positive, l.is_positive, theta) == (True, True, sp.Symbol("theta"))
    # asked for, even the pendulum is written through names; substituted, they are gone
    structured = scene.solve(structure="structured")
    assert structured.intermediates.names == ["M_11", "Q_theta", "z_1"]
    assert structured.expr(structured["accelerations"]["theta"]).to_sympy() == acc.to_sympy()["theta"]


def test_rod_on_shaft_structured_equals_expanded():
    scene = qdot.Scene.load(ROOT / "examples" / "rod_on_shaft.qd")
    assert "intermediates" not in scene.solve().data  # auto: small, expanded
    structured = scene.solve(structure="structured")
    inter = structured.intermediates
    assert inter.names[:2] == ["omega_B_y", "omega_B_z"] and inter.names[-1] == "z_1"
    assert structured.data["accelerations"] == {"theta": "z_1"}
    assert "intermediates" not in scene.solve(structure="expanded").data
    kept = scene.accelerations(structure="structured")
    assert kept.to_sympy(keep_intermediates=True) == {"theta": sp.Symbol("z_1")}
    for dynamic in (False, True):
        a = kept.to_sympy(dynamic=dynamic)["theta"]
        b = scene.accelerations(structure="expanded").to_sympy(dynamic=dynamic)["theta"]
        assert sp.simplify(a - b) == 0
    # the equations read M·q̈ + h = Q in the names; expanded, they are the expanded ones
    eq = scene.equations(structure="structured")[0]
    assert str(eq) == "M_11*theta'' + h_theta = Q_theta"
    assert eq.to_sympy(keep_intermediates=True) == sp.Eq(
        sp.Symbol("M_11") * sp.Symbol("theta''") + sp.Symbol("h_theta"), sp.Symbol("Q_theta"))
    lhs = eq.to_sympy()
    plain = scene.equations(structure="expanded")[0].to_sympy()
    assert sp.simplify((lhs.lhs - lhs.rhs) - (plain.lhs - plain.rhs)) == 0


def test_intermediates_are_typeset_as_qdot_writes_them():
    scene = qdot.Scene.load(ROOT / "examples" / "rod_on_shaft.qd")
    inter = scene.derive(structure="structured").intermediates
    assert inter["B_13_dot"].latex == (
        "\\dot{\\theta} \\cos\\theta \\sin(\\Omega t) + \\Omega \\cos(\\Omega t) \\sin\\theta")
    assert inter._repr_latex_().startswith(
        "$$\\begin{aligned} \\omega_{B,y} &= \\Omega \\sin\\theta \\\\ "
        "\\omega_{B,z} &= \\Omega \\cos\\theta \\\\ {B_{13}}' &= ")
    assert inter["M_11"].latex.endswith("\\frac{1}{4} l^{2} m \\sin^{2}\\theta + \\frac{1}{12} l^{2} m")
    assert "d_{B,13,theta}^{2}" in inter["M_11"].latex


def test_unknown_structure_is_refused():
    scene = qdot.Scene.load(ROOT / "examples" / "pendulum.qd")
    with pytest.raises(ValueError, match=r"unknown structure `kept`: auto, expanded or structured"):
        scene.solve(structure="kept")  # type: ignore[arg-type]


def test_slider_crank_keeps_alpha_as_the_cli_keep_does():
    scene = qdot.Scene.load(ROOT / "examples" / "slider_crank.qd")
    expanded = scene.solve()
    assert "intermediates" not in expanded.data
    kept = scene.solve(keep=["alpha"])
    # the kept definition's names, then the solutions in solving order
    assert kept.intermediates.names == ["alpha", "alpha_dot", "alpha_ddot",
                                        "Bx", "Ax", "Ay", "By", "N", "M"]
    assert kept.intermediates["alpha"].text == "asin(R*sin(omega*t)/L)"
    # solved body by body: each solution may use the ones before it
    assert list(kept.data["solutions"]) == ["Bx", "Ax", "Ay", "By", "N", "M"]
    ax = kept.data["solutions"]["Ax"]
    assert ax == ("-L*m*alpha_dot^2*cos(alpha)/2 - L*m*alpha_ddot*sin(alpha)/2"
                  " - m*omega^2*R*cos(omega*t) - Bx")
    assert kept.data["solutions"]["M"] == "Ax*R*sin(omega*t) - Ay*R*cos(omega*t)"
    # a single name reads as a list of one; the JSON is the CLI's `--keep alpha`
    assert scene.solve(keep="alpha").data == kept.data
    cli, _ = qdot._native.run_command("solve", scene.source, "json", keep=["alpha"])
    assert json.loads(cli) == kept.data
    # every reaction, its intermediates substituted, is the expanded one (at a state)
    symbols = {**scene.sympy_symbols(), "t": sp.Symbol("t")}
    values = {symbols[k]: v for k, v in
              {"R": 0.3, "L": 1.1, "m": 2.0, "J": 0.2, "mB": 0.7, "F": 1.3, "omega": 1.7,
               "g": 9.81, "t": 0.4}.items()}
    for name, text in kept.data["solutions"].items():
        got = float(kept.expr(text).to_sympy().xreplace(values).evalf())
        want = float(expanded.expr(expanded.data["solutions"][name]).to_sympy().xreplace(values).evalf())
        assert got == pytest.approx(want, rel=1e-12), name
    assert 4 * len(ax) < len(expanded.data["solutions"]["Ax"])
    # a name that is no definition is refused as the CLI refuses it
    with pytest.raises(qdot.QdotError, match="nope"):
        scene.solve(keep=["nope"])
