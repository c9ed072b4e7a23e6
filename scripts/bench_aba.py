#!/usr/bin/env python3
"""Cost per call of q̈(q, q̇): qdot's generated C against Pinocchio's ABA in C++.

What it measures: for chains of n rigid rods, the time of one evaluation of
the right-hand side of the equations of motion, the accelerations q̈ from
(q, q̇) with no joint torque:
  qdot       `qdot codegen SCENE --lang c --set m=1,A=0.1,C=0.05,l=1,g=9.81`
             writes `<prefix>_rhs(double t, const double *y, double *dy)`,
             y = (q, q̇), dy = (q̇, q̈): the exact equations (q̈ = M⁻¹·f for
             small n, M·q̈ = f by an unrolled Cholesky beyond), the
             parameters compiled in as constants; built with `gcc -O2`.
  Pinocchio  `pinocchio::aba(model, data, q, v, tau)` (the articulated-body
             algorithm, Convention::LOCAL, its default) on the same chain as a
             pinocchio::Model, called with Eigen::VectorXd arguments, so
             the templates are instantiated in the driver and built with
             `g++ -O2 -std=c++17 -DNDEBUG` (NDEBUG switches off Eigen's
             asserts, as in any release build).  The last column times the
             same call through the instantiation compiled into the wheel's
             libpinocchio_default (Eigen::Ref arguments and
             -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION, as that library's CMake
             target declares), i.e. with the wheel's own compiler flags.
Each driver calls the function in a loop, nudging one entry of the state by
1e-12 before each call (so nothing can be hoisted out of the loop) and summing
one entry of q̈ (printed, so nothing is dead); the number of calls is
calibrated to about --rep-seconds per repetition, and the figure is the best
of 5 repetitions, in ns per call.  `ratio` is Pinocchio's time over qdot's
(above 1: qdot's function is faster).

The chains ("family"):
  3d      the chain of scripts/anchor_frames.py (its `scene_text` is the
          scene): joint k about the previous rod's x axis for odd k, y for
          even k; every rod has mass m, central inertia diag[A, A, C] and
          length l, its centre l/2 along its own -z axis; gravity [0, 0, -g].
  planar  the same geometry with every joint about y (the same scene text
          with `rot(x, ` turned into `rot(y, `): a planar n-pendulum.
In Pinocchio: joint k is JointModelRX (odd k, 3d) or JointModelRY, placed at
the identity (k = 1) or at translation [0, 0, -l] in the previous joint's
frame, carrying Inertia(m, [0, 0, -l/2], diag[A, A, C]); gravity [0, 0, -g]
(the model of scripts/pinocchio_chain.py).
Before timing, both drivers print q̈ at one state (q_k = 0.4 sin(1.3k + 0.2),
q̇_k = 0.7 cos(0.8k + 0.1), k = 0..n-1) and the script checks that they agree
to 1e-9 (max |a - b| / max(1, max |b|)) for every family and n; it exits 1
if any differs.

Set-up: Pinocchio's C++ headers and libraries come from PyPI wheels, e.g.
    python3 -m venv /tmp/pinvenv
    /tmp/pinvenv/bin/pip install pin cmeel-eigen
(`pin` brings libpinocchio, cmeel-boost and the other cmeel-* wheels; Eigen's
headers are in cmeel-eigen).  The headers are under
site-packages/cmeel.prefix/include (and include/eigen3), the libraries
under cmeel.prefix/lib.  Pass that prefix with --pin-prefix; without it the
script looks in the running interpreter's site-packages, then in
/tmp/*/lib/python3*/site-packages.  gcc and g++ must be on PATH; the script's
own Python needs SymPy (scripts/anchor_frames.py imports it).

Usage:
    python3 scripts/bench_aba.py [--qdot PATH] [--n 2,5,10,20,30]
        [--pin-prefix DIR] [--rep-seconds 0.2] [--keep DIR]
Everything is built in a temporary directory (--keep DIR builds there
instead and leaves the files).  Output: the q̈ check, a Markdown table, the
build costs (qdot codegen and gcc -O2 times of each generated file), and one
JSON line per (family, n).

Figures measured on this project's 2-core machine (2026-11-27, qdot 0.1.0
release build, pin 4.1.0 wheels, gcc 12.2, one run; for orientation only:
always compare within one run; ratio = Pinocchio aba / qdot, "aba via lib"
the call through libpinocchio_default, sizes those of the generated C):
    | family | n  | qdot C rhs | Pinocchio aba | ratio | aba via lib | gcc -O2 of qdot's C |
    | 3d     |  2 |    19.4 ns |        424 ns | 21.84 |      369 ns |  0.0 s (2.5 kB)     |
    | 3d     |  5 |     227 ns |       1203 ns |  5.31 |     1024 ns |  0.2 s (33 kB)      |
    | 3d     | 10 |    1441 ns |       2449 ns |  1.70 |     2125 ns |  1.6 s (157 kB)     |
    | 3d     | 20 |    3262 ns |       5166 ns |  1.58 |     4320 ns |  5.6 s (346 kB)     |
    | 3d     | 30 |    4983 ns |       7651 ns |  1.54 |     6557 ns | 12.9 s (541 kB)     |
    | planar |  2 |    19.8 ns |        411 ns | 20.80 |      361 ns |  0.0 s (2.8 kB)     |
    | planar |  5 |     140 ns |       1154 ns |  8.26 |      991 ns |  0.1 s (22 kB)      |
    | planar | 10 |     339 ns |       2445 ns |  7.21 |     2062 ns |  0.2 s (53 kB)      |
    | planar | 20 |    1045 ns |       4990 ns |  4.78 |     4133 ns |  0.6 s (118 kB)     |
    | planar | 30 |    1484 ns |       7528 ns |  5.07 |     6262 ns |  1.2 s (183 kB)     |
From n = 4 (where the scene is read through intermediates) qdot's function
is the articulated-body recursion generated from the scene
(`Lagrange::articulated_accelerations`), linear in n like Pinocchio's ABA:
about 165 ns per link in space and 50 ns in the plane, against
Pinocchio's 250 ns.  Below, the closed form (exact accelerations or M, f
and an unrolled Cholesky) is cheaper still.  qdot codegen took at most 2.0 s
(3d, n = 30); gcc -O2 on the generated file is the long step (12.9 s for
3d, n = 30), and the Pinocchio driver with its templates instantiated takes
about 70 s to compile.  q̈ of the two agreed to 2e-16 (n = 2) ... 1e-13
(planar, n = 30).
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from anchor_frames import scene_text as chain3d_scene  # noqa: E402 (imports SymPy)

FAMILIES = ("3d", "planar")
PARAM_VALUES = {"m": 1.0, "A": 0.1, "C": 0.05, "l": 1.0, "g": 9.81}
PARAMS = ",".join("%s=%g" % kv for kv in PARAM_VALUES.items())  # m=1,A=0.1,...
CHECK_TOL = 1e-9

# The state of the q̈ check, the timing loop and its calibration: one text for
# both drivers.
DRIVER_COMMON = r"""
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void check_state(int n, double *y)
{
    for (int k = 0; k < n; k++) {
        y[k] = 0.4 * sin(1.3 * k + 0.2);
        y[n + k] = 0.7 * cos(0.8 * k + 0.1);
    }
}

