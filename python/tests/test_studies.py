"""response() and floquet(): the same JSON, text and CSV as ``qdot response``
and ``qdot floquet``, NumPy tables and SymPy for the exact parts; run_command
over the one table of commands."""

import json

import numpy as np
import pytest

import qdot
from conftest import ROOT

ABSORBER = ROOT / "examples" / "vibration_absorber.qd"
MATHIEU = ROOT / "examples" / "mathieu.qd"
SEED_21_3 = ROOT / "examples" / "seed_21_3.qd"
SWEPT_SET = "m1=1,m2=0.2,k1=1,k2=0.2,c=0.02,F0=1"


def cli_out(cli, *args):
    out = cli(*[str(a) for a in args])
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_the_exact_response_is_the_clis_and_sympy(cli):
    r = qdot.Scene.load(ABSORBER).response()
    assert r.to_json() == cli_out(cli, "response", ABSORBER, "--output", "json")
    assert r.to_text() == cli_out(cli, "response", ABSORBER)
    assert r.coordinates == ["x1", "x2"] and not r.swept
    assert r.columns == [] and r.values.shape == (0, 0)
    # the absorber's point: x1 stands still at Ω² = k2/m2
    assert [str(a) for a in r.antiresonances[0]] == ["k2/m2"]
    sympy = pytest.importorskip("sympy")
    amp = r.amplitude_squared[0].to_sympy()
    at = {s.name: s for s in amp.free_symbols}
    assert amp.subs(at["Omega"], sympy.sqrt(at["k2"] / at["m2"])).subs(at["c"], 0).simplify() == 0
    assert set(r.to_sympy()) == set(qdot.Response.EXACT)
    with pytest.raises(qdot.QdotError):
        r.to_csv()


def test_the_swept_response_is_the_clis_table(cli):
    r = qdot.Scene.load(ABSORBER).response(set=SWEPT_SET, over={"Omega": (0.6, 1.4, 9)})
    args = ["response", ABSORBER, "--set", SWEPT_SET, "--over", "Omega=0.6:1.4:9"]
    assert r.to_json() == cli_out(cli, *args, "--output", "json")
    assert r.to_csv() == cli_out(cli, *args, "--output", "csv")
    assert r.to_text() == cli_out(cli, *args, "--output", "text")
    assert r.columns == ["Omega", "amp_x1", "phase_x1", "amp_x2", "phase_x2"]
    assert r.values.shape == (9, 5)
    assert r["Omega"][0] == 0.6
    assert r["amp_x2"][4] == pytest.approx(5.0, rel=1e-12)
    assert r.natural_frequencies == pytest.approx([0.8010882788459809, 1.2483018743459389])
    assert r.peaks["x1"][0] == pytest.approx((0.8, 19.796284721071924))


def test_floquet_at_a_point_and_over_a_grid_is_the_clis(cli):
    mathieu = qdot.Scene.load(MATHIEU)
    f = mathieu.floquet(set="delta=0.25,eps=0.2,m=1,w=1")
    args = ["floquet", MATHIEU, "--set", "delta=0.25,eps=0.2,m=1,w=1"]
    assert f.to_json() == cli_out(cli, *args, "--output", "json")
    assert f.to_text() == cli_out(cli, *args)
    assert f.parameters == [] and f.values.shape == (1, 4)
    assert f.columns == ["period", "max_abs_multiplier", "trace", "error"]
    assert f["period"][0] == pytest.approx(2 * np.pi)
    mu = f.multipliers[0]
    assert mu.shape == (2,) and abs(mu[0] * mu[1] - 1) < 1e-8  # Liouville: det Φ = 1
    assert f.verdicts[0] in ("stable", "unstable")
    grid = mathieu.floquet(set={"m": 1, "w": 1}, over={"delta": (-0.5, 2.5, 13), "eps": (0, 2, 5)})
    args = ["floquet", MATHIEU, "--set", "m=1,w=1", "--over", "delta=-0.5:2.5:13,eps=0:2:5"]
    assert grid.to_csv() == cli_out(cli, *args, "--output", "csv")
    assert grid.to_json() == cli_out(cli, *args, "--output", "json")
    assert grid.parameters == ["delta", "eps"] and grid.values.shape == (65, 6)
    assert grid.verdicts[0] == "unstable"
    assert grid["max_abs_multiplier"][0] == pytest.approx(85.01969522320329)
    assert str(grid.equations[0]) == "m*x'' + eps*m*cos(w*t)*x + delta*m*x"


def test_plots_draw_with_matplotlib():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    r = qdot.Scene.load(ABSORBER).response(set=SWEPT_SET, over="Omega=0.6:1.4:9")
    amp, phase = r.plot()
    assert len(amp.lines) == 2 + 2  # two coordinates, two natural frequencies
    grid = qdot.Scene.load(MATHIEU).floquet(set="m=1,w=1", over="delta=-0.5:2.5:4,eps=0:2:3")
    ax = grid.plot()
    assert len(ax.collections) == 2
    with pytest.raises(ValueError, match="swept response"):
        qdot.Scene.load(ABSORBER).response().plot()


def test_errors_raise_the_diagnostic():
    with pytest.raises(qdot.QdotError) as e:
        qdot.Scene.load(MATHIEU).floquet(set="m=1")
    assert e.value.message
    with pytest.raises(qdot.QdotError, match="Omega"):
        qdot.Scene.load(ABSORBER).response(set=SWEPT_SET, over="Omega=1:0.5")


def test_run_command_reads_the_one_table(cli):
    assert list(qdot.COMMANDS)[:3] == ["derive", "solve", "forces"]
    for name in ("cycle", "response", "floquet"):
        assert name in qdot.COMMANDS
    assert qdot.COMMANDS["cycle"] == ("csv", "json", "text")
    scene = qdot.Scene.load(SEED_21_3)
    out = qdot.run_command(
        "cycle", scene, "csv", over="phi=0:360deg:13",
        set="G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20",
        guess="x2=0.25,xB=0.5", columns=["M"])
    theirs = cli_out(
        cli, "cycle", SEED_21_3, "--over", "phi=0:360deg:13", "--set",
        "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20",
        "--guess", "x2=0.25,xB=0.5", "--columns", "M")
    assert out == theirs and out.splitlines()[0] == "phi,M,note"
    assert qdot.run_command("solve", qdot.Scene.load(ABSORBER), "json") == cli_out(
        cli, "solve", ABSORBER, "--format", "json")
    with pytest.raises(ValueError, match="did you mean 'floquet'"):
        qdot.run_command("floquett", scene)
    with pytest.raises(ValueError, match="writes text, json, latex"):
        qdot.run_command("solve", scene, "csv")


def test_cycle_takes_columns(cli):
    c = qdot.Scene.load(SEED_21_3).cycle(
        "phi=0:360deg:13",
        set="G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20",
        guess="x2=0.25,xB=0.5", columns=["O_x", "M"])
    assert c.columns == ["phi", "O_x", "M"] and c.values.shape == (13, 3)
    theirs = cli_out(
        cli, "cycle", SEED_21_3, "--over", "phi=0:360deg:13", "--set",
        "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20",
        "--guess", "x2=0.25,xB=0.5", "--columns", "O_x,M", "--output", "json")
    assert c.to_json() == theirs
    assert json.loads(theirs)["columns"] == ["phi", "O_x", "M"]
