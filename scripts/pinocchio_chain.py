#!/usr/bin/env python3
"""Pinocchio reference fixture for the 3D chain of rigid rods.

The system is the chain of scripts/anchor_frames.py (its SymPy model `chain`
and its qdot scene text `scene_text` are the reference definition): rod k
turns about the previous rod's x axis (k odd) or y axis (k even) by q_k, rod
1 about the ground x axis at the origin; every rod has mass m, central
inertia diag[A, A, C] along its own axes and length l; rod k's centre is l/2
from its joint along its own -z axis and the next joint is at l along it;
gravity is [0, 0, -g].

As a pinocchio.Model, joint k is a JointModelRX (k odd) or JointModelRY
(k even) placed at the identity (k = 1) or at translation [0, 0, -l] in the
previous joint's frame (k > 1), carrying Inertia(m, [0, 0, -l/2],
diag[A, A, C]) (central inertia, in the joint's frame); model.gravity.linear
= [0, 0, -g].  Pinocchio's joint frames are the scene's frames B_k and its
joint angles are the scene's q_k, with the same sign (checked by --check
against SymPy).

What it writes: tests/fixtures/pinocchio_chain3d.json,
    {"generator": "scripts/pinocchio_chain.py", "pinocchio": VERSION,
     "scenes": {"N": qdot scene text of the N-rod chain, ...},
     "cases": [{"n", "seed", "params": {"m", "A", "C", "l", "g"},
                "q": [...], "qd": [...], "qdd": [...],
                "mass_matrix": [[...]], "nle": [...]}, ...]}
for n in 2, 3, 4, 8, 20, four cases each, every case drawn from
numpy.random.default_rng(seed): m, A, C, l, g uniform in [0.5, 2], q in
[-pi, pi], qd in [-2, 2].  qdd = pinocchio.aba(model, data, q, qd, 0) (no
torque); mass_matrix = crba (symmetrized: crba fills the upper triangle);
nle = pinocchio.nonLinearEffects (Coriolis, centrifugal and gravity), so that
mass_matrix * qdd = -nle.  Floats are written with Python's repr (the
shortest text that reads back to the same double, at most 17 significant
digits).  The scene texts come from scripts/anchor_frames.py.

How to run (Python 3 with pin, numpy and sympy; made with pin 4.1.0, numpy
2.4.6, SymPy 1.14.0, e.g. `python3 -m venv /tmp/pinvenv &&
/tmp/pinvenv/bin/pip install pin numpy sympy`):
    python3 scripts/pinocchio_chain.py > tests/fixtures/pinocchio_chain3d.json
    python3 scripts/pinocchio_chain.py --out tests/fixtures/pinocchio_chain3d.json
    python3 scripts/pinocchio_chain.py --check   # self-checks, prints a report
    python3 scripts/pinocchio_chain.py --time    # aba timings, JSON lines
CI does not need Python for this: the fixture is committed and the Rust test
reads the JSON.

--check: for n = 2 the kinetic energy of pinocchio.computeKineticEnergy
against 0.5 qd^T M qd; for every fixture case numpy's solve of M qdd = -nle
against aba (relative 1e-12); for n = 2 and 3, SymPy's Lagrange equations of
anchor_frames.chain (LagrangesMethod, mass_matrix * qdd = forcing) with the
first case's numbers against Pinocchio's M, -nle and qdd (relative 1e-10),
and SymPy's kinetic and potential energies against Pinocchio's.  An error is
max |a - b| / max(1, max |b|).  Exits 1 if any check fails.

--time: for n in 2, 5, 10, 20, 30, one JSON line per chain family,
{"family": "3d"|"planar", "n": n, "aba_ns": ...}: the median over repeats
of timeit's time per call of pinocchio.aba on random q, qd and zero torque.
"planar" is the same geometry with every joint a JointModelRY.  These are
Python-level times: they include the binding overhead (argument conversion
of the numpy arrays, the call into C++), which dominates for small n.
"""
import argparse
import json
import math
import os
import statistics
import sys
import timeit

import numpy as np
import pinocchio as pin

FIXTURE_N = (2, 3, 4, 8, 20)
CASES_PER_N = 4
TIME_N = (2, 5, 10, 20, 30)
PARAM_NAMES = ("m", "A", "C", "l", "g")


