"""cycle(): a planar mechanism over its cycle, the same numbers and pictures
as ``qdot cycle``, and the NumPy reference of tests/fixtures/mechanisms."""

import json
import math

import numpy as np
import pytest

import qdot
from conftest import ROOT

SEED_21_3 = ROOT / "examples" / "seed_21_3.qd"
SET = "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20"
GUESS = "x2=0.25,xB=0.5"
OVER = "phi=0:360deg:13"
STICK = "stick: the relative velocity in the joint `S` vanishes here"


@pytest.fixture(scope="module")
def crank():
    return qdot.Scene.load(SEED_21_3).cycle(OVER, set=SET, guess={"x2": 0.25, "xB": 0.5})


def cli_cycle(cli, *extra):
    out = cli("cycle", str(SEED_21_3), "--over", OVER, "--set", SET, "--guess", GUESS, *extra)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_columns_and_the_stick_rows(crank):
    assert crank.varied == "phi" and crank.degrees
    coordinates = ["x1", "y1", "phi", "x2", "y2", "alpha", "xB", "yB"]
    reactions = ["O_x", "O_y", "A_x", "A_y", "B_x", "B_y", "S_n", "M", "S_f"]
    assert crank.columns == (["phi"] + coordinates + [q + "'" for q in coordinates]
                             + [q + "''" for q in coordinates] + reactions)
    assert crank.values.shape == (13, 34) and crank.values.dtype == np.float64
    assert len(crank) == 13
    # φ = 0°, 180°, 360°: the slider stops, its friction's sense is undefined
    stuck = [i for i, n in enumerate(crank.notes) if n is not None]
    assert stuck == [0, 6, 12]
    assert all(crank.notes[i].startswith(STICK) for i in stuck)
    first = crank.columns.index("O_x")
    for i in range(13):
        reactions_of_row = np.isnan(crank.values[i, first:])
        assert reactions_of_row.all() if i in stuck else not reactions_of_row.any(), i
        assert not np.isnan(crank.values[i, :first]).any(), i
    # the positions are known at a stick: the slider at its dead centres
    assert crank["xB"][0] == 0.5 and crank["xB"][6] == pytest.approx(0.3, abs=1e-15)
    assert crank["phi"][6] == math.pi and crank["phi"][12] == 2 * math.pi
    assert np.isnan(crank["M"][6]) and crank["M"][3] == pytest.approx(1.51637, abs=1e-5)
    # the linear systems the friction solve took: both sign cases of S_n at
    # every row, and at a stick both one-sided limits (two cases each)
    assert list(crank.iterations) == [4, 2, 2, 2, 2, 2, 4, 2, 2, 2, 2, 2, 4]
    with pytest.raises(KeyError, match="no column 'Q_x'; the columns are phi, x1"):
        crank["Q_x"]


def test_the_cli_json_exactly(crank, cli):
    out = cli_cycle(cli, "--output", "json")
    data = json.loads(out)
    assert crank.to_json() == out
    assert data["columns"] == crank.columns and data["varied"] == crank.varied
    assert data["notes"] == crank.notes
    assert data["iterations"] == crank.iterations.tolist()
    table = np.array([[math.nan if x is None else x for x in row] for row in data["rows"]])
    # every value, bit for bit (NaN where the CLI writes null)
    assert np.array_equal(crank.values, table, equal_nan=True)
    # one row with every value a number: φ = 90°
    assert crank.values[3].tolist() == data["rows"][3]


def test_the_cli_csv_byte_for_byte(crank, cli):
    assert crank.to_csv() == cli_cycle(cli)