/* calls of the function under test, each after nudging one state entry */
static double run(int n, long calls, double *sink);

static double seconds_of(int n, long calls, double *sink)
{
    double t0 = now_s();
    run(n, calls, sink);
    return now_s() - t0;
}

/* best of 5 repetitions of about rep_s seconds each, in ns per call */
static double best_ns(int n, double rep_s, double *sink)
{
    long calls = 64;
    double s = seconds_of(n, calls, sink);
    while (s < 0.02) {
        calls *= 2;
        s = seconds_of(n, calls, sink);
    }
    calls = (long)(calls * rep_s / s) + 1;
    double best = 1e300;
    for (int r = 0; r < 5; r++) {
        double t = seconds_of(n, calls, sink) / calls;
        if (t < best) best = t;
    }
    return best * 1e9;
}

static void print_qdd(int n, const double *qdd)
{
    printf("[");
    for (int k = 0; k < n; k++) printf(k ? ", %.17g" : "%.17g", qdd[k]);
    printf("]\n");
}
"""

# Driver of qdot's generated function; -DN=.. -DRHS=<prefix>_rhs.
QDOT_DRIVER = DRIVER_COMMON + r"""
int RHS(double t, const double *y, double *dy);

static double run(int n, long calls, double *sink)
{
    double y[2 * N], dy[2 * N], acc = 0.0;
    int bad = 0;
    check_state(n, y);
    for (long i = 0; i < calls; i++) {
        y[i % (2 * N)] += 1e-12;
        bad |= RHS(0.0, y, dy);
        acc += dy[N + i % N];
    }
    if (bad) { fprintf(stderr, "rhs returned %d\n", bad); exit(2); }
    *sink += acc;
    return acc;
}

