#!/usr/bin/env python3
"""The reference of tests/floquet.rs: the Mathieu equation's stability
boundaries from SciPy's characteristic values, in the form of
examples/mathieu.qd, written to tests/fixtures/floquet/mathieu.json.

x'' + (delta + eps*cos(t))*x = 0 becomes, with t = 2*tau,
y'' + (a - 2*q*cos(2*tau))*y = 0 with a = 4*delta and q = -2*eps
(Abramowitz & Stegun 20.1.1). Since a_(2r+1)(-q) = b_(2r+1)(q) and
a_(2r)(-q) = a_(2r)(q), b_(2r)(-q) = b_(2r)(q) (A&S 20.8.2), the
boundaries in delta are the characteristic values at |q| = 2*eps over 4:
  the region delta < a_0/4 is unstable;
  the first tongue (delta near 1/4) lies between b_1/4 and a_1/4;
  the second (delta near 1) between b_2/4 and a_2/4.

Usage: /tmp/cycvenv/bin/python scripts/floquet_reference.py (needs scipy)
"""
import json
import pathlib

import scipy
from scipy.special import mathieu_a, mathieu_b

EPS = [0.01, 0.05, 0.1, 0.2]


def main():
    rows = []
    for eps in EPS:
        q = 2 * eps
        rows.append(
            {
                "eps": eps,
                "a0": mathieu_a(0, q) / 4,
                "b1": mathieu_b(1, q) / 4,
                "a1": mathieu_a(1, q) / 4,
                "b2": mathieu_b(2, q) / 4,
                "a2": mathieu_a(2, q) / 4,
            }
        )
    out = {
        "about": "boundaries in delta of x'' + (delta + eps*cos(t))*x = 0: "
        "characteristic values at q = 2*eps over 4 (scripts/floquet_reference.py)",
        "scipy": scipy.__version__,
        "rows": rows,
    }
    path = pathlib.Path(__file__).resolve().parent.parent / "tests/fixtures/floquet/mathieu.json"
    path.write_text(json.dumps(out, indent=2) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
