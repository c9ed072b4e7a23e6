#!/usr/bin/env python3
"""Independent NumPy reference for `qdot cycle` (issue 36): planar mechanisms
analysed over a cycle by the kinetostatic method.

Writes tests/fixtures/mechanisms/<case>.json, one per case:
    {"scene", "over", "set", "guess", "columns", "rows", "source", ...}
Each row is one position of the cycle: the varied value, every coordinate,
every velocity, every acceleration, every joint's reaction and every drive's
force, in the column order `qdot cycle` prints (tests/fixtures/mechanisms/
README.md states the conventions).

Nothing here reads a .qd file.  Every mechanism is written a second time
below, by hand, as rigid bodies (centre, angle) and particles with their joint
points given as body-fixed vectors, and then:
  1. positions: Newton on the loop-closure (joint) equations and the drives,
     from the fixture's guess at the first position, then continued position
     by position from the previous one (the same assembly branch);
  2. velocities and accelerations: the linear equations J q' = -Phi_t and
     J q'' = gamma, each joint's rows and gamma derived by hand (below);
  3. forces: the Newton-Euler equations of every body, m a_G = sum F and
     J_G alpha = sum M_G (a particle: the first two), assembled from the
     free-body diagrams into one square linear system for the joint forces
     and the drives, solved with numpy.linalg.solve;
  4. Coulomb friction (seed 21.74-21.75): fixed-point iteration, first
     without friction, then with the friction forces recomputed from the
     current reactions, until the change is below 1e-14 relative.
Checks run on every row before anything is written (the script stops with an
error otherwise): the constraint residuals, the velocities and accelerations
against finite differences of the positions solved at nearby times, and the
power balance  sum(drive * q') = d(T + V)/dt - P_loads + P_friction  (the
friction's dissipated power, >= 0), to 1e-10 relative.

Usage:  python3 scripts/mechanism_reference.py [OUTDIR]
        (NumPy only; OUTDIR defaults to tests/fixtures/mechanisms)
        python3 scripts/mechanism_reference.py --time CASE N [REPEATS]
        (prints the seconds one cycle of CASE over N positions takes, the
        best of REPEATS runs, 5 by default; for benches/cycle.rs)
"""

import json
import math
import os
import sys

import numpy as np

# ----------------------------------------------------------------------------
# Planar geometry
# ----------------------------------------------------------------------------


