#!/usr/bin/env python3
"""Anchor timing: SymPy's KanesMethod on the 3D chain of n rigid rods.

The chain is the one of scripts/anchor_frames.py (its docstring and `chain`
define it; its `scene_text` is the qdot scene used here): rod k turns about
the previous rod's x axis (k odd) or y axis (k even) by q_k, rod 1 about the
ground x axis at the origin; every rod has mass m, central inertia [A, A, C]
along its own axes and length l; rod k's centre is l/2 below its joint along
its own -z axis and the next joint is at l; gravity is [0, 0, -g].

As a KanesMethod model (`kane_chain`): frame B_k is oriented with
orient_axis about the parent's x or y axis by q_k and given the angular
velocity u_k times that axis (generalized speeds u_k, kinematic differential
equations q_k' - u_k = 0); centres and joints are located with locatenew and
their velocities found with v2pt_theory; each rod is a RigidBody with its
inertia about its centre; the loads are the weights (G_k, -m*g*N.z).  With
u = q' KanesMethod's equations read mass_matrix * u' = forcing, the same as
M q'' = f.

What it reports, one JSON line per run:
    {"n": n,
     "kanes_s": seconds (time.perf_counter) for
                KanesMethod(N, q, u, kd_eqs).kanes_equations(bodies, loads),
     "mass_matrix_ops": sum of sympy.count_ops(e, visual=False) over the
                entries of kane.mass_matrix,
     "forcing_ops": the same over kane.forcing,
     "qdot_s": wall seconds of `qdot solve --format json` on the scene text
                (a subprocess; includes process start and writing the JSON),
     "qdot_json_bytes": the size of that JSON}
Building the model (frames, points, bodies) is not timed.  With --repeat R
each side runs R times and the best time is reported; every SymPy run is in
a fresh forked process that first clears SymPy's cache (cold, like
anchor_frames.py).  With --timeout S a SymPy run (derivation and op counts)
that takes more than S seconds is killed and kanes_s, mass_matrix_ops and
forcing_ops are null; qdot still runs.

--check: for n = 2 and 3, KanesMethod's mass matrix and forcing evaluated
(30 digits, then floats) at the first case of that n in
tests/fixtures/pinocchio_chain3d.json (Pinocchio's crba, nle and aba at a
random state, see scripts/pinocchio_chain.py), compared as mass matrix vs
crba, forcing vs -nle and solve(mass_matrix, forcing) vs aba's q''.  An
error is max |a - b| / max(1, max |b|); tolerance 1e-10.  Exits 1 if any
check fails.

Figures measured on this project's 2-core machine (SymPy 1.14, qdot release
build of 2026-11-27 with named intermediates, 2026-11; best of 3 cold runs
for n <= 8, one run for n = 10 and 12; other builds were running, load 1.5
to 2.9; for orientation only: always measure qdot and the anchor in the same
run).  "ops" is mass_matrix_ops + forcing_ops:

     n   kanes_s          ops   qdot_s   qdot JSON bytes
     2     0.061          157   0.0063             1,938
     3     0.14         1,358   0.19              58,335
     4     0.34         7,132   0.027             38,808
     5     0.86        27,530   0.043             67,068
     6     2.0         88,250   0.062            103,342
     7     4.7        247,988   0.089            147,860
     8    10.0        635,515   0.12             201,079
    10    43        3,436,956   0.33             337,960
    12   165       15,703,088   0.38             522,714

KanesMethod is far faster than LagrangesMethod on this chain (n = 6: 2.0 s
against 104 s in anchor_frames.py; n = 10: 43 s against more than 84
minutes) because it forms no Lagrangian to differentiate; its M and f are
left unexpanded and grow about 2.3x to 2.7x per rod in ops (n = 12: 15.7 M
ops, 240 MB peak for the whole process).  qdot's n = 3 stands out: its
expanded M and f are under the size rule (256 terms) so it writes them, and
the exact accelerations, in full (52 kB of the 58 kB); from n = 4 on it
writes named intermediates and names the accelerations through the
factorization of M, which is cheaper.

Usage:
    python3 scripts/anchor_kane.py --n 5 [--repeat 3] [--qdot PATH] [--timeout 600]
        prints one JSON line as above
    python3 scripts/anchor_kane.py --check [--fixture PATH]
        prints a report of the cross-check against Pinocchio
"""
import argparse
import json
import multiprocessing
import os
import subprocess
import sys
import tempfile
import time

