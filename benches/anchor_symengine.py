"""The work-precision report's symbolic anchor: SymEngine (C++ core) deriving
Lagrange's equations of the n-link planar pendulum chain (equal m, l), the
scene of qdot::engine::gallery::pendulum_chain.

Usage: anchor_symengine.py N [N ...]   (needs `pip install symengine`)
Prints one JSON object: the SymEngine version and, per n, the best wall time
of three runs of: positions, kinetic and potential energy, then for each
coordinate d/dt(∂L/∂q̇ₖ) by the chain rule over (q, q̇) minus ∂L/∂qₖ,
expanded. Time is measured around the derivation only (no printing)."""
import json
import sys
import time

import symengine as se


def lagrange_equations(n):
    m, l, g = se.symbols("m l g")
    q = [se.Symbol(f"q{k}") for k in range(1, n + 1)]
    v = [se.Symbol(f"v{k}") for k in range(1, n + 1)]  # q̇
    a = [se.Symbol(f"a{k}") for k in range(1, n + 1)]  # q̈
    x = y = vx = vy = se.Integer(0)
    kinetic = potential = se.Integer(0)
    for k in range(n):
        x += l * se.sin(q[k])
        y -= l * se.cos(q[k])
        vx += l * se.cos(q[k]) * v[k]
        vy += l * se.sin(q[k]) * v[k]
        kinetic += m * (vx**2 + vy**2) / 2
        potential += m * g * y
    lag = kinetic - potential
    out = []
    for k in range(n):
        p = lag.diff(v[k])
        dp = se.Integer(0)
        for j in range(n):
            dp += p.diff(q[j]) * v[j] + p.diff(v[j]) * a[j]
        out.append(se.expand(dp - lag.diff(q[k])))
    return out


def best_of(runs, f):
    best = float("inf")
    for _ in range(runs):
        t0 = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t0)
    return best


def main():
    ns = [int(a) for a in sys.argv[1:]] or [10, 20, 30]
    rows = []
    for n in ns:
        terms = sum(len(se.Add.make_args(e)) for e in lagrange_equations(n))
        rows.append({"n": n, "seconds": best_of(3, lambda: lagrange_equations(n)), "terms": terms})
    print(json.dumps({"symengine": se.__version__, "python": sys.version.split()[0], "rows": rows}))


if __name__ == "__main__":
    main()
