"""to_sympy(): qdot's results as SymPy objects, checked against SymPy's own
derivations (sympy.simplify(a - b) == 0)."""

import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import qdot
from conftest import EXAMPLES, ROOT

t = dynamicsymbols._t


def lagrange_accelerations(T, V, Q, qs):
    """SymPy's own derivation: d/dt ∂T/∂q̇ − ∂T/∂q + ∂V/∂q = Q, solved for q̈."""
    eqs = [
        sp.diff(sp.diff(T, q.diff(t)), t) - sp.diff(T, q) + sp.diff(V, q) - Qk
        for q, Qk in zip(qs, Q)
    ]
    qdd = [q.diff(t, 2) for q in qs]
    sol = sp.solve(eqs, qdd, dict=True)[0]
    return [sol[a] for a in qdd]


def test_seed_23_4_accelerations_equal_sympys_derivation():
    scene = qdot.Scene.load(ROOT / "examples" / "seed_23_4.qd")
    y3, th3 = dynamicsymbols("y3 theta3")
    G, g, r = sp.symbols("G g r", positive=True)  # qdot's parameters are positive
    mu = sp.Rational(1, 8)
    m, J = G / g, 4 * G * r**2 / g
    y1, y2, th4, x5 = y3 + 2 * r * th3, y3 - r * th3, y3 / (2 * r), y3 / 2
    d = lambda x: x.diff(t)  # noqa: E731
    T = (m * d(y1) ** 2 + m * d(y2) ** 2 + 3 * m * d(y3) ** 2 + J * d(th3) ** 2
         + J * d(th4) ** 2 + 2 * m * d(x5) ** 2) / 2
    U = G * y1 + G * y2 + 3 * G * y3
    work = -mu * 2 * G * x5  # δL = −μ·2G·δx5
    Q = [sp.diff(work, q) for q in (y3, th3)]
    want = lagrange_accelerations(T, -U, Q, [y3, th3])
    acc = scene.accelerations().to_sympy(dynamic=True)
    assert acc["y3"] == sp.Rational(343, 460) * g
    for a, b in zip([acc["y3"], acc["theta3"]], want):
        assert sp.simplify(a - b) == 0


def test_double_pendulum_equations_equal_sympys():
    scene = qdot.Scene.load(ROOT / "examples" / "double_pendulum.qd")
    th1, th2 = dynamicsymbols("th1 th2")
    m1, m2, l1, l2, g = sp.symbols("m1 m2 l1 l2 g", positive=True)
    x1, y1 = l1 * sp.sin(th1), -l1 * sp.cos(th1)
    x2, y2 = x1 + l2 * sp.sin(th2), y1 - l2 * sp.cos(th2)
    d = lambda x: x.diff(t)  # noqa: E731
    T = m1 * (d(x1) ** 2 + d(y1) ** 2) / 2 + m2 * (d(x2) ** 2 + d(y2) ** 2) / 2
    V = m1 * g * y1 + m2 * g * y2
    for q, eq in zip((th1, th2), scene.equations().to_sympy(dynamic=True)):
        el = sp.diff(sp.diff(T, q.diff(t)), t) - sp.diff(T, q) + sp.diff(V, q)
        assert is_zero(eq.lhs - eq.rhs - el)
    # and the accelerations solve M·q̈ = f
    M = scene.mass_matrix().to_sympy(dynamic=True)
    f = scene.forcing().to_sympy(dynamic=True)
    a = scene.accelerations().to_sympy(dynamic=True)
    r = M * sp.Matrix([a["th1"], a["th2"]]) - f
    assert is_zero(r[0]) and is_zero(r[1])


SEEDS = [p for p in EXAMPLES if p.stem.startswith("seed_")]