int main(int argc, char **argv)
{
    double y[2 * N], dy[2 * N], sink = 0.0;
    if (argc > 1 && !strcmp(argv[1], "check")) {
        check_state(N, y);
        if (RHS(0.0, y, dy)) { fprintf(stderr, "rhs failed\n"); return 2; }
        print_qdd(N, dy + N);
        return 0;
    }
    double rep_s = argc > 2 ? atof(argv[2]) : 0.2;
    double ns = best_ns(N, rep_s, &sink);
    printf("%.3f %g\n", ns, sink);
    return 0;
}
"""

# Driver of pinocchio::aba; argv: check|time FAMILY N [REP_S].  With
# -DVIA_LIBRARY the call goes through libpinocchio_default's instantiation.
PINOCCHIO_DRIVER = r"""
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
""" + DRIVER_COMMON + r"""
namespace pin = pinocchio;

static pin::Model model;
static pin::Data *data;

static void build(bool planar, int n)
{
    const double @PARAMS@;
    Eigen::Matrix3d I = Eigen::Vector3d(A, A, C).asDiagonal();
    pin::Inertia body(m, Eigen::Vector3d(0, 0, -l / 2), I);
    pin::JointIndex parent = 0;
    for (int k = 1; k <= n; k++) {
        pin::SE3 placement = pin::SE3::Identity();
        if (k > 1) placement.translation() = Eigen::Vector3d(0, 0, -l);
        std::string name = "q" + std::to_string(k);
        if (k % 2 == 1 && !planar)
            parent = model.addJoint(parent, pin::JointModelRX(), placement, name);
        else
            parent = model.addJoint(parent, pin::JointModelRY(), placement, name);
        model.appendBodyToJoint(parent, body, pin::SE3::Identity());
    }
    model.gravity.linear(Eigen::Vector3d(0, 0, -g));
    data = new pin::Data(model);
}

static const Eigen::VectorXd &aba(const Eigen::VectorXd &q, const Eigen::VectorXd &v,
                                  const Eigen::VectorXd &tau)
{
#ifdef VIA_LIBRARY
    typedef Eigen::Ref<const Eigen::VectorXd> R;
    return pin::aba<double, 0, pin::JointCollectionDefaultTpl, R, R, R>(
        model, *data, R(q), R(v), R(tau), pin::Convention::LOCAL);
#else
    return pin::aba(model, *data, q, v, tau);
#endif
}

static double run(int n, long calls, double *sink)
{
    Eigen::VectorXd y(2 * n), q(n), v(n), tau = Eigen::VectorXd::Zero(n);
    double acc = 0.0;
    check_state(n, y.data());
    q = y.head(n);
    v = y.tail(n);
    for (long i = 0; i < calls; i++) {
        long j = i % (2 * n);
        if (j < n) q[j] += 1e-12; else v[j - n] += 1e-12;
        acc += aba(q, v, tau)[i % n];
    }
    *sink += acc;
    return acc;
}

