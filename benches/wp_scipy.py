# set-up: python3 -m pip install numpy scipy
# run:    python3 benches/wp_scipy.py IN.json OUT.json
#
# SciPy's side of qdot's work-precision report. The Rust bench
# (benches/work_precision.rs) writes IN.json (the problems, tolerances and
# methods) and runs this script as a subprocess; it times
# scipy.integrate.solve_ivp on the same six problems and writes OUT.json.
#
# IN.json:
#   {"tolerances": [1e-3, ..., 1e-13], "methods": ["DOP853", "RK45"],
#    "time_budget": 2.0,
#    "problems": [{"name", "params": {...}, "y0", "t_end", "reference",
#                  "energy_reference": null | H0,
#                  "baumgarte_alpha": null | α (a problem with constraints),
#                  "check": {"t", "y", "dy"}}, ...]}
# OUT.json:
#   {"python", "numpy", "scipy",
#    "results": [{"problem", "method", "tol", "seconds", "error",
#                 "energy_error", "constraint_drift", "nfev", "steps",
#                 "success", "skipped"}]}
# one record per problem × method × tolerance, in the input's problem and
# method order and from the loosest tolerance to the tightest. "seconds" is
# the minimum over 1 to 7 runs (until time_budget is spent); "error" is
# max_i |y_i(t_end) − reference_i| (null when the run stopped early);
# "energy_error" max |H(y) − H0| over the returned steps (null without an
# energy_reference); "constraint_drift" max |g(y)| over the returned steps
# (null for a problem without constraints); "skipped" null or the reason (a
# run over 60 s, or a
# looser tolerance's run over 60 s). Non-finite numbers are written as null.
#
# The right-hand sides are written by hand in numpy, as a SciPy user would;
# each is checked against qdot's own F(t, y) ("check", relative 1e-10) and
# each energy against qdot's H(y0) ("energy_reference", relative 1e-12)
# before anything is timed, so both sides integrate the same equations.
# Nothing in tests/ runs this script: CI does not need Python.

import json
import math
import platform
import signal
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

# A single run longer than this is abandoned, and the method's tighter
# tolerances on that problem are skipped.
RUN_LIMIT = 60.0
# At most this many timed runs per point (the minimum is reported).
MAX_REPEATS = 7
CHECK_RTOL = 1e-10
ENERGY_RTOL = 1e-12


def die(msg):
    print(f"wp_scipy: {msg}", file=sys.stderr)
    sys.exit(1)


# ---------------------------------------------------------------------------
# The six problems: right-hand side F(t, y) with y = (q, q̇), and the
# conserved energy H(y) over a (2n, T) array of states (None when the
# problem conserves none); a problem with constraints also returns its
# constraint g(y) over such an array.


def oscillator(p):
    """m ẍ + c ẋ + k x = F0 cos(p t)."""
    m, k, c, f0, om = p["m"], p["k"], p["c"], p["F0"], p["p"]

    def f(t, y):
        x, v = y
        return np.array([v, (f0 * np.cos(om * t) - c * v - k * x) / m])

    return f, None


def two_mode(p):
    """Seed 24.2: M = diag(4m, 3m/2), K = [[2k, −k], [−k, k]], M q̈ = −K q."""
    m, k = p["m"], p["k"]
    minv_k = np.array([[2 * k, -k], [-k, k]]) / np.array([[4 * m], [1.5 * m]])

    def f(t, y):
        return np.concatenate((y[2:], -minv_k @ y[:2]))

    def energy(y):
        x1, x2, v1, v2 = y
        return (
            2 * m * v1**2
            + 0.75 * m * v2**2
            + 0.5 * k * x1**2
            + 0.5 * k * (x2 - x1) ** 2
        )

    return f, energy


def pendulum(p):
    """θ̈ = −(g/l) sin θ."""
    m, l, g = p["m"], p["l"], p["g"]
    w2 = g / l

    def f(t, y):
        return np.array([y[1], -w2 * np.sin(y[0])])

    def energy(y):
        th, om = y
        return 0.5 * m * l**2 * om**2 - m * g * l * np.cos(th)

    return f, energy


def cartesian_pendulum(p):
    """The pendulum in x, y (y up) with the rod x² + y² = l² as a constraint,
    index-reduced with Baumgarte's stabilization g̈ + 2α ġ + α² g = 0 as
    qdot integrates it: q̈ = (0, −g) + μ (x, y) with
    2 (x ẍ + y ÿ) = −2 v² − 4α (x ẋ + y ẏ) − α² (x² + y² − l²)."""
    m, l, g, alpha = p["m"], p["l"], p["g"], p["alpha"]

    def f(t, y):
        x, yy, vx, vy = y
        r2 = x * x + yy * yy
        rhs = (
            -2.0 * (vx * vx + vy * vy)
            - 4.0 * alpha * (x * vx + yy * vy)
            - alpha * alpha * (r2 - l * l)
        )
        mu = (rhs + 2.0 * g * yy) / (2.0 * r2)
        return np.array([vx, vy, mu * x, mu * yy - g])

    def energy(y):
        x, yy, vx, vy = y
        return 0.5 * m * (vx**2 + vy**2) + m * g * yy

    def constraint(y):
        return y[0] ** 2 + y[1] ** 2 - l * l

    return f, energy, constraint