def is_zero(x):
    """Whether x is 0, decided exactly: the numerator of x with every
    sin(a), cos(a) expanded (expand_trig) and renamed S_a, C_a, reduced
    modulo the ideal of the S_a² + C_a² − 1 (a Gröbner basis: each in
    variables of its own). simplify() alone misses some of qdot's forms."""
    num = sp.expand(sp.expand_trig(sp.numer(sp.together(x))))
    args = {f.args[0] for f in num.atoms(sp.sin, sp.cos)}
    if not args:
        return sp.expand(num) == 0
    S = {a: sp.Dummy("S") for a in args}
    C = {a: sp.Dummy("C") for a in args}
    num = num.xreplace({sp.sin(a): S[a] for a in args}).xreplace({sp.cos(a): C[a] for a in args})
    gens = [S[a] for a in args] + [C[a] for a in args]
    _, r = sp.reduced(num, [S[a] ** 2 + C[a] ** 2 - 1 for a in args], *gens)
    return sp.expand(r) == 0


# A kinetostatic scene's solved acceleration, and the same problem solved by
# Lagrange's equations: (Lagrange scene, {unknown: coordinate}), and the
# answer of ../shared/problems.md.
KINETOSTATIC = {
    "seed_21_1_kinetostatic": ("seed_21_1", {"a1": "y1"}, {"a1": "256*g/715"}),
    "seed_21_2_kinetostatic": ("seed_21_2", {"a3": "y3", "eps3": "theta3"}, {"a3": "14*g/23"}),
    "seed_22_2_kinetostatic": ("seed_22_2", {"a1": "y1"}, {"a1": "178*g/635"}),
}


@pytest.mark.parametrize("path", SEEDS, ids=lambda p: p.stem)
def test_seed_accelerations_solve_the_equations_in_sympy(path):
    """For every seed problem with motion: SymPy checks that qdot's q̈ (and
    multipliers λ, for a scene with constraints) satisfy each of its
    Lagrange equations."""
    scene = qdot.Scene.load(path)
    try:
        solved = scene.solve()
    except qdot.QdotError as e:
        # a static or kinetostatic scene: the CLI refuses it the same way
        assert "no Lagrange equations" in str(e) or "is static" in str(e), str(e)
        return
    if path.stem in KINETOSTATIC:
        lagrange, unknowns, answers = KINETOSTATIC[path.stem]
        other = qdot.Scene.load(path.with_name(lagrange + ".qd")).accelerations()
        for unknown, q in unknowns.items():
            assert is_zero(solved.expr(solved["solutions"][unknown]).to_sympy() - other[q].to_sympy())
        for unknown, answer in answers.items():
            assert is_zero(solved.expr(solved["solutions"][unknown]).to_sympy() - solved.expr(answer).to_sympy())
        return
    if "mechanism" in solved.data:
        # a driven mechanism: its reactions, in solving order, satisfy
        # every equation with the accelerations and frictions as symbols
        values = {}
        for name, v in solved.data["mechanism"]["reactions"].items():
            values[sp.Symbol(name)] = solved.expr(v).to_sympy().subs(values)
        eqs = scene.equations()
        assert len(eqs) == len(values) > 0
        for eq in eqs:
            assert is_zero((eq.lhs.to_sympy() - eq.rhs.to_sympy()).subs(values)), str(eq)
        return
    acc = solved["accelerations"]
    subs = {sp.Symbol(q + "''"): solved.expr(a).to_sympy() for q, a in acc.items()}
    subs.update({sp.Symbol(k): solved.expr(v).to_sympy()
                 for k, v in solved.data.get("multipliers", {}).items()})
    eqs = scene.equations()
    assert len(eqs) == len(acc) > 0
    for eq in eqs:
        assert is_zero((eq.lhs.to_sympy() - eq.rhs.to_sympy()).subs(subs)), str(eq)


def test_seed_24_2_frequencies_are_sympys_eigenvalues():
    scene = qdot.Scene.load(ROOT / "examples" / "seed_24_2.qd")
    modes = scene.modes()
    M = sp.Matrix([[modes.expr(x).to_sympy() for x in row] for row in modes["mass_matrix"]])
    K = sp.Matrix([[modes.expr(x).to_sympy() for x in row] for row in modes["stiffness_matrix"]])
    eig = set((M.inv() * K).eigenvals())
    ours = set(modes.expr(w).to_sympy() for w in modes["omega_squared"])
    assert {sp.simplify(x) for x in eig} == {sp.simplify(x) for x in ours}


