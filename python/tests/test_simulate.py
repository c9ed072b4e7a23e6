"""simulate() and sweep(): NumPy arrays, the same numbers as the CLI."""

import numpy as np
import pytest

import qdot
from conftest import ROOT

PENDULUM = ROOT / "examples" / "pendulum.qd"


def test_simulate_is_the_cli_byte_for_byte(cli):
    scene = qdot.Scene.load(PENDULUM)
    sim = scene.simulate(set={"m": 1, "l": 1, "g": 9.81}, init={"theta": 2.5, "theta'": 0},
                         t_end=5, points=51, rtol=1e-10, atol=1e-12)
    out = cli("simulate", str(PENDULUM), "--set", "m=1,l=1,g=9.81", "--init", "theta=2.5,theta'=0",
              "--t-end", "5", "--points", "51", "--rtol", "1e-10", "--atol", "1e-12")
    assert out.returncode == 0, out.stderr
    assert sim.to_csv() == out.stdout
    table = np.loadtxt(out.stdout.splitlines()[1:], delimiter=",")
    assert np.array_equal(sim.data, table)
    assert sim.columns == ["t", "theta", "theta'", "energy"]
    assert sim.t.shape == (51,) and sim.q.shape == (51, 1) and sim.qdot.shape == (51, 1)
    assert sim.t[0] == 0 and sim.t[-1] == 5
    assert np.array_equal(sim["theta'"], sim.qdot[:, 0])
    # the energy is conserved to the tolerance
    assert np.max(np.abs(sim.energy - sim.energy[0])) < 1e-7
    assert sim.status == "done" and sim.stats["steps"] > 0


def test_simulate_methods_and_strings():
    scene = qdot.Scene.load(ROOT / "examples" / "seed_24_2.qd")
    # the first mode, x = (1, 4/3)·cos t with m = 1, k = 6
    for method in ["dop853", "vern7", "radau5"]:
        sim = scene.simulate(set="m=1,k=6,R=0.5", init="x1=1,x2=1.3333333333333333,x1'=0,x2'=0",
                             t_end=np.pi, points=3, method=method, rtol=1e-11, atol=1e-12)
        assert np.allclose(sim.q[-1], [-1, -4 / 3], atol=1e-8), method
    gauss = scene.simulate(set="m=1,k=6,R=0.5", init="x1=1,x2=1.3333333333333333,x1'=0,x2'=0",
                           t_end=np.pi, points=3, method="gauss6", dt=1e-3)
    assert np.allclose(gauss.q[-1], [-1, -4 / 3], atol=1e-8)


METHODS_HINT = ("the methods are rk4, dopri5, dop853, vern7 (explicit), gauss6 (symplectic) "
                "and radau5 (stiff)")


def test_a_method_has_one_name(cli):
    """SciPy's RK45 is qdot's dopri5: the name is refused with a hint that
    says so, in Python and on the command line alike (one method table)."""
    scene = qdot.Scene.load(PENDULUM)
    args = dict(set="m=1,l=1,g=1", init="theta=1,theta'=0", t_end=1, points=2)
    with pytest.raises(qdot.QdotError) as e:
        scene.simulate(method="rk45", **args)
    assert e.value.message == "unknown method `rk45`"
    assert e.value.hint == "SciPy's RK45 is `dopri5` here; " + METHODS_HINT
    with pytest.raises(qdot.QdotError) as e:
        scene.sweep(method="Radau", vary={"theta": (0.1, 1, 2)}, **args)
    assert e.value.hint == "SciPy's Radau is `radau5` here; " + METHODS_HINT
    with pytest.raises(qdot.QdotError) as e:
        scene.simulate(method="euler", **args)
    assert (e.value.message, e.value.hint) == ("unknown method `euler`", METHODS_HINT)
    # qdot's own names, in any case, run under that name
    assert scene.simulate(method="DOPRI5", **args).method == "dopri5"
    out = cli("simulate", str(PENDULUM), "--set", "m=1,l=1,g=1", "--init", "theta=1,theta'=0",
              "--t-end", "1", "--method", "rk45")
    assert out.returncode != 0
    assert "unknown method `rk45`" in out.stderr
    assert "= hint: SciPy's RK45 is `dopri5` here; " + METHODS_HINT in out.stderr


def test_a_velocity_not_given_is_zero():
    scene = qdot.Scene.load(PENDULUM)
    args = dict(set={"m": 1, "l": 1, "g": 9.81}, t_end=2, points=11)
    given = scene.simulate(init={"theta": 0.5, "theta'": 0}, **args)
    left_out = scene.simulate(init={"theta": 0.5}, **args)
    assert np.array_equal(given.data, left_out.data)
    # a coordinate is still required: it is where the run starts
    with pytest.raises(qdot.QdotError, match="no initial value for the coordinate theta"):
        scene.simulate(init={"theta'": 1}, **args)


