#!/usr/bin/env python3
"""The compact-forms panel (issue 18): qdot's accelerations against SymPy's
simplify, counted with SymPy's count_ops.

    python3 scripts/compact_panel.py sympy QDOT_BINARY   # writes tests/fixtures/compact_panel.json
    python3 scripts/compact_panel.py table QDOT_BINARY   # the table of the note, from the fixture
    python3 scripts/compact_panel.py time                # SymPy's simplify timed on the bench's scenes

`sympy` runs qdot (the binary given: the one *before* compact forms was
used for the committed fixture) on every panel scene, and SymPy's
simplify() on each acceleration it prints, capped at 60 s per expression
(a time-out keeps the input's count). The fixture keeps the inputs, SymPy's
results, their count_ops and the time simplify took.

`table` runs the given (current) qdot, parses every acceleration it prints
with SymPy, checks it equals the fixture's input exactly (simplify of the
difference is 0), counts its operations and prints the markdown table.
tests/compact.rs checks the same totals without Python (its own count of
operations agrees with count_ops on the committed strings)."""
import json
import multiprocessing as mp
import os
import re
import subprocess
import sys
import time

import sympy as sp

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIXTURE = os.path.join(ROOT, "tests", "fixtures", "compact_panel.json")
CAP = 60.0

PANEL = [
    "tests/data/compact/double_pendulum.qd",
    "tests/data/compact/triple_pendulum.qd",
    "tests/data/compact/sliding_support.qd",
    "examples/heavy_top.qd",
    "tests/data/compact/cart_double_pendulum.qd",
    "tests/data/compact/elastic_pendulum.qd",
    "tests/data/compact/spherical_pendulum.qd",
    "tests/data/compact/rotating_hoop.qd",
    "examples/disk_in_cylinder.qd",
    "examples/spherical_pendulum.qd",
    "examples/rod_on_shaft.qd",
    "examples/seed_22_2_lagrange.qd",
    "examples/seed_21_2.qd",
    "examples/seed_22_3.qd",
    "examples/seed_23_2.qd",
    "examples/seed_23_3.qd",
    "examples/seed_23_4.qd",
    "examples/seed_24_1.qd",
    "examples/seed_24_2.qd",
]


def accelerations(qdot, path):
    out = subprocess.run([qdot, "solve", os.path.join(ROOT, path), "--format", "json"],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out).get("accelerations") or {}


def to_sympy(text):
    """qdot's input syntax to a SymPy expression (q'' -> q_dd, q' -> q_d)."""
    s = re.sub(r"([A-Za-z_][A-Za-z_0-9]*)''", r"\1_dd", text)
    s = re.sub(r"([A-Za-z_][A-Za-z_0-9]*)'", r"\1_d", s)
    s = s.replace("^", "**")
    names = set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", s)) - {"sin", "cos", "sqrt", "pi", "exp", "log", "atan", "asin", "acos"}
    syms = {n: sp.Symbol(n, real=True) for n in names}
    return sp.sympify(s, locals=syms)


def _simplify(text, queue):
    e = to_sympy(text)
    t0 = time.perf_counter()
    r = sp.simplify(e)
    queue.put((str(r), int(sp.count_ops(r)), time.perf_counter() - t0))


def simplify_capped(text):
    q = mp.Queue()
    p = mp.Process(target=_simplify, args=(text, q))
    p.start()
    p.join(CAP)
    if p.is_alive():
        p.kill()
        p.join()
        return None
    return q.get()


def cmd_sympy(qdot):
    rows = []
    for path in PANEL:
        for coord, text in accelerations(qdot, path).items():
            ops_in = int(sp.count_ops(to_sympy(text)))
            res = simplify_capped(text)
            if res is None:
                row = dict(scene=path, coordinate=coord, input=text, input_ops=ops_in,
                           sympy=text, sympy_ops=ops_in, sympy_seconds=None)
            else:
                row = dict(scene=path, coordinate=coord, input=text, input_ops=ops_in,
                           sympy=res[0], sympy_ops=res[1], sympy_seconds=round(res[2], 3))
            print(f"{path} {coord}: {ops_in} -> {row['sympy_ops']} ({row['sympy_seconds']} s)",
                  file=sys.stderr)
            rows.append(row)
    with open(FIXTURE, "w") as f:
        json.dump({"generator": "scripts/compact_panel.py", "sympy_version": sp.__version__,
                   "cap_seconds": CAP, "rows": rows}, f, indent=1)
        f.write("\n")


def cmd_table(qdot):
    rows = json.load(open(FIXTURE))["rows"]
    by_scene = {}
    for r in rows:
        by_scene.setdefault(r["scene"], []).append(r)
    print("| scene | qdot before | SymPy simplify | s (SymPy) | qdot now | qdot s |")
    print("|---|---:|---:|---:|---:|---:|")
    tot = [0, 0, 0.0, 0, 0.0]
    for scene, rs in by_scene.items():
        t0 = time.perf_counter()
        now = accelerations(qdot, scene)
        dt = time.perf_counter() - t0
        ops_now = 0
        for r in rs:
            e = to_sympy(now[r["coordinate"]])
            if sp.simplify(e - to_sympy(r["input"])) != 0:
                raise SystemExit(f"{scene} {r['coordinate']}: not equal to the fixture's input")
            ops_now += int(sp.count_ops(e))
        before = sum(r["input_ops"] for r in rs)
        sym = sum(r["sympy_ops"] for r in rs)
        secs = sum((r["sympy_seconds"] or CAP) for r in rs)
        print(f"| {scene} | {before} | {sym} | {secs:.1f} | {ops_now} | {dt:.3f} |")
        tot = [tot[0] + before, tot[1] + sym, tot[2] + secs, tot[3] + ops_now, tot[4] + dt]
    print(f"| **total** | {tot[0]} | {tot[1]} | {tot[2]:.1f} | {tot[3]} | {tot[4]:.3f} |")


def cmd_time():
    """SymPy's simplify on the fixture's inputs of the scenes that
    benches/derive.rs `compact/*` prints, timed here (the anchor)."""
    rows = json.load(open(FIXTURE))["rows"]
    for name in ["double_pendulum", "triple_pendulum", "cart_double_pendulum", "heavy_top"]:
        total = 0.0
        for r in rows:
            if r["scene"].endswith(f"/{name}.qd"):
                t0 = time.perf_counter()
                sp.simplify(to_sympy(r["input"]))
                total += time.perf_counter() - t0
        print(f"compact/{name}: SymPy simplify {total:.3f} s")


if __name__ == "__main__":
    if sys.argv[1] == "time":
        cmd_time()
    else:
        {"sympy": cmd_sympy, "table": cmd_table}[sys.argv[1]](sys.argv[2])