def chain_model(n, m, A, C, l, g, planar=False):
    """The n-rod chain as a pinocchio.Model (planar: every joint about y)."""
    model = pin.Model()
    inertia = pin.Inertia(m, np.array([0.0, 0.0, -l / 2]), np.diag([A, A, C]))
    parent = 0
    for k in range(1, n + 1):
        about_x = k % 2 == 1 and not planar
        joint = pin.JointModelRX() if about_x else pin.JointModelRY()
        offset = np.zeros(3) if k == 1 else np.array([0.0, 0.0, -l])
        placement = pin.SE3(np.eye(3), offset)
        parent = model.addJoint(parent, joint, placement, "q%d" % k)
        model.appendBodyToJoint(parent, inertia, pin.SE3.Identity())
    model.gravity.linear = np.array([0.0, 0.0, -g])
    return model


def mass_matrix(model, data, q):
    """crba's joint-space inertia matrix, symmetrized."""
    M = pin.crba(model, data, q).copy()
    return np.triu(M) + np.triu(M, 1).T


def draw_case(n, seed):
    """Parameters and state of one case, all drawn from the seed."""
    rng = np.random.default_rng(seed)
    params = dict(zip(PARAM_NAMES, rng.uniform(0.5, 2.0, 5).tolist()))
    q = rng.uniform(-math.pi, math.pi, n)
    qd = rng.uniform(-2.0, 2.0, n)
    return params, q, qd


def solve_case(n, seed):
    """One fixture case: the drawn numbers and Pinocchio's answers."""
    params, q, qd = draw_case(n, seed)
    model = chain_model(n, **params)
    data = model.createData()
    qdd = pin.aba(model, data, q, qd, np.zeros(n)).copy()
    M = mass_matrix(model, data, q)
    nle = pin.nonLinearEffects(model, data, q, qd).copy()
    return {"n": n, "seed": seed, "params": params, "q": q.tolist(),
            "qd": qd.tolist(), "qdd": qdd.tolist(),
            "mass_matrix": M.tolist(), "nle": nle.tolist()}


def fixture_cases():
    return [solve_case(n, 1000 * n + i) for n in FIXTURE_N for i in range(CASES_PER_N)]


def scenes():
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from anchor_frames import scene_text
    return {str(n): scene_text(n) for n in FIXTURE_N}


def render(fixture):
    """The fixture as JSON text: one line per vector and per matrix row."""
    def flat(v):
        return json.dumps(v)
    out = ["{",
           ' "generator": %s,' % flat(fixture["generator"]),
           ' "pinocchio": %s,' % flat(fixture["pinocchio"]),
           ' "scenes": {']
    items = list(fixture["scenes"].items())
    for i, (n, text) in enumerate(items):
        out.append("  %s: %s%s" % (flat(n), flat(text), "," if i + 1 < len(items) else ""))
    out.append(" },")
    out.append(' "cases": [')
    for i, case in enumerate(fixture["cases"]):
        rows = ",\n    ".join(flat(r) for r in case["mass_matrix"])
        out.append("  {\"n\": %d, \"seed\": %d,\n   \"params\": %s,\n"
                   "   \"q\": %s,\n   \"qd\": %s,\n   \"qdd\": %s,\n"
                   "   \"mass_matrix\": [\n    %s],\n   \"nle\": %s}%s"
                   % (case["n"], case["seed"], flat(case["params"]), flat(case["q"]),
                      flat(case["qd"]), flat(case["qdd"]), rows, flat(case["nle"]),
                      "," if i + 1 < len(fixture["cases"]) else ""))
    out.append(" ]")
    out.append("}")
    text = "\n".join(out) + "\n"
    assert json.loads(text) == fixture, "render must read back to the same data"
    return text


def write_fixture(out):
    fixture = {"generator": "scripts/pinocchio_chain.py", "pinocchio": pin.__version__,
               "scenes": scenes(), "cases": fixture_cases()}
    text = render(fixture)
    if out is None or out == "-":
        sys.stdout.write(text)
    else:
        with open(out, "w") as f:
            f.write(text)


def rel_err(a, b):
    """max |a - b| relative to max |b|, with 1 as the floor of the scale."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.max(np.abs(a - b)) / max(1.0, float(np.max(np.abs(b)))))


def report(name, err, tol):
    ok = err <= tol
    print("%-58s max rel err %.3e (tol %.0e) %s" % (name, err, tol, "ok" if ok else "FAIL"))
    return ok


def check_energy():
    """n = 2: Pinocchio's kinetic energy against 0.5 qd^T M qd."""
    ok = True
    for i in range(CASES_PER_N):
        params, q, qd = draw_case(2, 2000 + i)
        model = chain_model(2, **params)
        data = model.createData()
        T = pin.computeKineticEnergy(model, data, q, qd)
        M = mass_matrix(model, data, q)
        ok &= report("n=2 seed %d: computeKineticEnergy vs qd^T M qd / 2" % (2000 + i),
                     rel_err(T, 0.5 * qd @ M @ qd), 1e-12)
    return ok