def test_symbols_and_primes():
    scene = qdot.Scene.load(ROOT / "examples" / "seed_23_4.qd")
    g = sp.Symbol("g", positive=True)
    acc = scene.accelerations().to_sympy(symbols={"g": g})
    assert acc["y3"] == sp.Rational(343, 460) * g
    eq = scene.equations()[0]
    plain = eq.lhs.to_sympy()
    assert sp.Symbol("y3''") in plain.free_symbols
    dyn = eq.lhs.to_sympy(dynamic=True)
    assert dynamicsymbols("y3").diff(t, 2) in dyn.atoms(sp.Derivative)


def test_functions_and_big_numbers():
    e = qdot.Expr("-3*sin(th)^2*ln(x)/sqrt(2) + 123456789012345678901234567890*pi")
    got = e.to_sympy()
    th, x = sp.symbols("th x")
    want = -3 * sp.sin(th) ** 2 * sp.log(x) / sp.sqrt(2) + 123456789012345678901234567890 * sp.pi
    assert sp.simplify(got - want) == 0


def test_long_sums_do_not_nest():
    text = " + ".join(f"{k}*x^{k}" for k in range(1, 600))
    got = qdot.Expr(text).to_sympy()
    x = sp.Symbol("x")
    assert sp.expand(got - sum(k * x**k for k in range(1, 600))) == 0


def test_parameters_are_positive_symbols_as_qdot_assumes():
    scene = qdot.Scene.load(ROOT / "examples" / "seed_23_4.qd")
    symbols = scene.sympy_symbols()
    assert list(symbols) == ["y3", "theta3", "G", "g", "r"]
    g, r = symbols["g"], symbols["r"]
    assert g == sp.Symbol("g", positive=True) and g != sp.Symbol("g")
    assert g.is_positive is True and sp.ask(sp.Q.positive(r)) is True
    assert sp.sqrt(r**2) == r and sp.Abs(g) == g
    # the results' symbols are these very ones
    acc = scene.accelerations().to_sympy()
    assert acc["y3"] == sp.Rational(343, 460) * g
    assert acc["theta3"].free_symbols == {g, r}
    assert scene.mass_matrix().to_sympy()[1, 1].free_symbols == {symbols["G"], g, r}
    # coordinates are as SymPy makes them: plain Symbols, or dynamicsymbols
    assert symbols["y3"] == sp.Symbol("y3") and symbols["y3"].is_positive is None
    assert scene.sympy_symbols(dynamic=True)["y3"] == dynamicsymbols("y3")
    # symbols= of the user's own still wins
    assert scene.accelerations().to_sympy(symbols={"g": sp.Symbol("g")})["y3"] == (
        sp.Rational(343, 460) * sp.Symbol("g"))


def test_a_parameter_assumed_real_is_a_real_symbol():
    scene = qdot.Scene.load(ROOT / "examples" / "mathieu.qd")
    symbols = scene.sympy_symbols()
    delta, eps, m, w = (symbols[n] for n in ("delta", "eps", "m", "w"))
    assert (delta.is_real, delta.is_positive, eps.is_real, eps.is_positive) == (True, None, True, None)
    assert (m.is_positive, w.is_positive) == (True, True)
    assert sp.sqrt(delta**2) == sp.Abs(delta) and sp.sqrt(m**2) == m
    x, t = symbols["x"], sp.Symbol("t")
    assert scene.accelerations().to_sympy()["x"] == -eps * x * sp.cos(w * t) - delta * x


def test_an_expression_without_a_scene_has_plain_symbols():
    # no scene, no parameters: nothing is assumed of the names
    assert qdot.Expr("sqrt(m^2)").to_sympy() == sp.sqrt(sp.Symbol("m") ** 2)
