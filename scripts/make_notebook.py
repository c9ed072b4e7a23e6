"""Writes examples/qdot_in_python.ipynb (without outputs): edit the cells here,
then `python scripts/make_notebook.py` from the repository root."""
import nbformat as nbf
nb = nbf.v4.new_notebook()
md, code = nbf.v4.new_markdown_cell, nbf.v4.new_code_cell
nb.cells = [
md("""# qdot in a notebook

qdot derives Lagrange's equations exactly, and fast. This notebook works
seed problem 23.4 and the double pendulum, checks qdot against SymPy's own
derivation, times both, and simulates the double pendulum.

Install: `pip install './python[test]'` from the repository's root (the
package with SymPy, matplotlib, Jupyter's kernel and Dask). CI runs this
notebook top to bottom (`python/tests/test_notebook.py`)."""),
code("""import os
import time
from pathlib import Path

import numpy as np
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols
import qdot


def examples_folder(name="seed_23_4.qd"):
    \"\"\"The repository's examples/ (this notebook's folder), wherever Jupyter
    was started: $QDOT_EXAMPLES, or the working directory or a folder above
    it, or its examples/.\"\"\"
    if os.environ.get("QDOT_EXAMPLES"):
        return Path(os.environ["QDOT_EXAMPLES"])
    for folder in [Path.cwd(), *Path.cwd().parents]:
        for candidate in (folder, folder / "examples"):
            if (candidate / name).is_file():
                return candidate
    raise FileNotFoundError(f"no {name} here, above here, or in an examples/ folder of either: "
                            "start Jupyter in the qdot repository, or set QDOT_EXAMPLES "
                            "to its examples folder")


EXAMPLES = examples_folder()
qdot.__version__"""),
md("""## Seed problem 23.4

Five bodies on a horizontal plane, two coordinates (y₃, θ₃), friction on
body 5. The scene is the file `seed_23_4.qd` beside this notebook, in `EXAMPLES`."""),
code("""scene = qdot.Scene.load(EXAMPLES / "seed_23_4.qd")
scene.equations()"""),
code("""scene.mass_matrix()"""),
code("""acc = scene.accelerations()
acc"""),
md("""`.to_sympy()` gives SymPy objects (the coordinates as `dynamicsymbols`
when asked; the parameters positive, as qdot takes them), so qdot can be
the derivation backend of a SymPy workflow."""),
code("""acc.to_sympy(dynamic=True)"""),
md("""### SymPy's own derivation

The same kinematic table and energies, written in SymPy, and Lagrange's
equations solved for the accelerations (the parameters positive, as in
qdot: the same SymPy symbols):"""),
code("""t = dynamicsymbols._t
y3, th3 = dynamicsymbols("y3 theta3")
G, g, r = sp.symbols("G g r", positive=True)

def sympy_seed_23_4():
    m, J = G / g, 4 * G * r**2 / g
    y1, y2, th4, x5 = y3 + 2 * r * th3, y3 - r * th3, y3 / (2 * r), y3 / 2
    d = lambda x: x.diff(t)
    T = (m * d(y1)**2 + m * d(y2)**2 + 3 * m * d(y3)**2 + J * d(th3)**2
         + J * d(th4)**2 + 2 * m * d(x5)**2) / 2
    U = G * y1 + G * y2 + 3 * G * y3
    work = -sp.Rational(1, 8) * 2 * G * x5
    eqs = [sp.diff(sp.diff(T, d(q)), t) - sp.diff(T, q) - sp.diff(U + work, q) for q in (y3, th3)]
    sol = sp.solve(eqs, [y3.diff(t, 2), th3.diff(t, 2)], dict=True)[0]
    return [sp.simplify(sol[q.diff(t, 2)]) for q in (y3, th3)]

start = time.perf_counter(); want = sympy_seed_23_4(); sympy_s = time.perf_counter() - start
start = time.perf_counter(); ours = qdot.Scene.load(EXAMPLES / "seed_23_4.qd").accelerations().to_sympy(dynamic=True)
qdot_s = time.perf_counter() - start
assert all(sp.simplify(ours[q] - w) == 0 for q, w in zip(["y3", "theta3"], want))
print(f"equal; SymPy {sympy_s * 1e3:.0f} ms, qdot {qdot_s * 1e3:.1f} ms (with the conversion to SymPy)")"""),
md("""## The double pendulum

Two point masses on massless rods, angles from the downward vertical. qdot
prints the accelerations in the textbook's compact form."""),
code("""dp = qdot.Scene.load(EXAMPLES / "double_pendulum.qd")
dp.accelerations()"""),
md("""SymPy's `LagrangesMethod` derives the same equations; its accelerations
need `simplify` to reach a readable form. Both are timed here:"""),
code("""from sympy.physics.mechanics import LagrangesMethod, Particle, Point, ReferenceFrame

def sympy_double_pendulum():
    th1, th2 = dynamicsymbols("th1 th2")
    m1, m2, l1, l2, g = sp.symbols("m1 m2 l1 l2 g", positive=True)
    N = ReferenceFrame("N")
    O = Point("O"); O.set_vel(N, 0)
    P1 = O.locatenew("P1", l1 * sp.sin(th1) * N.x - l1 * sp.cos(th1) * N.y)
    P2 = P1.locatenew("P2", l2 * sp.sin(th2) * N.x - l2 * sp.cos(th2) * N.y)
    P1.set_vel(N, P1.pos_from(O).dt(N)); P2.set_vel(N, P2.pos_from(O).dt(N))
    a, b = Particle("a", P1, m1), Particle("b", P2, m2)
    a.potential_energy = m1 * g * P1.pos_from(O).dot(N.y)
    b.potential_energy = m2 * g * P2.pos_from(O).dot(N.y)
    L = sp.physics.mechanics.Lagrangian(N, a, b)
    lm = LagrangesMethod(L, [th1, th2])
    lm.form_lagranges_equations()
    return [sp.simplify(x) for x in lm.rhs()[2:]]

start = time.perf_counter(); sympy_acc = sympy_double_pendulum(); sympy_s = time.perf_counter() - start
start = time.perf_counter(); qdot_acc = qdot.Scene.load(EXAMPLES / "double_pendulum.qd").accelerations(); qdot_s = time.perf_counter() - start
ours = qdot_acc.to_sympy(dynamic=True)
assert all(sp.simplify(ours[q] - w) == 0 for q, w in zip(["th1", "th2"], sympy_acc))
print(f"equal; SymPy {sympy_s:.2f} s, qdot {qdot_s * 1e3:.1f} ms: {sympy_s / qdot_s:.0f}x")"""),
md("""### A simulation

The exact equations compiled to floating point and integrated (DOP853);
`sim.t`, `sim.q`, `sim.qdot` and `sim.energy` are NumPy arrays."""),
code("""sim = dp.simulate(set={"m1": 1, "m2": 1, "l1": 1, "l2": 1, "g": 9.81},
                  init={"th1": 2.0, "th2": 2.5, "th1'": 0, "th2'": 0},
                  t_end=10, points=1001, rtol=1e-10, atol=1e-12)
sim"""),
code("""%matplotlib inline
import matplotlib.pyplot as plt
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.5))
sim.plot(ax1)
ax1.set_ylabel("angle (rad)")
ax2.semilogy(sim.t[1:], np.abs(sim.energy[1:] - sim.energy[0]) + 1e-18)
ax2.set_xlabel("t"); ax2.set_ylabel("|h(t) − h(0)|")
fig.tight_layout()
print(f"energy drift {np.max(np.abs(sim.energy - sim.energy[0])):.1e} after {sim.stats['steps']} steps")"""),
md("""### Small oscillations

About the lower equilibrium, the natural frequencies in closed form:"""),
code("""dp.modes()"""),
]
nb.metadata["kernelspec"] = {"display_name": "Python 3", "language": "python", "name": "python3"}
nb.metadata["language_info"] = {"name": "python"}
nbf.write(nb, "examples/qdot_in_python.ipynb")  # run from the repository root