int main(int argc, char **argv)
{
    if (argc < 4) { fprintf(stderr, "usage: check|time 3d|planar N [REP_S]\n"); return 2; }
    bool planar = !strcmp(argv[2], "planar");
    int n = atoi(argv[3]);
    build(planar, n);
    double sink = 0.0;
    if (!strcmp(argv[1], "check")) {
        Eigen::VectorXd y(2 * n), tau = Eigen::VectorXd::Zero(n);
        check_state(n, y.data());
        Eigen::VectorXd q = y.head(n), v = y.tail(n);
        print_qdd(n, aba(q, v, tau).data());
        return 0;
    }
    double rep_s = argc > 4 ? atof(argv[4]) : 0.2;
    double ns = best_ns(n, rep_s, &sink);
    printf("%.3f %g\n", ns, sink);
    return 0;
}
""".replace("@PARAMS@", ", ".join("%s = %r" % kv for kv in PARAM_VALUES.items()))


def scene_text(family, n):
    """The qdot scene of the n-rod chain of a family."""
    text = chain3d_scene(n)
    if family == "3d":
        return text
    head, rest = text.split("\n", 1)
    assert head.startswith("# 3D chain"), head
    return ("# planar chain of %d rods, every joint about y\n" % n
            + rest.replace("rot(x, ", "rot(y, "))


def run(cmd, cwd, what):
    """Run a command, returning (stdout, seconds); exit with its stderr if it fails."""
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit("%s failed (exit %d): %s\n%s" % (what, p.returncode, " ".join(cmd),
                                                  p.stderr[-4000:]))
    return p.stdout, dt


def find_pin_prefix(given):
    """The cmeel.prefix that holds Pinocchio's and Eigen's headers."""
    def ok(p):
        return (os.path.isdir(os.path.join(p, "include", "pinocchio"))
                and os.path.isdir(os.path.join(p, "include", "eigen3")))
    if given:
        if not ok(given):
            sys.exit("--pin-prefix %s: no include/pinocchio and include/eigen3 there" % given)
        return given
    dirs = [sysconfig.get_paths()[k] for k in ("purelib", "platlib")]
    dirs += sorted(glob.glob("/tmp/*/lib/python3*/site-packages"))
    for d in dirs:
        p = os.path.join(d, "cmeel.prefix")
        if ok(p):
            return p
    sys.exit("Pinocchio's C++ headers not found: `python3 -m venv /tmp/pinvenv && "
             "/tmp/pinvenv/bin/pip install pin cmeel-eigen`, then pass "
             "--pin-prefix /tmp/pinvenv/lib/python3.X/site-packages/cmeel.prefix")


def find_qdot(given):
    if given:
        return os.path.abspath(given)
    built = os.path.join(HERE, "..", "target", "release", "qdot")
    if os.path.exists(built):
        return os.path.abspath(built)
    found = shutil.which("qdot")
    if not found:
        sys.exit("qdot not found: build it (cargo build --release) or pass --qdot PATH")
    return found


def build_pinocchio(tmp, prefix):
    """The two Pinocchio drivers: templates instantiated here, and via the library."""
    src = os.path.join(tmp, "pin_aba.cpp")
    with open(src, "w") as f:
        f.write(PINOCCHIO_DRIVER)
    inc, lib = os.path.join(prefix, "include"), os.path.join(prefix, "lib")
    common = ["g++", "-O2", "-std=c++17", "-DNDEBUG", "-I" + inc,
              "-I" + os.path.join(inc, "eigen3"),
              # the compile definitions of pinocchio's CMake target pinocchio_headers
              "-DBOOST_MPL_LIMIT_LIST_SIZE=30", "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30",
              "-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS", "-DBOOST_FUSION_INVOKE_MAX_ARITY=12"]
    exes = {}
    for variant, extra, libs in (
            ("inline", [], []),
            ("library", ["-DVIA_LIBRARY", "-DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION"],
             ["-L" + lib, "-Wl,-rpath," + lib, "-lpinocchio_default"])):
        exe = os.path.join(tmp, "pin_aba_" + variant)
        _, dt = run(common + extra + [src, "-o", exe] + libs, tmp, "g++ (Pinocchio driver)")
        print("built Pinocchio driver (%s) in %.1f s" % (variant, dt), flush=True)
        exes[variant] = exe
    return exes


def build_qdot(tmp, qdot, family, n):
    """qdot's generated C for one chain, compiled with its driver."""
    name = "chain_%s_%d" % (family, n)
    scene = os.path.join(tmp, name + ".qd")
    with open(scene, "w") as f:
        f.write(scene_text(family, n))
    run([qdot, "solve", "--format", "json", scene], tmp, "qdot solve (parse check)")
    code, codegen_s = run([qdot, "codegen", scene, "--lang", "c", "--set", PARAMS], tmp,
                          "qdot codegen")
    csrc = os.path.join(tmp, name + ".c")
    with open(csrc, "w") as f:
        f.write(code)
    rhs = re.search(r"^int (\w+_rhs)\(double t, const double \*y, double \*dy\)$", code, re.M)
    if not rhs:
        sys.exit("no `int <prefix>_rhs(double t, const double *y, double *dy)` in %s" % csrc)
    _, gcc_s = run(["gcc", "-O2", "-c", csrc, "-o", name + ".o"], tmp, "gcc (generated C)")
    driver = os.path.join(tmp, name + "_main.c")
    with open(driver, "w") as f:
        f.write(QDOT_DRIVER)
    exe = os.path.join(tmp, name + "_bench")
    run(["gcc", "-O2", "-DN=%d" % n, "-DRHS=" + rhs.group(1), driver, name + ".o", "-o", exe,
         "-lm"], tmp, "gcc (qdot driver)")
    return exe, {"codegen_s": round(codegen_s, 3), "gcc_s": round(gcc_s, 2),
                 "c_bytes": len(code.encode())}


def rel_err(a, b):
    return max(abs(x - y) for x, y in zip(a, b)) / max(1.0, max(abs(y) for y in b))


def timed_ns(cmd, tmp):
    out, _ = run(cmd, tmp, "timing run")
    return float(out.split()[0])


