#!/usr/bin/env python3
"""Times SymPy's factor_list on the polynomials of benches/factor.rs (the
anchor for `cargo bench -p qdot-benches --bench factor`): median of repeated runs, in µs.

Usage: python3 scripts/anchor_factor.py
"""
import statistics
import time

from sympy import factor_list, symbols, sympify

x, y, z, k, m, l = symbols("x y z k m l")

# keep in step with CASES in benches/factor.rs
CASES = [
    ("x15_minus_1", "x^15 - 1"),
    ("swinnerton_dyer_8", "x^8 - 40*x^6 + 352*x^4 - 960*x^2 + 576"),
    ("univariate_deg12", "(3*x^4 - 7*x^3 + 2*x - 11)*(x^5 + 13*x^2 - 5)*(2*x^3 + x^2 - 17)"),
    ("x6_minus_y6", "x^6 - y^6"),
    ("bivariate_quartics", "(x^2 + x*y + y^2 + 1)*(x^2 - x*y + y^2 - 3)*(x^2*y^2 - 2)"),
    ("charpoly_irreducible", "2*k^2 - 4*k*m*l + m^2*l^2"),
    ("charpoly_split", "(k^2 - m^2*l^2)*(2*k - m*l)*(k - 6*m*l)"),
    ("trivariate", "(x^2*y + z^2 - 3)*(x*z^2 + y^2 + 2*x)*(y^2*z^2 + x^2 + 1)"),
]


def main():
    ns = {"x": x, "y": y, "z": z, "k": k, "m": m, "l": l}
    for name, src in CASES:
        p = sympify(src.replace("^", "**"), locals=ns).expand()
        gens = sorted(p.free_symbols, key=str)
        factor_list(p, *gens)  # warm the caches
        times = []
        budget = time.perf_counter() + 2.0
        while len(times) < 5 or (time.perf_counter() < budget and len(times) < 200):
            t0 = time.perf_counter()
            factor_list(p, *gens)
            times.append(time.perf_counter() - t0)
        print(f"{name:24s} {statistics.median(times) * 1e6:12.1f} µs  ({len(times)} runs)")


if __name__ == "__main__":
    main()