def test_the_cli_pictures_byte_for_byte(crank, cli, tmp_path):
    cli_cycle(cli, "--plot", str(tmp_path / "cli.svg"), "--animate", str(tmp_path / "cli.html"))
    crank.plot(tmp_path / "py.svg")
    crank.animate(tmp_path / "py.html")
    svg = (tmp_path / "py.svg").read_text(encoding="utf-8")
    assert svg == (tmp_path / "cli.svg").read_text(encoding="utf-8")
    # titled with the scene's name (its first comment), as the CLI's
    assert svg.startswith("<svg") and "The seed&apos;s problem 21.3" in svg
    page = (tmp_path / "py.html").read_text(encoding="utf-8")
    assert page == (tmp_path / "cli.html").read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>") and "<title>The seed's problem 21.3 (§21.5)</title>" in page
    cli_cycle(cli, "--animate", str(tmp_path / "cli_anim.svg"))
    crank.animate(str(tmp_path / "py_anim.svg"))
    assert ((tmp_path / "py_anim.svg").read_text(encoding="utf-8")
            == (tmp_path / "cli_anim.svg").read_text(encoding="utf-8"))
    crank.plot(tmp_path / "titled.svg", title="Problem 21.3")
    assert "Problem 21.3" in (tmp_path / "titled.svg").read_text(encoding="utf-8")


def test_over_and_guess_in_every_form(crank):
    scene = qdot.Scene.load(SEED_21_3)
    params = dict(kv.split("=") for kv in SET.split(","))
    for over, guess in [({"phi": (0, "360deg", 13)}, GUESS),
                        ({"phi": (0, 2 * math.pi, 13)}, "x2=0.25,xB=0.5"),
                        ("phi=0:2pi:13", {"x2": 0.25, "xB": 0.5})]:
        other = scene.cycle(over, set={k: float(v) for k, v in params.items()}, guess=guess)
        assert np.array_equal(other.values, crank.values, equal_nan=True), over
        assert other.notes == crank.notes
    with pytest.raises(ValueError, match=r"over\['phi'\]: \(from, to, count\)"):
        scene.cycle({"phi": (0, 1)}, set=SET)


@pytest.mark.parametrize("name", ["slider_crank_engine", "marghitu_slider_crank"])
def test_the_numpy_reference_to_1e_9(name):
    """As tests/mechanisms.rs: every value of every row equals the
    fixture's to 1e-9·max(1, |value|); qdot's only other columns are the
    frictions NAME_f. (Not four_bar or quick_return here: after their `th2`,
    this process prints the double pendulum's cos(th1 - th2) as
    cos(th2 - th1), and test_scene.py compares it with the CLI's text.)"""
    f = json.loads((ROOT / "tests" / "fixtures" / "mechanisms" / f"{name}.json").read_text())
    c = qdot.Scene.load(ROOT / f["scene"]).cycle(f["over"], set=f["set"], guess=f["guess"])
    n = len(f["columns"])
    assert c.columns[:n] == f["columns"]
    assert all(extra.endswith("_f") for extra in c.columns[n:])
    assert c.notes == [None] * len(f["rows"])
    want = np.array(f["rows"])
    got = c.values[:, :n]
    assert got.shape == want.shape and len(want) > 0
    assert (np.abs(got - want) <= 1e-9 * np.maximum(1, np.abs(want))).all()


def test_an_unknown_parameter_is_an_error():
    scene = qdot.Scene.load(SEED_21_3)
    with pytest.raises(qdot.QdotError) as e:
        scene.cycle(OVER, set=SET + ",foo=1", guess=GUESS)
    assert str(e.value) == (
        "error: `--set foo=…`: `foo` is not a parameter of the scene\n"
        "  = hint: the parameters are G1, G2, G3, g, R, AB, AC, J2, k, l0, mu, omega"
    )
    assert e.value.message == "`--set foo=…`: `foo` is not a parameter of the scene"
    assert e.value.line == 0


def test_a_bad_over_is_the_cli_error(cli):
    scene = qdot.Scene.load(SEED_21_3)
    with pytest.raises(qdot.QdotError) as e:
        scene.cycle("phi=0:360deg", set=SET)
    out = cli("cycle", str(SEED_21_3), "--over", "phi=0:360deg", "--set", SET)
    # the CLI's message; its hint in Python's syntax (`over="…"`)
    assert out.returncode != 0
    assert str(e.value).splitlines()[0] == out.stderr.strip().splitlines()[0]
    assert e.value.kind == "bad_option"
    assert e.value.hint.startswith("write the varied quantity, its first and last values")
    assert e.value.hint.endswith('over="phi=0:360deg:73" or over="t=0:2:101"')
