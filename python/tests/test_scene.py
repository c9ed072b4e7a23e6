"""The Python API against the command line, example by example."""

import json
import pickle
import warnings

import pytest

import qdot
from conftest import EXAMPLES, ROOT


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_example_round_trips(path, cli):
    """Every example loads; the API's equations, M, f and accelerations are
    the CLI's JSON, string for string."""
    scene = qdot.Scene.load(path)
    derive = cli("derive", str(path), "--format", "json")
    if derive.returncode != 0:
        # a scene with no equations (static, kinetostatic): the same error,
        # as the CLI's text and as its JSON error object
        with pytest.raises(qdot.QdotError) as e:
            scene.equations()
        assert str(e.value) == cli("derive", str(path)).stderr.rstrip()
        err = json.loads(derive.stderr)["error"]
        assert (err["kind"], err["message"], err["hint"]) == (e.value.kind, e.value.message, e.value.hint)
        return
    want = json.loads(derive.stdout)
    assert scene.coordinates == want["coordinates"]
    eqs = scene.equations()
    assert [(e.coordinate, str(e.lhs), str(e.rhs)) for e in eqs] == [
        (e["coordinate"], e["lhs"], e["rhs"]) for e in want["equations"]
    ]
    assert [[str(x) for x in row] for row in scene.mass_matrix().rows] == want["mass_matrix"]
    assert [str(x) for x in scene.forcing()] == want["forcing"]
    solve = cli("solve", str(path), "--format", "json")
    if solve.returncode == 0 and "accelerations" in json.loads(solve.stdout):
        acc = scene.accelerations()
        assert {k: str(v) for k, v in acc.items()} == json.loads(solve.stdout)["accelerations"]
    # every expression typesets
    assert all(e._repr_latex_().startswith("$") for e in eqs)
    # and pickles as its text
    again = pickle.loads(pickle.dumps(scene))
    assert again.source == scene.source and again.coordinates == scene.coordinates


@pytest.mark.parametrize("command", ["forces", "equilibrium", "modes", "hamilton", "integrals", "check"])
def test_results_are_the_cli_json(command, cli):
    path = ROOT / "examples" / "seed_24_2.qd"
    scene = qdot.Scene.load(path)
    result = {
        "forces": scene.forces,
        "equilibrium": scene.equilibria,
        "modes": scene.modes,
        "hamilton": scene.hamilton,
        "integrals": scene.integrals,
        "check": scene.check,
    }[command]()
    data = result.data if isinstance(result, qdot.Result) else None
    out = cli(command, str(path), "--format", "json")
    assert out.returncode == 0, out.stderr
    if data is not None:
        assert data == json.loads(out.stdout)
        text = cli(command, str(path))
        assert result.text == text.stdout
    else:
        assert {k: str(v) for k, v in result.items()} == json.loads(out.stdout)["generalized_forces"]


def test_modes_and_equilibria_about_steady_motions(cli):
    path = str(ROOT / "examples" / "spherical_pendulum.qd")
    scene = qdot.Scene.load(ROOT / "examples" / "spherical_pendulum.qd")
    modes = scene.modes(at="theta=pi/3", steady=["phi"])
    out = cli("modes", path, "--format", "json", "--steady", "phi", "--at", "theta=pi/3")
    assert modes.data == json.loads(out.stdout)
    assert modes.data["steady_motion"]["solved"][0]["value"] == "2*g/l"
    assert modes.data["omega_squared"] == ["7*g/(2*l)"]
    steady = scene.equilibria(steady="phi")
    assert steady.data["steady"] == {"phi": "phi'"}
    assert steady.data == json.loads(cli("equilibrium", path, "--format", "json", "--steady", "phi").stdout)


def test_modes_with_values_and_latex(cli):
    scene = qdot.Scene.load(ROOT / "examples" / "seed_24_2.qd")
    modes = scene.modes(set={"m": 1, "k": 6, "R": 0.5})
    out = cli("modes", str(ROOT / "examples" / "seed_24_2.qd"), "--format", "json", "--set", "m=1,k=6,R=0.5")
    assert modes.data == json.loads(out.stdout)
    # the same values written as the CLI writes them
    assert scene.modes(set="m=1,k=6,R=0.5").data == modes.data
    md = scene.modes()._repr_markdown_()
    assert "\\omega_{1}^{2} &= \\frac{k}{6 m}" in md
    latex = scene.latex()
    assert latex == cli("latex", str(ROOT / "examples" / "seed_24_2.qd")).stdout


def test_equilibrium_markdown_is_a_list():
    scene = qdot.Scene.load(ROOT / "examples" / "seed_24_2.qd")
    md = scene.equilibria()._repr_markdown_()
    assert "\\begin{enumerate}" not in md
    assert "1. $x_{1} = 0,\\quad x_{2} = 0$: stable" in md


def test_notebook_reprs():
    scene = qdot.Scene.load(ROOT / "examples" / "seed_23_4.qd")
    acc = scene.accelerations()
    assert acc._repr_latex_() == (
        "$$\\begin{aligned} \\ddot{y}_{3} &= \\frac{343}{460} g \\\\ "
        "\\ddot{\\theta}_{3} &= \\frac{13 g}{460 r} \\end{aligned}$$"
    )
    assert scene.mass_matrix()._repr_latex_().startswith("$$M = \\begin{pmatrix} \\frac{13 G}{2 g} & \\frac{G r}{g}")
    assert acc["y3"]._repr_latex_() == "$\\displaystyle \\frac{343}{460} g$"
    assert "Lagrange's equations" in scene._repr_markdown_()
    eq = scene.equations()["theta3"]
    assert str(eq) == "G*r*y3''/g + 9*G*r^2*theta3''/g = G*r"
    assert eq._repr_latex_() == "$\\displaystyle " + scene._latex_of([str(eq.lhs)])[0] + " = G r$"


def test_errors_are_positioned_python_exceptions():
    with pytest.raises(qdot.QdotError) as e:
        qdot.Scene("coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2 + k\n", name="bad.qd")
    err = e.value
    assert (err.line, err.column) == (3, 26)
    assert "bad.qd:3:26" in str(err)
    assert "^" in str(err)
    assert "k" in err.message
    assert err.hint
    # a bad value in a simulation is one too, without a position
    scene = qdot.Scene.load(ROOT / "examples" / "pendulum.qd")
    with pytest.raises(qdot.QdotError) as e:
        scene.simulate(set={"m": 1, "g": 1}, init={"theta": 1, "theta'": 0}, t_end=1)
    assert "no value for the parameter l" in str(e.value)
    assert e.value.line == 0
    # the hint in Python's terms: the keyword argument, not the CLI's option
    assert e.value.hint == 'give every parameter a value: set={"l": 1}'
    assert "--set" not in str(e.value)


def test_a_warning_is_shown_once():
    """A result's JSON, text and LaTeX are three runs of the command, each
    with the scene's warnings: Python says each warning once."""
    scene = qdot.Scene.load(ROOT / "examples" / "spinning_top.qd")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = scene.modes()
        assert result.text.startswith("Linearized about a = 0, b = 0")
        assert result._repr_markdown_() and result.latex
        scene.derive().latex
    assert [w.category for w in caught] == [qdot.QdotWarning]
    assert str(caught[0].message).startswith(
        "warning: the parameter `C` has the name of the damping matrix C of `modes`' output, "
        "and is in its entries\n --> " + str(ROOT / "examples" / "spinning_top.qd") + ":9:30\n")
