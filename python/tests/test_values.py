"""Numbers as people write them: ``set=``/``init=``/``vary=`` take text
(``"30deg"``, ``"2*pi"``, ``"pi/6"``) read by the CLI's one evaluator, and a
value it refuses raises :class:`qdot.QdotError`, never a bare ValueError."""

import math

import numpy as np
import pytest

import qdot
from conftest import ROOT

PENDULUM = ROOT / "examples" / "pendulum.qd"
HOOP = """coordinates theta: angle
parameters m, R, Omega, g
kinetic E = 1/2*m*R^2*(theta'^2 + Omega^2*sin(theta)^2)
potential V = -m*g*R*cos(theta)
"""


def test_init_30deg_is_the_cli_byte_for_byte(cli):
    scene = qdot.Scene.load(PENDULUM)
    sim = scene.simulate(set={"m": 1, "l": "1/2", "g": 9.81}, init={"theta": "30deg"},
                         t_end=1, points=5)
    out = cli("simulate", str(PENDULUM), "--set", "m=1,l=1/2,g=9.81", "--init", "theta=30deg",
              "--t-end", "1", "--points", "5")
    assert out.returncode == 0, out.stderr
    assert sim.to_csv() == out.stdout
    assert sim["theta"][0] == 30 * (math.pi / 180)
    # the same double written out gives the same run
    plain = scene.simulate(set={"m": 1, "l": 0.5, "g": 9.81}, init={"theta": 0.5235987755982988},
                           t_end=1, points=5)
    assert np.array_equal(sim.data, plain.data)


def test_set_2pi_in_every_numeric_method():
    scene = qdot.Scene(HOOP)
    written = {"m": 1, "R": 1, "Omega": "2*pi", "g": 9.81}
    plain = {"m": 1, "R": 1, "Omega": 2 * math.pi, "g": 9.81}
    a = scene.simulate(set=written, init={"theta": "pi/6"}, t_end=1, points=3)
    b = scene.simulate(set=plain, init={"theta": math.pi / 6}, t_end=1, points=3)
    assert np.array_equal(a.data, b.data)
    sa = scene.sweep(set={"m": 1, "R": 1, "g": 9.81}, init={"theta": "30deg"},
                     vary={"Omega": ("pi", "2*pi", 2)}, t_end=1, points=3, threads=1)
    sb = scene.sweep(set={"m": 1, "R": 1, "g": 9.81}, init={"theta": math.pi / 6},
                     vary={"Omega": (math.pi, 2 * math.pi, 2)}, t_end=1, points=3, threads=1)
    assert np.array_equal(sa.values, sb.values) and np.array_equal(sa.q, sb.q)
    assert sa.values[1, 0] == 2 * math.pi
    assert scene.modes(set=written).text == scene.modes(set=plain).text


@pytest.mark.parametrize("values, message", [
    ({"theta": "abc"}, "`--init theta=abc`: `abc` is not a number"),
    ({"theta": "1e400"},
     "`--init theta=1e400`: `1e400` is beyond the range of double precision (about 1.8e308)"),
    ({"theta": None}, "`--init theta=None`: `None` is not a number"),
    ({"theta": "1,theta'=2"}, "`theta=1,theta'=2`: one value for theta, not 2"),
])
def test_a_bad_init_value_is_a_qdot_error(values, message):
    scene = qdot.Scene.load(PENDULUM)
    with pytest.raises(qdot.QdotError) as e:
        scene.simulate(set={"m": 1, "l": 1, "g": 9.81}, init=values, t_end=1)
    assert message in str(e.value)


def test_a_bad_set_value_is_a_qdot_error():
    scene = qdot.Scene.load(PENDULUM)
    with pytest.raises(qdot.QdotError) as e:
        scene.simulate(set={"m": 1, "l": "sqrt(-1)", "g": 9.81}, init={"theta": 1}, t_end=1)
    assert e.value.message == "`--set l=sqrt(-1)`: `sqrt(-1)` is not a number"
    assert e.value.kind == "bad_option"


def test_floquet_threads_give_the_same_chart(cli):
    scene = qdot.Scene.load(ROOT / "examples" / "mathieu.qd")
    over = {"delta": (-0.5, 2.5, 13), "eps": (0, 2, 5)}
    one = scene.floquet(set={"m": 1, "w": 1}, over=over, threads=1)
    two = scene.floquet(set={"m": 1, "w": "2/2"}, over=over, threads=2)
    assert one.to_csv() == two.to_csv()
    out = cli("floquet", str(ROOT / "examples" / "mathieu.qd"), "--set", "m=1,w=1", "--over",
              "delta=-0.5:2.5:13,eps=0:2:5", "--output", "csv", "--threads", "1")
    assert out.returncode == 0, out.stderr
    assert one.to_csv() == out.stdout
