#!/usr/bin/env python3
"""Anchor timing: SymPy's mechanics on a 3D chain of n rigid rods.

The chain (the same system as the `chain3d_n*` cases of
tests/fixtures/frames.json, which check this model against its scene text):
rod k turns about the previous rod's x axis (k odd) or y axis (k even) by
q_k; every rod has mass m, central inertia [A, A, C] along its own axes and
length l; rod k's centre is l/2 below its joint along its own -z axis and the
next joint is at l; gravity is [0, 0, -g].  The qdot scene text for the same
system is printed by `--scene`:

    frame B1 = rot(x, q1)
    frame B2 = B1 * rot(y, q2)
    body b1: mass m, inertia [A, A, C], frame B1, at -l/2*axis(B1, 3)
    P1 = -l*axis(B1, 3)
    body b2: mass m, inertia [A, A, C], frame B2, at P1 - l/2*axis(B2, 3)
    ...
    gravity [0, 0, -g]

Timed with time.perf_counter():
  equations_s    building frames, points and bodies (orient_axis, v2pt_theory,
                 RigidBody, inertia), Lagrangian(N, *bodies) and
                 LagrangesMethod(L, q).form_lagranges_equations();
  mass_matrix_s  reading lm.mass_matrix afterwards.  (In SymPy 1.14
                 form_lagranges_equations already forms the mass matrix as a
                 Jacobian, so this is only the property access: ~0.)
With --repeat R the system is derived R times, each time from a cleared
SymPy cache (cold, like the first run), and the best time of each part is
reported.

Figures measured on this project's 2-core machine (SymPy 1.14, 2026-11, one
cold run each, for orientation only: always measure qdot and the anchor in
the same run):  n = 2: 0.32 s,  3: 1.8 s,  4: 8.6 s,  5: 33 s (37.4 s in a
second run on a loaded machine),  6: 104 s,  7: 292 s,  8: 726 s;  n = 10 had
not finished after 84 wall / 81 CPU minutes (killed).
The time is spent in form_lagranges_equations (d/dt of the unexpanded
Lagrangian's partial derivatives); building the model takes < 1 s.

qdot on the same system (criterion, benches/derive.rs group `frames`, one
run): heavy_top 307 us; chain3d n = 2: 111 us, 3: 441 us, 5: 8.3 ms
(about 4,500x SymPy's 37.4 s); n = 10: about 35 s for a CLI derive, which
stops at the print budget after expanding 6.7 M symbols, so the ratio there
is more than 140x (SymPy did not finish in 84 minutes).

Usage:
    python3 scripts/anchor_frames.py --n 10 [--repeat 3]
        prints one JSON line {"n": 10, "equations_s": ..., "mass_matrix_s": ...}
    python3 scripts/anchor_frames.py --n 10 --scene
        prints the qdot scene text for that n
"""
import argparse
import json
import time

import sympy as sp
from sympy.core.cache import clear_cache
from sympy.physics.mechanics import (LagrangesMethod, Lagrangian, Point,
                                     ReferenceFrame, RigidBody,
                                     dynamicsymbols, inertia)


def scene_text(n):
    """The qdot scene of the n-rod chain."""
    lines = ["# 3D chain of %d rods, joint axes alternating x, y, x, ..." % n,
             "coordinates " + ", ".join("q%d" % (k + 1) for k in range(n)),
             "parameters m, A, C, l, g"]
    for k in range(1, n + 1):
        ax = "x" if k % 2 == 1 else "y"
        if k == 1:
            lines.append("frame B1 = rot(x, q1)")
        else:
            lines.append("frame B%d = B%d * rot(%s, q%d)" % (k, k - 1, ax, k))
    for k in range(1, n + 1):
        base = "" if k == 1 else "P%d " % (k - 1)
        lead = "-l/2*" if k == 1 else "- l/2*"
        lines.append("body b%d: mass m, inertia [A, A, C], frame B%d, at %s%saxis(B%d, 3)"
                     % (k, k, base, lead, k))
        if k < n:
            lead = "-l*" if k == 1 else "- l*"
            lines.append("P%d = %s%saxis(B%d, 3)" % (k, base, lead, k))
    lines.append("gravity [0, 0, -g]")
    return "\n".join(lines) + "\n"


def chain(n):
    """SymPy mechanics model of the chain: (coordinates, ground frame, bodies)."""
    q = dynamicsymbols("q1:%d" % (n + 1))
    m, A, C, l, g = sp.symbols("m A C l g", positive=True)
    N = ReferenceFrame("N")
    O = Point("O")
    O.set_vel(N, 0)
    parent, joint = N, O
    bodies = []
    for k in range(n):
        B = ReferenceFrame("B%d" % (k + 1))
        B.orient_axis(parent, parent.x if k % 2 == 0 else parent.y, q[k])
        G = joint.locatenew("G%d" % (k + 1), -l / 2 * B.z)
        G.v2pt_theory(joint, N, B)
        body = RigidBody("b%d" % (k + 1), G, B, m, (inertia(B, A, A, C), G))
        body.potential_energy = m * g * G.pos_from(O).dot(N.z)
        bodies.append(body)
        P = joint.locatenew("P%d" % (k + 1), -l * B.z)
        P.v2pt_theory(joint, N, B)
        parent, joint = B, P
    return q, N, bodies


def derive(n):
    t0 = time.perf_counter()
    q, N, bodies = chain(n)
    lm = LagrangesMethod(Lagrangian(N, *bodies), q)
    lm.form_lagranges_equations()
    t1 = time.perf_counter()
    M = lm.mass_matrix
    t2 = time.perf_counter()
    assert M.shape == (n, n)
    return t1 - t0, t2 - t1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=10, help="number of rods")
    ap.add_argument("--repeat", type=int, default=1, help="best of R cold runs")
    ap.add_argument("--scene", action="store_true", help="print the qdot scene instead")
    a = ap.parse_args()
    if a.n < 1:
        ap.error("--n must be at least 1")
    if a.scene:
        print(scene_text(a.n), end="")
        return
    best_eq = best_mm = None
    for _ in range(max(1, a.repeat)):
        clear_cache()
        eq, mm = derive(a.n)
        best_eq = eq if best_eq is None else min(best_eq, eq)
        best_mm = mm if best_mm is None else min(best_mm, mm)
    print(json.dumps({"n": a.n, "equations_s": round(best_eq, 6),
                      "mass_matrix_s": round(best_mm, 6)}), flush=True)


if __name__ == "__main__":
    main()