def check_solve():
    """Every fixture case: numpy's solve of M qdd = -nle against aba."""
    ok = True
    for case in fixture_cases():
        qdd = np.linalg.solve(np.array(case["mass_matrix"]), -np.array(case["nle"]))
        ok &= report("n=%d seed %d: solve(M, -nle) vs aba" % (case["n"], case["seed"]),
                     rel_err(qdd, case["qdd"]), 1e-12)
    return ok


def check_sympy(n):
    """SymPy's Lagrange equations of anchor_frames.chain against Pinocchio."""
    import sympy as sp
    from sympy.physics.mechanics import (LagrangesMethod, Lagrangian, dynamicsymbols,
                                         kinetic_energy,
                                         msubs, potential_energy)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from anchor_frames import chain

    case = solve_case(n, 1000 * n)
    q, N, bodies = chain(n)
    lm = LagrangesMethod(Lagrangian(N, *bodies), q)
    lm.form_lagranges_equations()
    t = dynamicsymbols._t
    values = {sp.Symbol(k, positive=True): v for k, v in case["params"].items()}
    values.update({qk.diff(t): v for qk, v in zip(q, case["qd"])})
    values.update({qk: v for qk, v in zip(q, case["q"])})

    def number(expr):
        return np.array(sp.Matrix(msubs(expr, values)).evalf(30), dtype=float)

    M = number(lm.mass_matrix)
    f = number(lm.forcing).reshape(n)
    qdd = np.linalg.solve(M, f)
    T = float(msubs(kinetic_energy(N, *bodies), values).evalf(30))
    V = float(msubs(potential_energy(*bodies), values).evalf(30))

    model = chain_model(n, **case["params"])
    data = model.createData()
    q_, qd_ = np.array(case["q"]), np.array(case["qd"])
    T_pin = pin.computeKineticEnergy(model, data, q_, qd_)
    V_pin = pin.computePotentialEnergy(model, data, q_)
    tag = "n=%d seed %d: SymPy" % (n, case["seed"])
    ok = report(tag + " mass matrix vs crba", rel_err(M, case["mass_matrix"]), 1e-10)
    ok &= report(tag + " forcing vs -nle", rel_err(f, -np.array(case["nle"])), 1e-10)
    ok &= report(tag + " qdd vs aba", rel_err(qdd, case["qdd"]), 1e-10)
    ok &= report(tag + " kinetic energy", rel_err(T, T_pin), 1e-10)
    ok &= report(tag + " potential energy", rel_err(V, V_pin), 1e-10)
    return ok


def check():
    print("pinocchio %s, numpy %s" % (pin.__version__, np.__version__))
    ok = check_energy()
    ok &= check_solve()
    try:
        import sympy
    except ImportError:
        print("SymPy not installed: SymPy cross-check skipped")
    else:
        print("sympy %s" % sympy.__version__)
        for n in (2, 3):
            ok &= check_sympy(n)
    print("all checks passed" if ok else "SOME CHECKS FAILED")
    return ok


def time_aba():
    """Python-level time per pinocchio.aba call, JSON lines."""
    for n in TIME_N:
        for family in ("3d", "planar"):
            params, q, qd = draw_case(n, 7000 + n)
            model = chain_model(n, planar=family == "planar", **params)
            data = model.createData()
            tau = np.zeros(n)
            timer = timeit.Timer(lambda: pin.aba(model, data, q, qd, tau))
            number, _ = timer.autorange()
            number = max(number, 1000)
            per_call = [s / number for s in timer.repeat(repeat=15, number=number)]
            print(json.dumps({"family": family, "n": n,
                              "aba_ns": round(statistics.median(per_call) * 1e9, 1)}),
                  flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", help="write the fixture here instead of stdout ('-' = stdout)")
    ap.add_argument("--check", action="store_true", help="run the self-checks instead")
    ap.add_argument("--time", action="store_true", help="time pinocchio.aba instead")
    a = ap.parse_args()
    if a.check:
        sys.exit(0 if check() else 1)
    if a.time:
        time_aba()
        return
    write_fixture(a.out)


if __name__ == "__main__":
    main()