def chain(n):
    """The n-link chain (qdot's gallery::pendulum_chain): equal masses m on
    rods l, angles θi from the downward vertical. With 0-based i, j and
    W_ij = m l² (n − max(i, j)): M = W ∘ cos(θi − θj),
    f_i = −Σ_j W_ij sin(θi − θj) θ̇j² − m g l (n − i) sin θi, M θ̈ = f."""

    def build(p):
        m, l, g = p["m"], p["l"], p["g"]
        idx = np.arange(n)
        w = m * l**2 * (n - np.maximum.outer(idx, idx))
        grav = m * g * l * (n - idx)

        def f(t, y):
            th, om = y[:n], y[n:]
            d = th[:, None] - th[None, :]
            rhs = -(w * np.sin(d)) @ (om * om) - grav * np.sin(th)
            return np.concatenate((om, np.linalg.solve(w * np.cos(d), rhs)))

        def energy(y):
            th, om = y[:n], y[n:]
            d = th[:, None, :] - th[None, :, :]
            kin = 0.5 * np.einsum("ij,ijt,it,jt->t", w, np.cos(d), om, om)
            return kin - grav @ np.cos(th)

        return f, energy

    return build


PROBLEMS = {
    "oscillator": oscillator,
    "two_mode": two_mode,
    "pendulum": pendulum,
    "cartesian_pendulum": cartesian_pendulum,
    "double_pendulum": chain(2),
    "chain10": chain(10),
}


def energy_of(energy, y, chunk=4096):
    """H at every column of y (2n × T), in chunks to bound memory."""
    return np.concatenate(
        [energy(y[:, s : s + chunk]) for s in range(0, y.shape[1], chunk)]
    )


# ---------------------------------------------------------------------------
# Checks against qdot's equations.


def check_problem(prob, f, energy):
    name = prob["name"]
    chk = prob.get("check")
    if chk is None:
        die(f"{name}: no \"check\" entry in the input")
    y = np.asarray(chk["y"], dtype=float)
    want = np.asarray(chk["dy"], dtype=float)
    shapes = {np.shape(v) for v in (y, want, prob["y0"], prob["reference"])}
    if len(shapes) != 1:
        die(f"{name}: check y, check dy, y0 and reference differ in length")
    got = np.asarray(f(float(chk["t"]), y), dtype=float)
    scale = max(np.max(np.abs(want)), np.finfo(float).tiny)
    rel = np.max(np.abs(got - want)) / scale
    if not rel <= CHECK_RTOL:
        die(
            f"{name}: the numpy right-hand side differs from qdot's "
            f"(relative error {rel:.3e} > {CHECK_RTOL:g} at t = {chk['t']}):\n"
            f"  numpy: {got.tolist()}\n  qdot:  {want.tolist()}"
        )
    h0 = prob.get("energy_reference")
    if h0 is None:
        return None
    if energy is None:
        die(f"{name}: an energy_reference is given but no energy is written here")
    h = float(energy_of(energy, np.asarray(prob["y0"], dtype=float)[:, None])[0])
    if not abs(h - h0) <= ENERGY_RTOL * max(abs(h0), np.finfo(float).tiny):
        die(
            f"{name}: the numpy energy H(y0) = {h!r} differs from qdot's "
            f"{h0!r} (relative {abs(h - h0) / abs(h0):.3e} > {ENERGY_RTOL:g})"
        )
    return float(h0)


# ---------------------------------------------------------------------------
# Timing.


class Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise Timeout()


HAVE_ALARM = hasattr(signal, "setitimer")
if HAVE_ALARM:
    signal.signal(signal.SIGALRM, _alarm)


def run_once(f, prob, method, tol):
    """One solve_ivp call; (seconds, solution), or Timeout after RUN_LIMIT."""
    y0 = np.asarray(prob["y0"], dtype=float)
    if HAVE_ALARM:
        signal.setitimer(signal.ITIMER_REAL, RUN_LIMIT)
    try:
        t0 = time.perf_counter()
        sol = solve_ivp(
            f, (0.0, float(prob["t_end"])), y0, method=method, rtol=tol, atol=tol
        )
        secs = time.perf_counter() - t0
    finally:
        if HAVE_ALARM:
            signal.setitimer(signal.ITIMER_REAL, 0)
    if secs > RUN_LIMIT:
        raise Timeout()
    return secs, sol