def rot(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def perp(v):
    """v turned +90 degrees: (x, y) -> (-y, x)."""
    return np.array([-v[1], v[0]])


def cross(a, b):
    """The scalar a_x b_y - a_y b_x (the moment of b at arm a)."""
    return a[0] * b[1] - a[1] * b[0]


# ----------------------------------------------------------------------------
# A mechanism: bodies, joints, drives, applied forces
# ----------------------------------------------------------------------------


class Body:
    """A rigid body (x, y, angle) or a particle (x, y); `ix` are the indices
    of its coordinates in the coordinate vector."""

    def __init__(self, name, mass, inertia, ix):
        self.name = name
        self.mass = mass
        self.inertia = inertia  # None for a particle
        self.ix = ix  # (x, y, angle) or (x, y)

    @property
    def rigid(self):
        return self.inertia is not None


class Mechanism:
    """Bodies and particles with their joints, drives and applied forces, in
    absolute coordinates (each body its own x, y, angle)."""

    def __init__(self, coordinates, params):
        self.coordinates = coordinates
        self.p = params
        self.bodies = {}
        self.joints = []  # dicts, in the order of the scene's joint statements
        self.drives = []  # dicts, in the order of the scene's drive statements
        self.gravity = np.zeros(2)
        self.loads = []  # (body, local point, force function(t, q, v))
        self.torques = []  # (body, couple function)
        self.springs = []  # (coordinate index, potential V(q), dV/dq)

    def idx(self, name):
        return self.coordinates.index(name)

    # --- declarations ---------------------------------------------------
    def body(self, name, mass, inertia, x, y, angle):
        self.bodies[name] = Body(name, mass, inertia, (self.idx(x), self.idx(y), self.idx(angle)))

    def particle(self, name, mass, x, y):
        self.bodies[name] = Body(name, mass, None, (self.idx(x), self.idx(y)))

    def pin(self, name, a, sa, b, sb, friction=None):
        """Joint NAME: pin A at P, B at Q.  sa, sb: the joint point in A's and
        B's body frame (from the centre, along the body's angle); for the
        ground, its fixed position.  friction: mu0*r0 or None."""
        self.joints.append(dict(kind="pin", name=name, a=a, sa=np.array(sa, float),
                                b=b, sb=np.array(sb, float), friction=friction))

    def slider(self, name, a, sa, ua, b, sb, friction=None):
        """Joint NAME: slider A at P, B at Q along U.  ua: U in A's frame (the
        ground's: fixed).  friction: mu or None."""
        ja = self.bodies.get(a)
        jb = self.bodies.get(b)
        fixed = ja is not None and jb is not None and ja.rigid and jb.rigid
        self.joints.append(dict(kind="slider", name=name, a=a, sa=np.array(sa, float),
                                ua=np.array(ua, float), b=b, sb=np.array(sb, float),
                                fixed_angle=fixed, angle0=None, friction=friction))

    def drive(self, name, coordinate, f, df, ddf):
        self.drives.append(dict(name=name, k=self.idx(coordinate), f=f, df=df, ddf=ddf))

    # --- columns ----------------------------------------------------------
    def reaction_columns(self):
        cols = []
        for j in self.joints:
            if j["kind"] == "pin":
                cols += [j["name"] + "_x", j["name"] + "_y"]
            else:
                cols.append(j["name"] + "_n")
                if j["fixed_angle"]:
                    cols.append(j["name"] + "_m")
        return cols + [d["name"] for d in self.drives]

    def columns(self, varied):
        c = self.coordinates
        return [varied] + c + [n + "'" for n in c] + [n + "''" for n in c] + self.reaction_columns()

    # --- body kinematics --------------------------------------------------
    def angle(self, body, q):
        b = self.bodies.get(body)
        return q[b.ix[2]] if b is not None and b.rigid else 0.0

    def omega(self, body, v):
        b = self.bodies.get(body)
        return v[b.ix[2]] if b is not None and b.rigid else 0.0

    def arm(self, body, s, q):
        """The joint point relative to the body's centre, in ground components
        (R(theta) s; zero for a particle; for the ground, the point itself)."""
        b = self.bodies.get(body)
        if b is None:
            return s.copy()
        if b.rigid:
            return rot(q[b.ix[2]]) @ s
        return np.zeros(2)

    def point(self, body, s, q):
        b = self.bodies.get(body)
        if b is None:
            return s.copy()
        return np.array([q[b.ix[0]], q[b.ix[1]]]) + self.arm(body, s, q)

    def point_velocity(self, body, s, q, v):
        b = self.bodies.get(body)
        if b is None:
            return np.zeros(2)
        vel = np.array([v[b.ix[0]], v[b.ix[1]]])
        if b.rigid:
            vel = vel + v[b.ix[2]] * perp(self.arm(body, s, q))
        return vel

    def guide(self, j, q):
        """A slider's direction U in ground components."""
        return rot(self.angle(j["a"], q)) @ j["ua"] if j["a"] in self.bodies else j["ua"].copy()

    # --- constraints: Phi(q, t), its Jacobian, Phi_t and gamma -------------
    def n_constraints(self):
        n = 0
        for j in self.joints:
            n += 2 if j["kind"] == "pin" else (2 if j["fixed_angle"] else 1)
        return n + len(self.drives)

    def phi(self, q, t):
        rows = []
        for j in self.joints:
            if j["kind"] == "pin":
                rows += list(self.point(j["a"], j["sa"], q) - self.point(j["b"], j["sb"], q))
            else:
                u = self.guide(j, q)
                d = self.point(j["b"], j["sb"], q) - self.point(j["a"], j["sa"], q)
                rows.append(perp(u) @ d)
                if j["fixed_angle"]:
                    rows.append(self.angle(j["b"], q) - self.angle(j["a"], q) - j["angle0"])
        for dr in self.drives:
            rows.append(q[dr["k"]] - dr["f"](t))
        return np.array(rows)

    def _add_point_rows(self, jac, row, body, s, q, sign, weight):
        """Add sign * weight . d(point)/dq to jac[row]: weight a 2-vector."""
        b = self.bodies.get(body)
        if b is None:
            return
        jac[row, b.ix[0]] += sign * weight[0]
        jac[row, b.ix[1]] += sign * weight[1]
        if b.rigid:
            jac[row, b.ix[2]] += sign * (weight @ perp(self.arm(body, s, q)))

    def jacobian(self, q):
        n = len(self.coordinates)
        jac = np.zeros((self.n_constraints(), n))
        r = 0
        for j in self.joints:
            if j["kind"] == "pin":
                # d/dq (P_A - P_B), row by row (x, then y)
                for comp in range(2):
                    w = np.eye(2)[comp]
                    self._add_point_rows(jac, r + comp, j["a"], j["sa"], q, +1, w)
                    self._add_point_rows(jac, r + comp, j["b"], j["sb"], q, -1, w)
                r += 2
            else:
                u = self.guide(j, q)
                nvec = perp(u)
                d = self.point(j["b"], j["sb"], q) - self.point(j["a"], j["sa"], q)
                self._add_point_rows(jac, r, j["b"], j["sb"], q, +1, nvec)
                self._add_point_rows(jac, r, j["a"], j["sa"], q, -1, nvec)
                a = self.bodies.get(j["a"])
                if a is not None and a.rigid:
                    # n = perp(R_A ua) turns with A: dn/dtheta_A = perp(n) = -U
                    jac[r, a.ix[2]] += -u @ d
                r += 1
                if j["fixed_angle"]:
                    jac[r, self.bodies[j["b"]].ix[2]] += 1.0
                    jac[r, self.bodies[j["a"]].ix[2]] -= 1.0
                    r += 1
        for dr in self.drives:
            jac[r, dr["k"]] = 1.0
            r += 1
        return jac

    def phi_t(self, t):
        rows = np.zeros(self.n_constraints())
        for i, dr in enumerate(self.drives):
            rows[len(rows) - len(self.drives) + i] = -dr["df"](t)
        return rows

    def gamma(self, q, v, t):
        """The right-hand side of J q'' = gamma (d^2 Phi/dt^2 = J q'' - gamma).

        Pin: P = r + R s has P'' = r'' + alpha perp(R s) - omega^2 R s, so
          gamma = omega_A^2 R_A s_A - omega_B^2 R_B s_B.
        Slider, C = n . d with n = perp(U) turning with A (n' = -omega_A U,
        n'' = -omega_A^2 n - alpha_A U) and d = Q - P:
          C'' = n.d'' + 2 n'.d' + n''.d, whose terms without second
          derivatives are  n.(omega_A^2 R_A s_A - omega_B^2 R_B s_B)
          - 2 omega_A U.d' - omega_A^2 n.d, so
          gamma = n.(omega_B^2 R_B s_B - omega_A^2 R_A s_A)
                  + 2 omega_A U.d' + omega_A^2 n.d.
        Fixed relative angle: gamma = 0.  Drive q_k = f(t): gamma = f''(t).
        """
        rows = []
        for j in self.joints:
            wa, wb = self.omega(j["a"], v), self.omega(j["b"], v)
            ra, rb = self.arm(j["a"], j["sa"], q), self.arm(j["b"], j["sb"], q)
            if j["a"] not in self.bodies:
                ra = np.zeros(2)
            if j["b"] not in self.bodies:
                rb = np.zeros(2)
            if j["kind"] == "pin":
                rows += list(wa ** 2 * ra - wb ** 2 * rb)
            else:
                u = self.guide(j, q)
                nvec = perp(u)
                d = self.point(j["b"], j["sb"], q) - self.point(j["a"], j["sa"], q)
                dd = (self.point_velocity(j["b"], j["sb"], q, v)
                      - self.point_velocity(j["a"], j["sa"], q, v))
                rows.append(nvec @ (wb ** 2 * rb - wa ** 2 * ra) + 2 * wa * (u @ dd)
                            + wa ** 2 * (nvec @ d))
                if j["fixed_angle"]:
                    rows.append(0.0)
        for dr in self.drives:
            rows.append(dr["ddf"](t))
        return np.array(rows)

    # --- positions, velocities, accelerations -----------------------------
    def assemble(self, q0, t, tol=1e-15, max_iter=60):
        q = np.array(q0, float)
        for _ in range(max_iter):
            res = self.phi(q, t)
            dq = np.linalg.solve(self.jacobian(q), -res)
            q = q + dq
            if np.max(np.abs(dq)) <= tol * max(1.0, np.max(np.abs(q))):
                break
        else:
            raise RuntimeError("Newton did not converge at t = %r" % t)
        # one more step after convergence: the residual at rounding level
        q = q + np.linalg.solve(self.jacobian(q), -self.phi(q, t))
        if np.max(np.abs(self.phi(q, t))) > 1e-13:
            raise RuntimeError("constraints not satisfied at t = %r" % t)
        return q

    def kinematics(self, q, t):
        jac = self.jacobian(q)
        cond = np.linalg.cond(jac)
        if cond > 1e8:
            raise RuntimeError("near a dead point at t = %r (cond %.3g)" % (t, cond))
        v = np.linalg.solve(jac, -self.phi_t(t))
        a = np.linalg.solve(jac, self.gamma(q, v, t))
        return v, a

    # --- Newton-Euler: one linear system per position -----------------------
    def unknowns(self):
        """[(joint index or drive, component)] in column order."""
        out = []
        for i, j in enumerate(self.joints):
            if j["kind"] == "pin":
                out += [("pin", i, 0), ("pin", i, 1)]
            else:
                out.append(("slider_n", i, None))
                if j["fixed_angle"]:
                    out.append(("slider_m", i, None))
        for i, _ in enumerate(self.drives):
            out.append(("drive", i, None))
        return out

    def body_rows(self):
        rows = {}
        r = 0
        for name, b in self.bodies.items():
            rows[name] = r
            r += 3 if b.rigid else 2
        return rows, r

    def _apply(self, mat_or_vec, rows, body, force, arm, col=None, sign=1.0):
        """Add the force `force` (a 2-vector) applied at `arm` from the centre
        of `body` to that body's force and moment equations: into column
        `col` of the matrix (force per unit unknown), or into the vector."""
        if body not in self.bodies:
            return
        r = rows[body]
        b = self.bodies[body]
        entries = [(r, force[0]), (r + 1, force[1])]
        if b.rigid:
            entries.append((r + 2, cross(arm, force)))
        for row, val in entries:
            if col is None:
                mat_or_vec[row] += sign * val
            else:
                mat_or_vec[row, col] += sign * val

    def _apply_couple(self, mat_or_vec, rows, body, couple, col=None, sign=1.0):
        if body not in self.bodies or not self.bodies[body].rigid:
            return
        r = rows[body] + 2
        if col is None:
            mat_or_vec[r] += sign * couple
        else:
            mat_or_vec[r, col] += sign * couple

    def relative_slide(self, j, q, v):
        """v_rel = d/dt [U^.(Q - P)] = omega_A n^.(Q - P) + U^.(Q' - P')."""
        u = self.guide(j, q)
        uh = u / np.linalg.norm(u)
        d = self.point(j["b"], j["sb"], q) - self.point(j["a"], j["sa"], q)
        dd = (self.point_velocity(j["b"], j["sb"], q, v)
              - self.point_velocity(j["a"], j["sa"], q, v))
        return self.omega(j["a"], v) * (perp(uh) @ d) + uh @ dd

    def friction_loads(self, x, q, v):
        """The friction forces and couples for the reactions x (column order):
        [(body, force, arm), ...], [(body, couple), ...]."""
        forces, couples = [], []
        cols = self.unknowns()
        value = {}
        for c, val in zip(cols, x):
            value[c] = val
        for i, j in enumerate(self.joints):
            if j["friction"] is None:
                continue
            if j["kind"] == "pin":
                mag = math.hypot(value[("pin", i, 0)], value[("pin", i, 1)])
                wrel = self.omega(j["b"], v) - self.omega(j["a"], v)
                if abs(wrel) < 1e-9:
                    raise RuntimeError("pin %s: relative rotation vanishes" % j["name"])
                m = -j["friction"] * mag * math.copysign(1.0, wrel)
                couples += [(j["b"], m), (j["a"], -m)]
            else:
                vrel = self.relative_slide(j, q, v)
                if abs(vrel) < 1e-9:
                    raise RuntimeError("slider %s: relative sliding vanishes" % j["name"])
                u = self.guide(j, q)
                uh = u / np.linalg.norm(u)
                f = -j["friction"] * abs(value[("slider_n", i, None)]) * math.copysign(1.0, vrel) * uh
                qpt = self.point(j["b"], j["sb"], q)
                for body, sign in ((j["b"], 1.0), (j["a"], -1.0)):
                    if body in self.bodies:
                        centre = self.point(body, np.zeros(2), q)
                        forces.append((body, sign * f, qpt - centre))
        return forces, couples

    def newton_euler(self, q, v, a, t, friction=None):
        """Solve the bodies' Newton-Euler equations for the joint forces and
        the drives, with the given friction loads (known) added."""
        rows, n = self.body_rows()
        cols = self.unknowns()
        if len(cols) != n:
            raise RuntimeError("%d unknowns for %d equations" % (len(cols), n))
        mat = np.zeros((n, n))
        rhs = np.zeros(n)  # m a - known forces; J alpha - known moments
        for name, b in self.bodies.items():
            r = rows[name]
            rhs[r] += b.mass * a[b.ix[0]] - b.mass * self.gravity[0]
            rhs[r + 1] += b.mass * a[b.ix[1]] - b.mass * self.gravity[1]
            if b.rigid:
                rhs[r + 2] += b.inertia * a[b.ix[2]]
        # unknown joint forces: +F on B at its point, -F on A at the same point
        for col, (kind, i, comp) in enumerate(cols):
            if kind == "drive":
                dr = self.drives[i]
                body, what = self.coordinate_owner(dr["k"])
                if what == 2:
                    self._apply_couple(mat, rows, body, 1.0, col)
                else:
                    self._apply(mat, rows, body, np.eye(2)[what], np.zeros(2), col)
                continue
            j = self.joints[i]
            pt = self.point(j["b"], j["sb"], q)
            if kind == "pin":
                f = np.eye(2)[comp]
            elif kind == "slider_n":
                u = self.guide(j, q)
                f = perp(u) / np.linalg.norm(u)
            else:  # slider_m: a couple on B, the opposite on A
                self._apply_couple(mat, rows, j["b"], 1.0, col)
                self._apply_couple(mat, rows, j["a"], 1.0, col, sign=-1.0)
                continue
            for body, sign in ((j["b"], 1.0), (j["a"], -1.0)):
                if body in self.bodies:
                    centre = self.point(body, np.zeros(2), q)
                    self._apply(mat, rows, body, f, pt - centre, col, sign)
        # known applied forces: loads at points, couples, springs, friction
        for body, s, force in self.loads:
            centre = self.point(body, np.zeros(2), q)
            self._apply(rhs, rows, body, force(t, q, v), self.point(body, s, q) - centre, sign=-1.0)
        for body, couple in self.torques:
            self._apply_couple(rhs, rows, body, couple(t, q, v), sign=-1.0)
        for k, _, dv in self.springs:
            body, what = self.coordinate_owner(k)
            gen = -dv(q)
            if what == 2:
                self._apply_couple(rhs, rows, body, gen, sign=-1.0)
            else:
                self._apply(rhs, rows, body, gen * np.eye(2)[what], np.zeros(2), sign=-1.0)
        if friction is not None:
            forces, couples = friction
            for body, f, arm in forces:
                self._apply(rhs, rows, body, f, arm, sign=-1.0)
            for body, c in couples:
                self._apply_couple(rhs, rows, body, c, sign=-1.0)
        return np.linalg.solve(mat, rhs)

    def coordinate_owner(self, k):
        for name, b in self.bodies.items():
            if k in b.ix:
                return name, b.ix.index(k)
        raise KeyError(self.coordinates[k])

    def has_friction(self):
        return any(j["friction"] is not None for j in self.joints)

    def forces(self, q, v, a, t):
        x = self.newton_euler(q, v, a, t)
        if not self.has_friction():
            return x, 0
        for it in range(1, 200):
            x_new = self.newton_euler(q, v, a, t, self.friction_loads(x, q, v))
            change = np.max(np.abs(x_new - x))
            x = x_new
            if change <= 1e-14 * np.max(np.abs(x)):
                return x, it
        raise RuntimeError("friction iteration did not converge at t = %r" % t)

    # --- checks -------------------------------------------------------------
    def energy_rate(self, q, v, a):
        """d(T + V)/dt: kinetic energy, gravity and springs."""
        rate = 0.0
        for b in self.bodies.values():
            vel = np.array([v[b.ix[0]], v[b.ix[1]]])
            acc = np.array([a[b.ix[0]], a[b.ix[1]]])
            rate += b.mass * (vel @ acc) - b.mass * (self.gravity @ vel)
            if b.rigid:
                rate += b.inertia * v[b.ix[2]] * a[b.ix[2]]
        for k, _, dv in self.springs:
            rate += dv(q) * v[k]
        return rate

    def load_power(self, q, v, t):
        p = 0.0
        for body, s, force in self.loads:
            p += force(t, q, v) @ self.point_velocity(body, s, q, v)
        for body, couple in self.torques:
            p += couple(t, q, v) * self.omega(body, v)
        return p

    def friction_dissipation(self, x, q, v):
        """The power the friction forces take out: -(sum F.v_point + sum C.omega)."""
        if not self.has_friction():
            return 0.0
        forces, couples = self.friction_loads(x, q, v)
        p = 0.0
        for body, f, arm in forces:
            b = self.bodies[body]
            vel = np.array([v[b.ix[0]], v[b.ix[1]]])
            if b.rigid:
                vel = vel + v[b.ix[2]] * perp(arm)
            p -= f @ vel
        for body, c in couples:
            p -= c * self.omega(body, v)
        return p


# ----------------------------------------------------------------------------
# Sweeping a cycle
# ----------------------------------------------------------------------------


def parse_angle(text):
    """'360deg' -> 2 pi, '2pi' -> 2 pi, '0.5' -> 0.5."""
    text = text.strip()
    if text.endswith("deg"):
        return float(text[:-3]) * math.pi / 180.0
    if text.endswith("pi"):
        head = text[:-2]
        return (float(head) if head else 1.0) * math.pi
    return float(text)


def parse_over(over):
    name, spec = over.split("=")
    a, b, n = spec.split(":")
    return name, np.linspace(parse_angle(a), parse_angle(b), int(n))


def parse_assignments(text):
    out = {}
    for item in text.split(","):
        k, val = item.split("=")
        out[k.strip()] = float(val)
    return out


def sweep(mech, over, guess, time_of, check=True):
    """Rows of the cycle: `time_of(value)` is the time at which the driven
    coordinate has the varied value (the drive solved for t).  `check`
    runs check_row on every row (off only for timing)."""
    name, values = parse_over(over)
    q = np.zeros(len(mech.coordinates))
    for k, val in parse_assignments(guess).items():
        q[mech.idx(k)] = val
    # a slider between two rigid bodies keeps their relative angle at its
    # value in the guess
    for j in mech.joints:
        if j["kind"] == "slider" and j["fixed_angle"]:
            j["angle0"] = mech.angle(j["b"], q) - mech.angle(j["a"], q)
    rows, iterations = [], []
    prev = None
    for value in values:
        t = time_of(value)
        if prev is not None:
            qp, vp, ap, tp = prev
            dt = t - tp
            q = qp + vp * dt + 0.5 * ap * dt * dt
        q = mech.assemble(q, t)
        v, a = mech.kinematics(q, t)
        x, its = mech.forces(q, v, a, t)
        if check:
            check_row(mech, q, v, a, x, t)
        rows.append([float(value)] + list(q) + list(v) + list(a) + list(x))
        iterations.append(its)
        prev = (q, v, a, t)
    return mech.columns(name), rows, iterations


def multiplier_reactions(mech, q, v, a, x, t):
    """The reactions a second way, by Lagrange's equations of the first kind:
    M q'' - Q = J^T lambda with the same applied (and friction) forces taken
    as generalized forces, then each multiplier read as a reaction: a pin
    P_A - P_B = 0 pushes B with -lambda; a slider n.(Q - P) = 0 with
    n = perp(U) pushes B with lambda n (so NAME_n = lambda |U|); a fixed
    relative angle turns B with lambda; a drive q_k - f(t) = 0 is lambda."""
    n = len(mech.coordinates)
    gen = np.zeros(n)  # M q'' - Q
    for b in mech.bodies.values():
        gen[b.ix[0]] += b.mass * (a[b.ix[0]] - mech.gravity[0])
        gen[b.ix[1]] += b.mass * (a[b.ix[1]] - mech.gravity[1])
        if b.rigid:
            gen[b.ix[2]] += b.inertia * a[b.ix[2]]

    def push(body, force, arm):
        b = mech.bodies[body]
        gen[b.ix[0]] -= force[0]
        gen[b.ix[1]] -= force[1]
        if b.rigid:
            gen[b.ix[2]] -= cross(arm, force)

    for body, s, force in mech.loads:
        push(body, force(t, q, v), mech.point(body, s, q) - mech.point(body, np.zeros(2), q))
    for body, couple in mech.torques:
        gen[mech.bodies[body].ix[2]] -= couple(t, q, v)
    for k, _, dv in mech.springs:
        gen[k] += dv(q)
    if mech.has_friction():
        forces, couples = mech.friction_loads(x, q, v)
        for body, f, arm in forces:
            push(body, f, arm)
        for body, c in couples:
            if body in mech.bodies and mech.bodies[body].rigid:
                gen[mech.bodies[body].ix[2]] -= c
    lam = np.linalg.solve(mech.jacobian(q).T, gen)
    out, r = [], 0
    for j in mech.joints:
        if j["kind"] == "pin":
            out += [-lam[r], -lam[r + 1]]
            r += 2
        else:
            out.append(lam[r] * np.linalg.norm(mech.guide(j, q)))
            r += 1
            if j["fixed_angle"]:
                out.append(lam[r])
                r += 1
    out += list(lam[r:])
    return np.array(out)


def check_row(mech, q, v, a, x, t):
    """Finite differences of the positions for q' and q''; the reactions
    against Lagrange's multipliers; the power balance."""
    y = multiplier_reactions(mech, q, v, a, x, t)
    if np.max(np.abs(y - x)) > 1e-10 * max(1.0, np.max(np.abs(x))):
        raise RuntimeError("Newton-Euler and the multipliers disagree at t = %r: %r"
                           % (t, np.max(np.abs(y - x))))
    h = 1e-5
    qm = mech.assemble(q - v * h, t - h)
    qp = mech.assemble(q + v * h, t + h)
    v_fd = (qp - qm) / (2 * h)
    a_fd = (qp - 2 * q + qm) / (h * h)
    scale_v = max(1.0, np.max(np.abs(v)))
    scale_a = max(1.0, np.max(np.abs(a)))
    if np.max(np.abs(v_fd - v)) > 1e-7 * scale_v:
        raise RuntimeError("velocities disagree with finite differences at t = %r" % t)
    if np.max(np.abs(a_fd - a)) > 1e-3 * scale_a:
        raise RuntimeError("accelerations disagree with finite differences at t = %r: %r"
                           % (t, np.max(np.abs(a_fd - a))))
    drives = x[len(x) - len(mech.drives):]
    drive_power = sum(d * v[dr["k"]] for d, dr in zip(drives, mech.drives))
    rate = mech.energy_rate(q, v, a)
    loads = mech.load_power(q, v, t)
    dissipated = mech.friction_dissipation(x, q, v)
    if dissipated < -1e-12:
        raise RuntimeError("friction does positive work at t = %r" % t)
    balance = drive_power - (rate - loads + dissipated)
    scale = max(abs(drive_power), abs(rate), abs(loads), abs(dissipated), 1.0)
    if abs(balance) > 1e-10 * scale:
        raise RuntimeError("power balance fails at t = %r: %r" % (t, balance))


# ----------------------------------------------------------------------------
# The mechanisms (each written from its figure, not from its .qd file)
# ----------------------------------------------------------------------------


def slider_crank_engine(p):
    """Crank OA (centre of mass c1 from O), connecting rod AB (centre a2
    from A), piston B on the line y = e; spring k (free length l0) and a
    constant gas force P on the piston; Coulomb friction in the main bearing
    O, the crank pin A and the cylinder wall G."""
    m = Mechanism(["x1", "y1", "phi", "x2", "y2", "th", "xb", "yb"], p)
    m.body("crank", p["m1"], p["J1"], "x1", "y1", "phi")
    m.body("rod", p["m2"], p["J2"], "x2", "y2", "th")
    m.particle("piston", p["m3"], "xb", "yb")
    m.gravity = np.array([0.0, -p["g"]])
    fr_pin = p["mu0"] * p["r0"]
    m.pin("O", "ground", [0, 0], "crank", [-p["c1"], 0], friction=fr_pin)
    m.pin("A", "crank", [p["R"] - p["c1"], 0], "rod", [-p["a2"], 0], friction=fr_pin)
    m.pin("B", "rod", [p["L"] - p["a2"], 0], "piston", [0, 0])
    m.slider("G", "ground", [0, p["e"]], [1, 0], "piston", [0, 0], friction=p["mu"])
    w = p["omega"]
    m.drive("M", "phi", lambda t: w * t, lambda t: w, lambda t: 0.0)
    k, l0 = p["k"], p["l0"]
    xb = m.idx("xb")
    m.springs.append((xb, lambda q: 0.5 * k * (q[xb] - l0) ** 2, lambda q: k * (q[xb] - l0)))
    m.loads.append(("piston", np.zeros(2), lambda t, q, v: np.array([-p["P"], 0.0])))
    return m


def four_bar(p):
    """Crank O2A (a, centre at its middle), coupler AB (b) whose centre of mass
    lies r3 from A at d3 off AB and which carries a payload particle pinned
    p3 from the centre at e3 off AB, rocker O4B (c, centre at its middle),
    O4 = (d, 0); a resisting couple T4 on the rocker."""
    m = Mechanism(["x2", "y2", "th2", "x3", "y3", "th3", "x4", "y4", "th4", "xp", "yp"], p)
    m.body("crank", p["m2"], p["J2"], "x2", "y2", "th2")
    m.body("coupler", p["m3"], p["J3"], "x3", "y3", "th3")
    m.body("rocker", p["m4"], p["J4"], "x4", "y4", "th4")
    m.particle("payload", p["mp"], "xp", "yp")
    m.gravity = np.array([0.0, -p["g"]])
    a, b, c, d = p["a"], p["b"], p["c"], p["d"]
    sA = -p["r3"] * np.array([math.cos(p["d3"]), math.sin(p["d3"])])
    sB = sA + np.array([b, 0.0])
    sP = p["p3"] * np.array([math.cos(p["e3"]), math.sin(p["e3"])])
    m.pin("O2", "ground", [0, 0], "crank", [-a / 2, 0])
    m.pin("A", "crank", [a / 2, 0], "coupler", sA)
    m.pin("B", "coupler", sB, "rocker", [c / 2, 0])
    m.pin("O4", "ground", [d, 0], "rocker", [-c / 2, 0])
    m.pin("P", "coupler", sP, "payload", [0, 0])
    w = p["omega"]
    m.drive("M", "th2", lambda t: w * t, lambda t: w, lambda t: 0.0)
    m.torques.append(("rocker", lambda t, q, v: -p["T4"]))
    return m


def quick_return(p):
    """Crank-shaper quick return: crank O2A (r) drives a block sliding on the
    slotted lever O4C (pivot O4 = (f, -d), centre of mass c4 from O4); the
    link CD (l5) drives the ram D along the line y = h against a constant
    cutting force F.  The block slides on the lever with Coulomb friction mu
    and turns with it."""
    m = Mechanism(["x2", "y2", "th2", "xs", "ys", "ths", "x4", "y4", "th4",
                   "x5", "y5", "th5", "xr", "yr"], p)
    m.body("crank", p["m2"], p["J2"], "x2", "y2", "th2")
    m.body("block", p["ms"], p["Js"], "xs", "ys", "ths")
    m.body("lever", p["m4"], p["J4"], "x4", "y4", "th4")
    m.body("link", p["m5"], p["J5"], "x5", "y5", "th5")
    m.particle("ram", p["m6"], "xr", "yr")
    m.gravity = np.array([0.0, -p["g"]])
    r, c4, l4, l5 = p["r"], p["c4"], p["l4"], p["l5"]
    m.pin("O2", "ground", [0, 0], "crank", [-r / 2, 0])
    m.pin("A", "crank", [r / 2, 0], "block", [0, 0])
    m.slider("S", "lever", [-c4, 0], [1, 0], "block", [0, 0], friction=p["mu"])
    m.pin("O4", "ground", [p["f"], -p["d"]], "lever", [-c4, 0])
    m.pin("C", "lever", [l4 - c4, 0], "link", [-l5 / 2, 0])
    m.pin("D", "link", [l5 / 2, 0], "ram", [0, 0])
    m.slider("R", "ground", [0, p["h"]], [1, 0], "ram", [0, 0])
    w = p["omega"]
    m.drive("M", "th2", lambda t: w * t, lambda t: w, lambda t: 0.0)
    m.loads.append(("ram", np.zeros(2), lambda t, q, v: np.array([-p["F"], 0.0])))
    return m


def marghitu_slider_crank(p):
    """Marghitu's R-RRT example: crank AB and rod BC (centres at their
    middles, I = m (l^2 + h^2)/12), slider C on the x axis through A, an
    external force Fext along x on the slider."""
    m = Mechanism(["x1", "y1", "phi", "x2", "y2", "th", "xc", "yc"], p)
    j1 = p["m1"] * (p["AB"] ** 2 + p["h"] ** 2) / 12
    j2 = p["m2"] * (p["BC"] ** 2 + p["h"] ** 2) / 12
    m.body("crank", p["m1"], j1, "x1", "y1", "phi")
    m.body("rod", p["m2"], j2, "x2", "y2", "th")
    m.particle("block", p["m3"], "xc", "yc")
    m.gravity = np.array([0.0, -p["g"]])
    m.pin("A", "ground", [0, 0], "crank", [-p["AB"] / 2, 0])
    m.pin("B", "crank", [p["AB"] / 2, 0], "rod", [-p["BC"] / 2, 0])
    m.pin("C", "rod", [p["BC"] / 2, 0], "block", [0, 0])
    m.slider("T", "ground", [0, 0], [1, 0], "block", [0, 0])
    w = p["omega"]
    m.drive("Me", "phi", lambda t: w * t, lambda t: w, lambda t: 0.0)
    m.loads.append(("block", np.zeros(2), lambda t, q, v: np.array([p["Fext"], 0.0])))
    return m


# ----------------------------------------------------------------------------
# The cases
# ----------------------------------------------------------------------------

ENGINE = ("R=0.1,L=0.4,c1=0.02,a2=0.13,e=0.02,omega=30,m1=2,J1=0.01,m2=1.2,J2=0.018,"
          "m3=0.8,g=9.81,k=2000,l0=0.45,P=300,mu=0.1,mu0=0.05,r0=0.01")
ENGINE_FREE = ENGINE.replace("mu=0.1,mu0=0.05", "mu=0,mu0=0")
ENGINE_GUESS = "x1=0.02,phi=0,x2=0.23,y2=0.0065,th=0.05,xb=0.5,yb=0.02"

FOUR_BAR = ("a=0.05,b=0.2,c=0.12,d=0.18,r3=0.09,d3=0.3,p3=0.07,e3=1.2,omega=20,"
            "m2=0.4,J2=0.0002,m3=1.5,J3=0.006,m4=0.8,J4=0.0012,mp=0.6,g=9.81,T4=2")
FOUR_BAR_GUESS = ("x2=0.025,th2=0,x3=0.105,y3=0.071,th3=0.61,x4=0.197,y4=0.058,th4=1.29,"
                  "xp=0.088,yp=0.139")

QUICK = ("r=0.1,f=0.013,d=0.3,c4=0.3,l4=0.6,l5=0.25,h=0.32,omega=6,m2=1,J2=0.002,"
         "ms=0.3,Js=0.0002,m4=3,J4=0.09,m5=1,J5=0.005,m6=8,g=9.81,F=150,mu=0.15")
QUICK_FREE = QUICK.replace("mu=0.15", "mu=0")
QUICK_GUESS = ("x2=0.05,th2=0,xs=0.1,ths=1.29,x4=0.097,y4=-0.012,th4=1.29,x5=0.303,"
               "y5=0.298,th5=0.18,xr=0.426,yr=0.32")

MARGHITU = "AB=1,BC=1,h=0.01,omega=1,m1=1,m2=1,m3=1,g=10,Fext=100"
MARGHITU_GUESS = "x1=0.35,y1=0.35,phi=0.785,x2=1.06,y2=0.35,th=-0.785,xc=1.41"

MARGHITU_SOURCE = (
    "D. B. Marghitu, Mechanisms and Robots Analysis with MATLAB, Springer, 2009, "
    "ch. 4 'Dynamic Force Analysis', the R-RRT example (contour method, Eqs. "
    "4.51-4.52, p. 144; https://studmed.ru/view/dan-b-marghitu-mechanisms-and-"
    "robots-analysis-with-matlab_8be015c74f0.html?page=15), and the same example "
    "in Marghitu's lecture notes 'Dynamic Force Analysis: R-RRT mechanism', sec. "
    "1.1 (https://www.scribd.com/doc/193600397/Dynamic-Force-Analysis): "
    "slider-crank with AB = BC = 1 m, driver angle pi/4, constant speed "
    "n = 30/pi rpm (omega = 1 rad/s), m1 = m2 = m3 = 1 kg, links of height "
    "h = 0.01 m (I_C1 = I_C2 = m (l^2 + h^2)/12), g = 10 m/s^2, Fext = 100 N "
    "on the slider opposing v_C.  Row 2 (phi = 45 deg) is the book's position.")


def marghitu_extra(rows, columns):
    """The book's printed numbers at phi = 45 deg (row 1) and the hand-solved
    closed forms of that position, each checked against the row."""
    r2 = math.sqrt(2.0)
    row = rows[1]
    reactions = 1 + 3 * 8  # the first reaction column

    def at(name):
        return row[columns.index(name, reactions if "_" in name or name == "Me" else 1)]

    printed = {
        "B_x": ["F12x = -(1/4)(400 + 7*sqrt(2)) N (p. 144)", -(400 + 7 * r2) / 4],
        "B_y": ["F12y = (5/4)(84 + sqrt(2)) N (p. 144)", 5 * (84 + r2) / 4],
    }
    closed = {  # solved by hand from the free-body diagrams at phi = pi/4
        "A_x": ["-100 - 2*sqrt(2) N", -100 - 2 * r2],
        "A_y": ["115 + sqrt(2) N", 115 + r2],
        "B_x": ["-100 - 7*sqrt(2)/4 N", -100 - 7 * r2 / 4],
        "B_y": ["105 + 5*sqrt(2)/4 N", 105 + 5 * r2 / 4],
        "C_x": ["-100 - sqrt(2) N", -100 - r2],
        "C_y": ["95 + 3*sqrt(2)/2 N", 95 + 3 * r2 / 2],
        "T_n": ["-85 - 3*sqrt(2)/2 N", -85 - 3 * r2 / 2],
        "Me": ["3 + 105*sqrt(2) N m", 3 + 105 * r2],
        "th'": ["-1 rad/s", -1.0],
        "th''": ["0 rad/s^2", 0.0],
        "xc'": ["-sqrt(2) m/s", -r2],
        "xc''": ["-sqrt(2) m/s^2", -r2],
    }
    agreement = {}
    for name, (text, value) in list(printed.items()) + list(closed.items()):
        got = at(name)
        if abs(got - value) > 1e-12 * max(1.0, abs(value)):
            raise RuntimeError("Marghitu's %s: %r, expected %r" % (name, got, value))
    for name, (text, value) in printed.items():
        agreement[name] = {"printed": text, "printed_value": value, "fixture": at(name),
                           "difference": at(name) - value}
    return {
        "printed": {
            "B_x": "F12x = -(1/4)(400 + 7*sqrt(2)) N = -102.4749 N",
            "B_y": "F12y = (5/4)(84 + sqrt(2)) N = 106.7678 N",
            "I_C1 = I_C2": "0.0833417 kg m^2 (the lecture notes; = (1 + 0.01^2)/12 = 0.08334167 rounded)",
            "alpha1 = alpha2": "0 rad/s^2 at phi = pi/4 (the lecture notes)",
            "Fext": "100 N (the lecture notes)",
        },
        "printed_row": 1,
        "agreement": agreement,
        "closed_forms": {k: v[0] for k, v in closed.items()},
        "not_found": ("The book's values of F01, F23, F03 and the equilibrium moment M were not in "
                      "the excerpts that could be read, so only F12 is compared with print. "
                      "The closed forms above (solved by hand) match the fixture's row to 1e-12."),
    }


def engine_source(friction):
    text = ("Single-cylinder engine (a slider-crank with offset cylinder, spring "
            "and gas load), values chosen for this fixture after the slider-crank "
            "of issue 36 / the seed's problem 21.3; bearing loads at O, A, B, the "
            "cylinder's normal force G_n and the driving couple M.")
    if friction:
        text += (" Coulomb friction as in the seed's (21.74)-(21.75): mu0*r0 in "
                 "the pins O and A, mu on the cylinder wall G.")
    else:
        text += " Frictionless: the same scene with mu = mu0 = 0."
    return text


CASES = [
    dict(name="slider_crank_engine", build=slider_crank_engine, set=ENGINE,
         over="phi=0:360deg:73", guess=ENGINE_GUESS,
         scene="examples/mechanisms/slider_crank_engine.qd", source=engine_source(True)),
    dict(name="slider_crank_engine_frictionless", mean_drive_zero=True, build=slider_crank_engine, set=ENGINE_FREE,
         over="phi=0:360deg:73", guess=ENGINE_GUESS,
         scene="examples/mechanisms/slider_crank_engine.qd", source=engine_source(False)),
    dict(name="four_bar", mean_drive_zero=True, build=four_bar, set=FOUR_BAR, over="th2=0:360deg:73",
         guess=FOUR_BAR_GUESS, scene="examples/mechanisms/four_bar.qd",
         source=("Crank-rocker four-bar (Grashof, transmission angle 39-88 deg) whose "
                 "coupler's centre of mass lies off the line AB and carries a payload "
                 "mass at a coupler point, resisting couple on the rocker; values "
                 "chosen for this fixture after Norton, Design of Machinery, sec. 11.5 "
                 "(the four-bar's dynamic force analysis).")),
    dict(name="quick_return", build=quick_return, set=QUICK, over="th2=0:360deg:73",
         guess=QUICK_GUESS, scene="examples/mechanisms/quick_return.qd",
         source=("Crank-shaper (Whitworth-type) quick-return mechanism: crank, block "
                 "sliding on the slotted lever (a slider between two rigid bodies, "
                 "with Coulomb friction mu), link and ram against a cutting force; "
                 "values chosen for this fixture (time ratio about 1.5).")),
    dict(name="quick_return_frictionless", mean_drive_zero=True, build=quick_return, set=QUICK_FREE,
         over="th2=0:360deg:73", guess=QUICK_GUESS, scene="examples/mechanisms/quick_return.qd",
         source="The quick-return mechanism without friction (mu = 0)."),
    dict(name="marghitu_slider_crank", build=marghitu_slider_crank, set=MARGHITU,
         over="phi=40deg:50deg:3", guess=MARGHITU_GUESS,
         scene="examples/mechanisms/marghitu_slider_crank.qd", source=MARGHITU_SOURCE,
         extra=marghitu_extra),
]


def run_case(case, over=None, check=True):
    params = parse_assignments(case["set"])
    mech = case["build"](params)
    omega = params["omega"]
    # every drive here is q = omega*t: the varied value v is reached at t = v/omega
    columns, rows, iterations = sweep(mech, over or case["over"], case["guess"],
                                      lambda val: val / omega, check)
    return mech, columns, rows, iterations


def time_case(name, count, repeats=5):
    """The seconds one cycle of the case `name` takes over `count` positions
    of its varied angle from 0 to 360 degrees (building the mechanism,
    positions, velocities, accelerations, forces and friction; the
    per-row checks off), the best of `repeats` runs."""
    import time
    case = next((c for c in CASES if c["name"] == name), None)
    if case is None:
        raise SystemExit("no case %r: %s" % (name, ", ".join(c["name"] for c in CASES)))
    varied = case["over"].split("=")[0]
    over = "%s=0:360deg:%d" % (varied, count)
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        _, _, rows, _ = run_case(case, over=over, check=False)
        best = min(best, time.perf_counter() - start)
    assert len(rows) == count
    return best


def check_cycle_mean(mech, columns, rows):
    """Without friction, at constant speed, the drive's work over a whole
    cycle is the change of T + V (zero) minus the loads' work (constant
    forces and couples: zero over a closed cycle), so the drive's mean over
    the periodic grid (the first 72 of 73 rows) vanishes."""
    for dr in mech.drives:
        values = np.array([r[columns.index(dr["name"], 1 + 3 * len(mech.coordinates))] for r in rows])
        mean = np.mean(values[:-1])
        if abs(mean) > 1e-10 * np.max(np.abs(values)):
            raise RuntimeError("drive %s: mean %r over the cycle" % (dr["name"], mean))


def main():
    if len(sys.argv) >= 4 and sys.argv[1] == "--time":
        repeats = int(sys.argv[4]) if len(sys.argv) > 4 else 5
        print(repr(time_case(sys.argv[2], int(sys.argv[3]), repeats)))
        return
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "tests", "fixtures", "mechanisms")
    os.makedirs(out, exist_ok=True)
    for case in CASES:
        mech, columns, rows, iterations = run_case(case)
        if case.get("mean_drive_zero"):
            check_cycle_mean(mech, columns, rows)
        doc = {
            "scene": case["scene"],
            "over": case["over"],
            "set": case["set"],
            "guess": case["guess"],
            "columns": columns,
            "rows": rows,
            "source": case["source"],
        }
        if max(iterations) > 1:
            doc["friction_iterations"] = iterations
        extra = case.get("extra")
        if extra:
            doc.update(extra(rows, columns))
        path = os.path.join(out, case["name"] + ".json")
        with open(path, "w") as fh:
            fh.write(dump(doc))
        print("%-36s %3d rows, %2d columns" % (case["name"], len(rows), len(columns)), file=sys.stderr)


def dump(doc):
    """JSON with one row per line; floats as repr (shortest round trip)."""
    lines = ["{"]
    keys = list(doc)
    for i, k in enumerate(keys):
        comma = "," if i + 1 < len(keys) else ""
        if k == "rows":
            lines.append('  "rows": [')
            for r, row in enumerate(doc[k]):
                sep = "," if r + 1 < len(doc[k]) else ""
                lines.append("    [" + ", ".join(repr(float(x)) for x in row) + "]" + sep)
            lines.append("  ]" + comma)
        else:
            lines.append("  " + json.dumps(k) + ": " + json.dumps(doc[k], ensure_ascii=False) + comma)
    lines.append("}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