import sympy as sp
from sympy.core.cache import clear_cache
from sympy.physics.mechanics import (KanesMethod, Point, ReferenceFrame,
                                     RigidBody, dynamicsymbols, inertia, msubs)

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from anchor_frames import scene_text  # noqa: E402  (the one scene text of the chain)

FIXTURE = os.path.join(ROOT, "tests", "fixtures", "pinocchio_chain3d.json")
CHECK_N = (2, 3)
CHECK_TOL = 1e-10


def kane_chain(n):
    """KanesMethod model of the chain: (q, u, kd_eqs, ground frame, bodies, loads)."""
    q = dynamicsymbols("q1:%d" % (n + 1))
    u = dynamicsymbols("u1:%d" % (n + 1))
    m, A, C, l, g = sp.symbols("m A C l g", positive=True)
    N = ReferenceFrame("N")
    O = Point("O")
    O.set_vel(N, 0)
    parent, joint = N, O
    bodies, loads = [], []
    for k in range(n):
        axis = parent.x if k % 2 == 0 else parent.y
        B = ReferenceFrame("B%d" % (k + 1))
        B.orient_axis(parent, axis, q[k])
        B.set_ang_vel(parent, u[k] * axis)
        G = joint.locatenew("G%d" % (k + 1), -l / 2 * B.z)
        G.v2pt_theory(joint, N, B)
        bodies.append(RigidBody("b%d" % (k + 1), G, B, m, (inertia(B, A, A, C), G)))
        loads.append((G, -m * g * N.z))
        P = joint.locatenew("P%d" % (k + 1), -l * B.z)
        P.v2pt_theory(joint, N, B)
        parent, joint = B, P
    kd_eqs = [qk.diff() - uk for qk, uk in zip(q, u)]
    return q, u, kd_eqs, N, bodies, loads


def kanes_equations(n):
    """(seconds for KanesMethod(...).kanes_equations, the KanesMethod, q, u)."""
    q, u, kd_eqs, N, bodies, loads = kane_chain(n)
    t0 = time.perf_counter()
    kane = KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=kd_eqs)
    kane.kanes_equations(bodies, loads)
    seconds = time.perf_counter() - t0
    return seconds, kane, q, u


def ops(matrix):
    return int(sum(sp.count_ops(e, visual=False) for e in matrix))


def sympy_run(n, conn):
    """One cold SymPy run (in a child process): sends (kanes_s, M ops, f ops)."""
    clear_cache()
    seconds, kane, _, _ = kanes_equations(n)
    conn.send((seconds, ops(kane.mass_matrix), ops(kane.forcing)))
    conn.close()


def sympy_timed(n, timeout):
    """(kanes_s, M ops, f ops) of one forked run, or None past the timeout."""
    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    child = ctx.Process(target=sympy_run, args=(n, send))
    child.start()
    send.close()
    timed_out = not recv.poll(timeout)
    result = None
    if timed_out:
        child.terminate()
    else:
        try:
            result = recv.recv()
        except EOFError:
            pass
    child.join()
    if not timed_out and result is None:
        raise RuntimeError("the SymPy run for n = %d failed (exit code %s)"
                           % (n, child.exitcode))
    return result


def qdot_timed(qdot, scene_path, timeout):
    """(wall seconds, JSON bytes) of `qdot solve --format json` on the scene."""
    t0 = time.perf_counter()
    run = subprocess.run([qdot, "solve", "--format", "json", scene_path],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout)
    seconds = time.perf_counter() - t0
    if run.returncode != 0:
        raise RuntimeError("%s failed (exit %d): %s" % (qdot, run.returncode,
                                                         run.stderr.decode()[-2000:]))
    json.loads(run.stdout)
    return seconds, len(run.stdout)