def finite(x):
    return float(x) if x is not None and math.isfinite(x) else None


def blank_point(prob, method, tol, skipped=None):
    return {
        "problem": prob["name"],
        "method": method,
        "tol": tol,
        "seconds": None,
        "error": None,
        "energy_error": None,
        "constraint_drift": None,
        "nfev": None,
        "steps": None,
        "success": None,
        "skipped": skipped,
    }


def measure(prob, f, energy, h0, constraint, method, tol, budget):
    """Time one point: ({…record…}, whether the first run hit RUN_LIMIT)."""
    point = blank_point(prob, method, tol)
    try:
        best, sol = run_once(f, prob, method, tol)
    except Timeout:
        point["skipped"] = f"a single run exceeded {RUN_LIMIT:g} s"
        return point, True
    total, runs = best, 1
    while total < budget and runs < MAX_REPEATS:
        try:
            secs, _ = run_once(f, prob, method, tol)
        except Timeout:
            break
        best, total, runs = min(best, secs), total + secs, runs + 1
    ref = np.asarray(prob["reference"], dtype=float)
    reached = sol.success and sol.t[-1] == float(prob["t_end"])
    point["seconds"] = best
    point["error"] = finite(np.max(np.abs(sol.y[:, -1] - ref))) if reached else None
    if h0 is not None:
        point["energy_error"] = finite(np.max(np.abs(energy_of(energy, sol.y) - h0)))
    if constraint is not None:
        point["constraint_drift"] = finite(np.max(np.abs(constraint(sol.y))))
    point["nfev"] = int(sol.nfev)
    point["steps"] = len(sol.t) - 1
    point["success"] = bool(sol.success)
    if not sol.success:
        print(f"wp_scipy: solve_ivp failed: {sol.message}", file=sys.stderr)
    return point, False


def main(argv):
    if len(argv) != 3:
        die("usage: python3 benches/wp_scipy.py IN.json OUT.json")
    with open(argv[1]) as fh:
        spec = json.load(fh)
    tols = [float(t) for t in spec["tolerances"]]
    methods = list(spec["methods"])
    budget = float(spec.get("time_budget", 2.0))

    # Build and check every problem before timing anything.
    built = []
    for prob in spec["problems"]:
        name = prob["name"]
        if name not in PROBLEMS:
            die(f"unknown problem {name!r} (known: {', '.join(PROBLEMS)})")
        params = dict(prob["params"])
        alpha = prob.get("baumgarte_alpha")
        if alpha is not None:
            params["alpha"] = float(alpha)
        f, energy, *rest = PROBLEMS[name](params)
        constraint = rest[0] if rest else None
        if (constraint is None) != (alpha is None):
            die(f"{name}: baumgarte_alpha given without constraints here, or missing")
        h0 = check_problem(prob, f, energy)
        built.append((prob, f, energy, h0, constraint))
    print(f"wp_scipy: {len(built)} problems checked against qdot", file=sys.stderr)

    results = []
    start = time.perf_counter()
    for prob, f, energy, h0, constraint in built:
        for method in methods:
            too_slow = None  # the tolerance whose run exceeded RUN_LIMIT
            for tol in sorted(tols, reverse=True):
                if too_slow is not None:
                    why = f"tol {too_slow:g} already exceeded {RUN_LIMIT:g} s"
                    point = blank_point(prob, method, tol, why)
                else:
                    point, slow = measure(
                        prob, f, energy, h0, constraint, method, tol, budget
                    )
                    if slow:
                        too_slow = tol
                results.append(point)
                if point["skipped"]:
                    what = f"skipped: {point['skipped']}"
                else:
                    e = point["error"]
                    what = (
                        f"{point['seconds'] * 1e3:10.3f} ms  "
                        f"error {e if e is None else format(e, '.2e')}  "
                        f"nfev {point['nfev']}  steps {point['steps']}"
                    )
                    if point["energy_error"] is not None:
                        what += f"  dH {point['energy_error']:.2e}"
                    if point["constraint_drift"] is not None:
                        what += f"  |g| {point['constraint_drift']:.2e}"
                    if not point["success"]:
                        what += "  FAILED"
                print(
                    f"wp_scipy: {prob['name']:<16} {method:<7} tol {tol:.0e}  {what}",
                    file=sys.stderr,
                )
    print(
        f"wp_scipy: {len(results)} points in {time.perf_counter() - start:.1f} s",
        file=sys.stderr,
    )

    out = {
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "results": results,
    }
    with open(argv[2], "w") as fh:
        json.dump(out, fh, indent=1, allow_nan=False)
        fh.write("\n")


if __name__ == "__main__":
    main(sys.argv)
