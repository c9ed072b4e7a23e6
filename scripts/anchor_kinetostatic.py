"""SymPy on the kinetostatic systems of seed problems 21.2 and 22.2 (the
same equations as examples/seed_21_2_kinetostatic.qd and
examples/seed_22_2_kinetostatic.qd), timed like qdot's `seed/*_kinetostatic`
criterion benches: build the symbols and equations, solve exactly
(sympy.linsolve), simplify each value; and seed 23.1's equilibrium by
sympy.solve, like `equilibrium/seed_23_1`. Prints the best of N runs in
seconds.

Usage: /tmp/anchors/bin/python scripts/anchor_kinetostatic.py [N=20]
"""
import sys
import time

import sympy as sp


def system_21_2():
    G, g, r = sp.symbols("G g r", positive=True)
    a3, eps3, T1, T2, T3, T4, N, Ff, H, V = sp.symbols("a3 eps3 T1 T2 T3 T4 N Ff H V")
    al = sp.pi / 6
    mu = 1 / sp.sqrt(3)
    m1 = m2 = G / g
    m3 = 3 * G / g
    m5 = 2 * G / g
    J3 = J4 = 4 * G * r**2 / g
    Fi1 = m1 * (a3 + 2 * r * eps3)
    Fi2 = m2 * (a3 - r * eps3)
    Fi3 = m3 * a3
    Mi3 = J3 * eps3
    Mi4 = J4 * a3 / (2 * r)
    Fi5 = m5 * a3 / 2
    eqs = [
        T1 - G + Fi1,
        T2 - G + Fi2,
        T3 - T1 - T2 - 3 * G + Fi3,
        T2 * r - T1 * 2 * r + Mi3,
        T4 * sp.cos(al) - H,
        V - T3 - T4 * sp.sin(al) - 3 * G,
        T3 * 2 * r - T4 * r - Mi4,
        T4 - Ff - 2 * G * sp.sin(al) - Fi5,
        N - 2 * G * sp.cos(al),
        Ff - mu * N,
    ]
    return eqs, [a3, eps3, T1, T2, T3, T4, N, Ff, H, V]


def system_22_2():
    G, g, r = sp.symbols("G g r", positive=True)
    a1, T1, T2, T3, T4, H, V, N, Mr, Ff = sp.symbols("a1 T1 T2 T3 T4 H V N Mr Ff")
    al = sp.pi / 6
    s = r / (20 * sp.sqrt(3))
    m1 = G / g
    m2 = m4 = 2 * G / g
    J2 = J3 = 4 * G * r**2 / g
    J4 = m4 * (3 * r / 2) ** 2 / 2
    Fi1, Fi2 = m1 * a1, m2 * a1
    Mi2, Mi3 = J2 * a1 / (2 * r), J3 * 3 * a1 / (4 * r)
    Fi4, Mi4 = m4 * 3 * a1 / 4, J4 * a1 / (2 * r)
    eqs = [
        T1 + Fi1 - G,
        T2 + T3 - T1 - 2 * G + Fi2,
        T2 * 2 * r - T3 * r - Mi2,
        H - T4 * sp.cos(al),
        V - 2 * G - T3 - T4 * sp.sin(al),
        T4 * r - T3 * 2 * r + Mi3,
        T4 - Fi4 - Ff - 2 * G * sp.sin(al),
        N - 2 * G * sp.cos(al),
        Mi4 + Mr - Ff * 3 * r / 2,
        Mr - s * N,
    ]
    return eqs, [a1, T1, T2, T3, T4, H, V, N, Mr, Ff]


def equilibrium_23_1():
    """Seed 23.1: Q_k = 0 by sympy.solve, as `qdot equilibrium` (without
    the stability classification)."""
    G, P, l = sp.symbols("G P l", positive=True)
    t1, t2 = sp.symbols("theta1 theta2")
    r1 = sp.Matrix([l * sp.sin(t1), l * sp.cos(t1)])
    r2 = sp.Matrix([2 * l * sp.sin(t1) + l * sp.sin(t2), 2 * l * sp.cos(t1) + l * sp.cos(t2)])
    r3 = sp.Matrix([2 * l * sp.sin(t1) + 2 * l * sp.sin(t2), 2 * l * sp.cos(t1) + 2 * l * sp.cos(t2)])
    F = [(sp.Matrix([0, G]), r1), (sp.Matrix([0, G]), r2), (sp.Matrix([P, 0]), r3)]
    Q = [sum((f.dot(r.diff(q)) for f, r in F), sp.S(0)) for q in (t1, t2)]
    return sp.solve(Q, [t1, t2], dict=True)


def modes_chain3():
    """The three-mass chain: M, K, det(K - lam*M), its roots and the
    eigenvectors, like `modes/chain3`."""
    m, k, lam = sp.symbols("m k lam", positive=True)
    M = sp.diag(m, m, m)
    K = sp.Matrix([[2 * k, -k, 0], [-k, 2 * k, -k], [0, -k, 2 * k]])
    p = sp.factor((K - lam * M).det())
    roots = sp.solve(p, lam)
    vecs = [(K - r * M).nullspace() for r in roots]
    return p, roots, vecs


def modes_24_2():
    m, k, lam = sp.symbols("m k lam", positive=True)
    M = sp.diag(4 * m, sp.Rational(3, 2) * m)
    K = sp.Matrix([[2 * k, -k], [-k, k]])
    p = sp.factor((K - lam * M).det())
    roots = sp.solve(p, lam)
    vecs = [(K - r * M).nullspace() for r in roots]
    return p, roots, vecs


def run(build):
    eqs, unknowns = build()
    (sol,) = sp.linsolve(eqs, unknowns)
    return [sp.simplify(v) for v in sol]


def best(build, n):
    t = []
    for _ in range(n):
        t0 = time.perf_counter()
        run(build)
        t.append(time.perf_counter() - t0)
    return min(t)


if __name__ == "__main__":
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    print("seed_21_2_kinetostatic", best(system_21_2, n), run(system_21_2)[:2])
    print("seed_22_2_kinetostatic", best(system_22_2, n), run(system_22_2)[0])
    t = []
    for _ in range(max(1, n // 4)):
        t0 = time.perf_counter()
        sols = equilibrium_23_1()
        t.append(time.perf_counter() - t0)
    print("equilibrium_23_1", min(t), len(sols), sols[:1])
    for name, f in [("modes_seed_24_2", modes_24_2), ("modes_chain3", modes_chain3)]:
        t = []
        for _ in range(n):
            t0 = time.perf_counter()
            out = f()
            t.append(time.perf_counter() - t0)
        print(name, min(t), out[0], out[1])