def measure(n, repeat, qdot, timeout):
    kanes_s = mm_ops = f_ops = None
    for _ in range(repeat):
        result = sympy_timed(n, timeout)
        if result is None:
            kanes_s = mm_ops = f_ops = None
            break
        kanes_s = result[0] if kanes_s is None else min(kanes_s, result[0])
        mm_ops, f_ops = result[1], result[2]
    with tempfile.TemporaryDirectory() as tmp:
        scene_path = os.path.join(tmp, "chain%d.qd" % n)
        with open(scene_path, "w") as f:
            f.write(scene_text(n))
        qdot_s = size = None
        for _ in range(repeat):
            seconds, size = qdot_timed(qdot, scene_path, timeout)
            qdot_s = seconds if qdot_s is None else min(qdot_s, seconds)
    return {"n": n, "kanes_s": None if kanes_s is None else round(kanes_s, 6),
            "mass_matrix_ops": mm_ops, "forcing_ops": f_ops,
            "qdot_s": round(qdot_s, 6), "qdot_json_bytes": size}


def rel_err(a, b):
    """max |a - b| relative to max |b|, with 1 as the floor of the scale."""
    import numpy as np
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.max(np.abs(a - b)) / max(1.0, float(np.max(np.abs(b)))))


def report(name, err):
    ok = err <= CHECK_TOL
    print("%-52s max rel err %.3e (tol %.0e) %s" % (name, err, CHECK_TOL,
                                                     "ok" if ok else "FAIL"))
    return ok


def check_case(case):
    """KanesMethod's M and f at the case's numbers against Pinocchio's."""
    import numpy as np
    n = case["n"]
    _, kane, q, u = kanes_equations(n)
    values = {sp.Symbol(k, positive=True): v for k, v in case["params"].items()}
    values.update({uk: v for uk, v in zip(u, case["qd"])})
    values.update({qk: v for qk, v in zip(q, case["q"])})

    def number(expr):
        return np.array(sp.Matrix(msubs(expr, values)).evalf(30), dtype=float)

    M = number(kane.mass_matrix)
    f = number(kane.forcing).reshape(n)
    tag = "n=%d seed %d: KanesMethod" % (n, case["seed"])
    ok = report(tag + " mass matrix vs crba", rel_err(M, case["mass_matrix"]))
    ok &= report(tag + " forcing vs -nle", rel_err(f, -np.array(case["nle"])))
    ok &= report(tag + " solve(M, f) vs aba", rel_err(np.linalg.solve(M, f), case["qdd"]))
    return ok


def check(fixture_path):
    with open(fixture_path) as f:
        fixture = json.load(f)
    print("sympy %s, fixture %s (pinocchio %s)"
          % (sp.__version__, os.path.relpath(fixture_path), fixture["pinocchio"]))
    ok = True
    for n in CHECK_N:
        case = next(c for c in fixture["cases"] if c["n"] == n)
        ok &= check_case(case)
    print("all checks passed" if ok else "SOME CHECKS FAILED")
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=5, help="number of rods")
    ap.add_argument("--repeat", type=int, default=1, help="best of R cold runs")
    ap.add_argument("--qdot", default=os.path.join(ROOT, "target", "release", "qdot"),
                    help="the qdot binary (default target/release/qdot)")
    ap.add_argument("--timeout", type=float, default=None,
                    help="seconds after which a SymPy run is killed (reported null)")
    ap.add_argument("--check", action="store_true",
                    help="cross-check against the Pinocchio fixture instead")
    ap.add_argument("--fixture", default=FIXTURE, help="the Pinocchio fixture for --check")
    a = ap.parse_args()
    if a.check:
        sys.exit(0 if check(a.fixture) else 1)
    if a.n < 1:
        ap.error("--n must be at least 1")
    if a.repeat < 1:
        ap.error("--repeat must be at least 1")
    if not os.access(a.qdot, os.X_OK):
        ap.error("no qdot binary at %s (build it with `cargo build --release "
                 "--features cli` or pass --qdot PATH)" % a.qdot)
    print(json.dumps(measure(a.n, a.repeat, a.qdot, a.timeout)), flush=True)


if __name__ == "__main__":
    main()