def test_stop_when():
    scene = qdot.Scene.load(PENDULUM)
    sim = scene.simulate(set={"m": 1, "l": 1, "g": 1}, init={"theta": 3, "theta'": 0}, t_end=10,
                         stop_when="theta = 0", rtol=1e-12, atol=1e-12)
    assert sim.status == "event"
    # a quarter period: K(sin²(3/2)) = 4.038884843098342…
    assert abs(sim.t[-1] - 4.038884843098342) < 1e-9


def test_sweep_grid_matches_single_runs(cli):
    scene = qdot.Scene.load(PENDULUM)
    sw = scene.sweep(set={"m": 1, "g": 9.81}, init={"theta'": 0},
                     vary={"l": (0.5, 2, 4), "theta": (0.1, 3, 3)}, t_end=3, threads=2)
    assert len(sw) == 12 and sw.names == ["l", "theta"]
    assert sw.compilations == 12  # parameters vary: one per run
    assert all(s == "done" for s in sw.status)
    for i in [0, 5, 11]:
        l, th = sw.values[i]
        one = scene.simulate(set={"m": 1, "g": 9.81, "l": l}, init={"theta": th, "theta'": 0}, t_end=3)
        assert sw.q[i, 0] == one.q[-1, 0] and sw.qdot[i, 0] == one.qdot[-1, 0]
        assert sw.max_abs_q[i, 0] == np.max(np.abs(one.q[:, 0]))
        assert sw.energy_drift[i] == np.max(np.abs(one.energy - one.energy[0]))
    # the CLI prints the same sweep
    out = cli("sweep", str(PENDULUM), "--set", "m=1,g=9.81", "--init", "theta'=0",
              "--vary", "l=0.5:2:4", "--vary", "theta=0.1:3:3", "--t-end", "3")
    assert out.returncode == 0, out.stderr
    rows = out.stdout.splitlines()
    assert rows[0].split(",")[:5] == ["l", "theta", "status", "t", "theta(t)"]
    assert float(rows[6].split(",")[4]) == sw.q[5, 0]


def test_random_sweep_is_reproducible_and_compiles_once():
    scene = qdot.Scene.load(PENDULUM)
    args = dict(set={"m": 1, "g": 9.81, "l": 1}, init={"theta'": 0}, vary={"theta": (0.1, 3)},
                t_end=2, samples=200, seed=7)
    a, b = scene.sweep(**args, threads=1), scene.sweep(**args, threads=2)
    assert a.compilations == 1
    assert np.array_equal(a.values, b.values) and np.array_equal(a.q, b.q)
    assert np.all((a.values >= 0.1) & (a.values < 3))
    assert a.runs_per_second > 0


def test_sweep_errors():
    scene = qdot.Scene.load(PENDULUM)
    with pytest.raises(qdot.QdotError, match="not a parameter, a coordinate or a velocity"):
        scene.sweep(set={"m": 1, "g": 1, "l": 1}, init={"theta'": 0}, vary={"x": (0, 1, 2)}, t_end=1)
    with pytest.raises(qdot.QdotError, match="a grid needs COUNT"):
        scene.sweep(set={"m": 1, "g": 1, "l": 1}, init={"theta'": 0}, vary={"theta": (0, 1)}, t_end=1)
    with pytest.raises(qdot.QdotError, match="more than 1,000,000"):
        scene.sweep(set={"m": 1, "g": 1}, init={"theta'": 0},
                    vary={"theta": (0, 1, 1001), "l": (1, 2, 1001)}, t_end=1)


def test_the_work_budget_holds_in_python():
    """Scene(max_terms=…) bounds the exact work of every native call: past
    it, a QdotError naming the statement, never a hang."""
    path = ROOT / "examples" / "double_pendulum.qd"
    with pytest.raises(qdot.QdotError, match="expression too large: 3 terms while evaluating `E`"):
        qdot.Scene.load(path, max_terms=2)
    scene = qdot.Scene.load(path, max_terms=5)
    # the exact accelerations are past the budget: M and f serve
    sim = scene.simulate(set={"m1": 1, "m2": 1, "l1": 1, "l2": 1, "g": 9.81},
                         init={"th1": 1, "th2": 1, "th1'": 0, "th2'": 0}, t_end=1)
    assert sim.evaluator == "mass_matrix" and sim.status == "done"
    sw = scene.sweep(set={"m1": 1, "l1": 1, "l2": 1, "g": 9.81},
                     init={"th1": 1, "th2": 1, "th1'": 0, "th2'": 0}, vary={"m2": (1, 2, 2)}, t_end=1)
    assert sw.status == ["done", "done"]