def fmt(v):
    return "%.0f" % v if v >= 100 else "%.1f" % v


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--qdot", help="the qdot binary (default: target/release/qdot, then PATH)")
    ap.add_argument("--n", default="2,5,10,20,30", help="chain lengths, comma-separated")
    ap.add_argument("--pin-prefix", help="cmeel.prefix of the pin and cmeel-eigen wheels")
    ap.add_argument("--rep-seconds", type=float, default=0.2, help="length of one repetition")
    ap.add_argument("--keep", help="build in this directory and keep it")
    a = ap.parse_args()
    try:
        ns = [int(x) for x in a.n.split(",") if x.strip()]
    except ValueError:
        ap.error("--n takes integers separated by commas, e.g. 2,5,10")
    if not ns or min(ns) < 1:
        ap.error("--n needs chain lengths of at least 1")
    qdot, prefix = find_qdot(a.qdot), find_pin_prefix(a.pin_prefix)
    print("qdot: %s\nPinocchio prefix: %s" % (qdot, prefix), flush=True)
    if a.keep:
        os.makedirs(a.keep, exist_ok=True)
        work(qdot, prefix, ns, a.rep_seconds, os.path.abspath(a.keep))
    else:
        with tempfile.TemporaryDirectory(prefix="bench_aba_") as tmp:
            work(qdot, prefix, ns, a.rep_seconds, tmp)


def work(qdot, prefix, ns, rep_s, tmp):
    pin_exes = build_pinocchio(tmp, prefix)
    cases = []
    for family in FAMILIES:
        for n in ns:
            exe, build = build_qdot(tmp, qdot, family, n)
            print("built %s n=%d: codegen %.2f s, gcc -O2 %.1f s, %d bytes of C"
                  % (family, n, build["codegen_s"], build["gcc_s"], build["c_bytes"]),
                  flush=True)
            cases.append((family, n, exe, build))

    ok = True
    print("\nq̈ at q_k = 0.4 sin(1.3k + 0.2), q̇_k = 0.7 cos(0.8k + 0.1):")
    for family, n, exe, build in cases:
        qd = json.loads(run([exe, "check"], tmp, "qdot check")[0])
        errs = {}
        for variant, pexe in pin_exes.items():
            pn = json.loads(run([pexe, "check", family, str(n)], tmp, "Pinocchio check")[0])
            errs[variant] = rel_err(qd, pn)
        if n == ns[0]:
            print("  %s n=%d qdot      %s\n  %s n=%d Pinocchio %s" % (family, n, qd, family, n, pn))
        worst = max(errs.values())
        print("  %s n=%d: max rel difference %.2e %s"
              % (family, n, worst, "ok" if worst <= CHECK_TOL else "FAIL"), flush=True)
        ok &= worst <= CHECK_TOL
        build["qdd_rel_err"] = float("%.3g" % worst)
    if not ok:
        sys.exit("q̈ of qdot and Pinocchio differ by more than %g" % CHECK_TOL)

    print("\ntiming (best of 5, about %g s each) ..." % rep_s, flush=True)
    rows = []
    for family, n, exe, build in cases:
        q_ns = timed_ns([exe, "time", str(rep_s)], tmp)
        p_ns = timed_ns([pin_exes["inline"], "time", family, str(n), str(rep_s)], tmp)
        l_ns = timed_ns([pin_exes["library"], "time", family, str(n), str(rep_s)], tmp)
        rows.append(dict(family=family, n=n, qdot_ns=round(q_ns, 1), pinocchio_ns=round(p_ns, 1),
                         ratio=round(p_ns / q_ns, 2), pinocchio_lib_ns=round(l_ns, 1), **build))

    print("\n| family | n | qdot C rhs (ns) | Pinocchio aba C++ (ns) | ratio "
          "| Pinocchio aba via libpinocchio_default (ns) |")
    print("|---|---:|---:|---:|---:|---:|")
    for r in rows:
        print("| %s | %d | %s | %s | %.2f | %s |" % (r["family"], r["n"], fmt(r["qdot_ns"]),
                                                     fmt(r["pinocchio_ns"]), r["ratio"],
                                                     fmt(r["pinocchio_lib_ns"])))
    print("\nbuild of qdot's function: | family | n | codegen (s) | gcc -O2 (s) | C (bytes) |")
    for r in rows:
        print("| %s | %d | %.2f | %.1f | %d |" % (r["family"], r["n"], r["codegen_s"],
                                                 r["gcc_s"], r["c_bytes"]))
    print()
    for r in rows:
        print(json.dumps(r))


if __name__ == "__main__":
    main()
