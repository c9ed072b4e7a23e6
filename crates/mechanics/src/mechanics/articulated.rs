//! The accelerations of a tree of rigid bodies by the articulated-body
//! algorithm (Featherstone, *Rigid Body Dynamics Algorithms*, 2008,
//! Table 7.1, in absolute coordinates as in §2.11): every quantity an
//! intermediate of the scene's tape, so q̈ costs O(n) small expressions,
//! where M = L·D·Lᵀ costs O(n³). A port of a published algorithm: the
//! passes keep its order and names.
//!
//! Spatial vectors are in ground coordinates at the ground's origin. A
//! body's velocity is V = (ω, v), v the velocity of the body point at the
//! origin (v = ċ − ω×c); its momentum 𝕀·V = (I_g·ω + m·c×ċ, m·ċ) with
//! I_g = R·I·Rᵀ; the net force on it is d(𝕀·V)/dt = 𝕀·A + V ×* 𝕀·V. In the
//! plane, V = (ω, vx, vy).
//!
//! The tree is read from the scene: a body's coordinates are those its
//! centre and frame depend on; bodies with the same coordinates are one
//! link; a link's parent is the link whose coordinates are the largest
//! proper subset of its own, and the rest are its joint's (every subset
//! must lie inside the parent's: a tree). A particle turns with its
//! parent (its rotational inertia is zero, so any ω consistent with ċ
//! serves). Gravity is the ground's acceleration −g; every other force of
//! the scene (potentials, loads, torques, forces, dissipation) enters as
//! the generalized force τ on the coordinates.
//!
//! The reading assumes rigid joints: V_link = V_parent + S·q̇_joint + β(q, t).
//! A scene that is not such a tree (a particle's motion relative to its
//! parent's frame that depends on the parent's coordinates, say) gives a
//! different q̈. So the result is compared with M⁻¹·f (the tape's M and f,
//! solved numerically) at random states, and used only when they agree.

use super::Lagrange;
use crate::expr::atom::{self, Atom};
use crate::expr::tape::{Calculus, Tape};
use crate::expr::Expr;
use crate::parse::ast::Role;
use crate::poly::Var;
use crate::scene::{Scene, Turning};
use rustc_hash::FxHashMap;

/// How many random states the recursion is compared with M⁻¹·f at.
const PROBES: u64 = 3;
/// The largest joint (coordinates of one link) the recursion inverts.
const MAX_JOINT: usize = 6;

/// One link of the tree: bodies moving together.
struct Link {
    /// Indices of its bodies in `scene.bodies`.
    bodies: Vec<usize>,
    /// Its coordinates (sorted indices).
    coordinates: Vec<usize>,
    /// The parent link (an earlier index), `None` on the ground.
    parent: Option<usize>,
    /// The joint's coordinates: `coordinates` minus the parent's.
    joint: Vec<usize>,
}

/// The exact accelerations of `lagrange`'s scene through the
/// articulated-body recursion, written on a copy of its tape, or why the
/// scene is not a tree of rigid bodies that the recursion reads exactly.
pub(crate) fn articulated(scene: &Scene, lagrange: &Lagrange) -> Result<(Vec<Expr>, Tape), String> {
    let Some(tape) = lagrange.intermediates.as_deref() else {
        return Err("the equations are expanded".into());
    };
    // the scene's intermediates come first on its equations' tape
    let scene_first = scene.tape.as_ref().and_then(|t| t.entries().first());
    if scene_first.is_some_and(|a| tape.entries().first().is_none_or(|b| a.var != b.var)) {
        return Err("the equations were not derived from this scene".into());
    }
    eligible(scene)?;
    let mut tape = tape.clone();
    let links = tree(scene, &mut tape)?;
    let tau = joint_forces(scene, &mut tape)?;
    let planar = scene.bodies[0].mass_properties.centre.len() == 2;
    let mut abc = Recursion {
        tape: &mut tape,
        scene,
        s: if planar { 3 } else { 6 },
        coordinates: &lagrange.coordinates,
        at_rest: lagrange
            .coordinates
            .iter()
            .map(|c| (atom::coord(c, 2), Expr::zero()))
            .collect(),
    };
    let acc = abc.accelerations(&links, &tau)?;
    verify(&tape, lagrange, &acc)?;
    Ok((acc, tape))
}

/// An error unless the kinetic energy is the bodies' alone and nothing
/// else in the scene carries inertia.
fn eligible(scene: &Scene) -> Result<(), String> {
    if scene.bodies.is_empty() {
        return Err("the scene has no bodies".into());
    }
    if !scene.constraints.is_empty() || !scene.functions.is_empty() {
        return Err("the scene has constraints or given functions".into());
    }
    if scene.has_role(Role::Lagrangian) {
        return Err("the scene writes a Lagrangian".into());
    }
    let kinetic: Vec<&str> = scene.bodies.iter().map(|b| b.kinetic.as_str()).collect();
    if scene
        .role(Role::Kinetic)
        .any(|d| !kinetic.contains(&d.name.as_str()))
    {
        return Err("the scene has kinetic energy besides its bodies'".into());
    }
    let d = scene.bodies[0].mass_properties.centre.len();
    if scene
        .bodies
        .iter()
        .any(|b| b.mass_properties.centre.len() != d)
    {
        return Err("the bodies mix the plane and space".into());
    }
    Ok(())
}

/// The links of the scene's bodies, parents first.
fn tree(scene: &Scene, tape: &mut Tape) -> Result<Vec<Link>, String> {
    let n = scene.coordinates.len();
    let q: Vec<Var> = scene
        .coordinates
        .iter()
        .map(|c| atom::coord(&c.name, 0))
        .collect();
    let mut sets: Vec<(Vec<usize>, usize)> = Vec::new();
    for (b, body) in scene.bodies.iter().enumerate() {
        let p = &body.mass_properties;
        let mut pose: Vec<&Expr> = p.centre.iter().collect();
        match &p.turning {
            Some(Turning::Space { frame, .. }) => pose.extend(frame.entries()),
            Some(Turning::Plane { angle, .. }) => pose.push(angle),
            None => {}
        }
        let set: Vec<usize> = (0..n)
            .filter(|&k| pose.iter().any(|e| tape.depends(e, q[k])))
            .collect();
        sets.push((set, b));
    }
    sets.sort_by(|a, b| a.0.len().cmp(&b.0.len()).then(a.1.cmp(&b.1)));
    let mut links: Vec<Link> = Vec::new();
    for (set, b) in sets {
        if set.is_empty() {
            // fixed in the ground: no inertia reaches the coordinates
            continue;
        }
        if let Some(l) = links.iter_mut().find(|l| l.coordinates == set) {
            l.bodies.push(b);
            continue;
        }
        let inside = |l: &Link| l.coordinates.iter().all(|k| set.contains(k));
        let parent = (0..links.len())
            .filter(|&i| inside(&links[i]))
            .max_by_key(|&i| links[i].coordinates.len());
        if let Some(p) = parent {
            let within_parent = |l: &Link| {
                l.coordinates
                    .iter()
                    .all(|k| links[p].coordinates.contains(k))
            };
            if links
                .iter()
                .filter(|l| inside(l))
                .any(|l| !within_parent(l))
            {
                return Err("the bodies' coordinates do not form a tree".into());
            }
        }
        let joint: Vec<usize> = set
            .iter()
            .copied()
            .filter(|k| parent.is_none_or(|p| !links[p].coordinates.contains(k)))
            .collect();
        if joint.len() > MAX_JOINT {
            return Err(format!("a joint has more than {MAX_JOINT} coordinates"));
        }
        links.push(Link {
            bodies: vec![b],
            coordinates: set,
            parent,
            joint,
        });
    }
    let mut owned = vec![false; n];
    for l in &links {
        for &k in &l.joint {
            if std::mem::replace(&mut owned[k], true) {
                return Err("the bodies' coordinates do not form a tree".into());
            }
        }
    }
    if let Some(k) = owned.iter().position(|o| !o) {
        return Err(format!("no body moves with {}", scene.coordinates[k].name));
    }
    Ok(links)
}

/// τ_k: the generalized forces of everything but the bodies' inertia and
/// weight.
fn joint_forces(scene: &Scene, tape: &mut Tape) -> Result<Vec<Expr>, String> {
    let mut rest = scene.clone();
    let own: Vec<&str> = scene
        .bodies
        .iter()
        .flat_map(|b| std::iter::once(b.kinetic.as_str()).chain(b.gravity.as_deref()))
        .collect();
    rest.definitions.retain(|d| !own.contains(&d.name.as_str()));
    let qdd: Vec<Var> = scene
        .coordinates
        .iter()
        .map(|c| atom::coord(&c.name, 2))
        .collect();
    let terms = super::force_terms_with(&rest, tape);
    let mut tau = Vec::with_capacity(terms.len());
    for t in terms {
        let v = super::sum_terms(&t);
        if qdd.iter().any(|&a| tape.depends(&v, a)) {
            return Err("a force depends on the accelerations".into());
        }
        tau.push(v);
    }
    Ok(tau)
}

/// The state of the recursion: the tape its quantities are named on.
struct Recursion<'a> {
    tape: &'a mut Tape,
    scene: &'a Scene,
    /// 6 in space, 3 in the plane.
    s: usize,
    coordinates: &'a [String],
    /// Every q̈ at 0: a rate read at q̈ = 0 is a bias term.
    at_rest: FxHashMap<Var, Expr>,
}

/// A symmetric matrix, in full.
type Sym = Vec<Vec<Expr>>;

/// What the passes know of one link.
struct LinkState {
    /// V, its spatial velocity.
    velocity: Vec<Expr>,
    /// S, a column per joint coordinate.
    axes: Vec<Vec<Expr>>,
    /// c, its bias acceleration relative to its parent.
    bias: Vec<Expr>,
    /// 𝕀, then Iᴬ as its children add to it.
    inertia: Sym,
    /// V ×* 𝕀·V, then pᴬ as its children add to it.
    bias_force: Vec<Expr>,
    /// U = Iᴬ·S, a column per joint coordinate.
    u: Vec<Vec<Expr>>,
    /// D⁻¹ = (Sᵀ·U)⁻¹.
    d_inverse: Sym,
    /// u = τ − Sᵀ·pᴬ.
    rest: Vec<Expr>,
}

impl Recursion<'_> {
    fn name(&mut self, hint: String, e: Expr) -> Expr {
        self.tape.define(&hint, e)
    }

    fn name_vec(&mut self, hint: &str, v: Vec<Expr>) -> Vec<Expr> {
        v.into_iter()
            .enumerate()
            .map(|(i, e)| self.name(format!("{hint}_{}", i + 1), e))
            .collect()
    }

    fn name_sym(&mut self, hint: &str, m: Sym) -> Sym {
        let s = m.len();
        let mut out = vec![vec![Expr::zero(); s]; s];
        for i in 0..s {
            for j in i..s {
                let e = self.name(format!("{hint}_{}{}", i + 1, j + 1), m[i][j].clone());
                out[i][j] = e.clone();
                out[j][i] = e;
            }
        }
        out
    }

    /// The body's angular velocity in ground coordinates, if it turns.
    fn omega(&mut self, b: usize) -> Option<Vec<Expr>> {
        match &self.scene.bodies[b].mass_properties.turning {
            Some(Turning::Space { frame, .. }) => Some(frame.omega_ground().to_vec()),
            Some(Turning::Plane { angle, .. }) => Some(vec![self.tape.dt(angle)]),
            None => None,
        }
    }

    /// The spatial velocity of a link: ω of its first turning body (else
    /// its parent's), v = ċ − ω×c at that body's centre.
    fn velocity(&mut self, link: &Link, parent: Option<&Vec<Expr>>) -> Vec<Expr> {
        let turning = link
            .bodies
            .iter()
            .copied()
            .find_map(|b| self.omega(b).map(|w| (b, w)));
        let (b, w) = match turning {
            Some(bw) => bw,
            None => {
                let w = match parent {
                    Some(v) => v[..self.s / 2].to_vec(),
                    None => vec![Expr::zero(); self.s / 2],
                };
                (link.bodies[0], w)
            }
        };
        let c = self.scene.bodies[b].mass_properties.centre.clone();
        let cdot: Vec<Expr> = c.iter().map(|x| self.tape.dt(x)).collect();
        let wxc = cross(&w, &c);
        let mut v = w;
        v.extend(cdot.iter().zip(&wxc).map(|(a, b)| a.sub(b)));
        v
    }

    /// The spatial inertia at the origin of the link's bodies together.
    fn inertia(&mut self, link: &Link) -> Sym {
        let s = self.s;
        let mut total = vec![vec![Expr::zero(); s]; s];
        for &b in &link.bodies {
            let i = body_inertia(&self.scene.bodies[b].mass_properties, s);
            for r in 0..s {
                for c in 0..s {
                    total[r][c] = total[r][c].add(&i[r][c]);
                }
            }
        }
        total
    }

    /// q̈ by the three passes.
    fn accelerations(&mut self, links: &[Link], tau: &[Expr]) -> Result<Vec<Expr>, String> {
        let mut state: Vec<LinkState> = Vec::with_capacity(links.len());
        for (l, link) in links.iter().enumerate() {
            let parent = link.parent.map(|p| state[p].velocity.clone());
            let st = self.outward(l + 1, link, parent.as_ref())?;
            state.push(st);
        }
        for l in (0..links.len()).rev() {
            self.inward(l, &links[l], tau, &mut state)?;
        }
        Ok(self.accelerations_outward(links, &state))
    }

    /// Pass 1 for one link: its velocity, joint axes, bias acceleration,
    /// inertia and bias force.
    fn outward(
        &mut self,
        tag: usize,
        link: &Link,
        parent: Option<&Vec<Expr>>,
    ) -> Result<LinkState, String> {
        let v = self.velocity(link, parent);
        let v = self.name_vec(&format!("V{tag}"), v);
        let rel: Vec<Expr> = match parent {
            Some(p) => v.iter().zip(p).map(|(a, b)| a.sub(b)).collect(),
            None => v.clone(),
        };
        let mut axes = Vec::with_capacity(link.joint.len());
        for (j, &k) in link.joint.iter().enumerate() {
            let qd = atom::coord(&self.coordinates[k], 1);
            let col: Vec<Expr> = rel.iter().map(|e| self.tape.partial(e, qd)).collect();
            axes.push(self.name_vec(&format!("S{tag}{}", j + 1), col));
        }
        // c = Ṡ·q̇ + β̇: the rate of the joint's velocity at q̈ = 0
        let mut c = Vec::with_capacity(self.s);
        for e in &rel {
            let rate = self.tape.dt(e);
            c.push(rate.subs_many(&self.at_rest).map_err(|e| e.message)?);
        }
        let bias = self.name_vec(&format!("c{tag}"), c);
        let inertia = self.inertia(link);
        let inertia = self.name_sym(&format!("I{tag}"), inertia);
        let h = mat_vec(&inertia, &v);
        let h = self.name_vec(&format!("h{tag}"), h);
        Ok(LinkState {
            bias_force: force_cross(&v, &h),
            velocity: v,
            axes,
            bias,
            inertia,
            u: Vec::new(),
            d_inverse: Vec::new(),
            rest: Vec::new(),
        })
    }

    /// Pass 2 for link `l` (its children done): its articulated inertia
    /// and bias force, its joint's U, D⁻¹ and u, and what it passes to its
    /// parent: Iᵃ = Iᴬ − U·D⁻¹·Uᵀ, pᵃ = pᴬ + Iᵃ·c + U·D⁻¹·u.
    fn inward(
        &mut self,
        l: usize,
        link: &Link,
        tau: &[Expr],
        state: &mut [LinkState],
    ) -> Result<(), String> {
        let (s, tag, k) = (self.s, l + 1, link.joint.len());
        let i = self.name_sym(&format!("IA{tag}"), std::mem::take(&mut state[l].inertia));
        let p = self.name_vec(
            &format!("pA{tag}"),
            std::mem::take(&mut state[l].bias_force),
        );
        let axes = &state[l].axes;
        let mut u_cols = Vec::with_capacity(k);
        for (j, col) in axes.iter().enumerate() {
            let u = mat_vec(&i, col);
            u_cols.push(self.name_vec(&format!("U{tag}{}", j + 1), u));
        }
        let d: Sym = (0..k)
            .map(|a| (0..k).map(|b| dot(&axes[a], &u_cols[b])).collect())
            .collect();
        let d = self.name_sym(&format!("Dj{tag}"), d);
        let dinv = self.inverse(&d, tag)?;
        let mut rest = Vec::with_capacity(k);
        for (a, &q) in link.joint.iter().enumerate() {
            let e = tau[q].sub(&dot(&axes[a], &p));
            rest.push(self.name(format!("u{tag}_{}", a + 1), e));
        }
        if let Some(parent) = link.parent {
            // W = U·D⁻¹, column by column (D⁻¹ is symmetric)
            let mut w = Vec::with_capacity(k);
            for (a, drow) in dinv.iter().enumerate() {
                let col: Vec<Expr> = (0..s)
                    .map(|r| {
                        u_cols
                            .iter()
                            .zip(drow)
                            .fold(Expr::zero(), |acc, (u, d)| acc.add(&u[r].mul(d)))
                    })
                    .collect();
                w.push(self.name_vec(&format!("W{tag}{}", a + 1), col));
            }
            let mut art = i;
            for r in 0..s {
                for c in r..s {
                    let e =
                        (0..k).fold(art[r][c].clone(), |e, a| e.sub(&w[a][r].mul(&u_cols[a][c])));
                    art[r][c] = e.clone();
                    art[c][r] = e;
                }
            }
            let art = self.name_sym(&format!("Ia{tag}"), art);
            let ic = mat_vec(&art, &state[l].bias);
            let up = &mut state[parent];
            for r in 0..s {
                let e = (0..k).fold(p[r].add(&ic[r]), |e, a| e.add(&w[a][r].mul(&rest[a])));
                up.bias_force[r] = up.bias_force[r].add(&e);
                for (dst, x) in up.inertia[r].iter_mut().zip(&art[r]) {
                    *dst = dst.add(x);
                }
            }
        }
        let st = &mut state[l];
        st.u = u_cols;
        st.d_inverse = dinv;
        st.rest = rest;
        Ok(())
    }

    /// Pass 3: the links' accelerations from the ground's, and q̈ of each
    /// joint: q̈ = D⁻¹·(u − Uᵀ·(A_parent + c)).
    fn accelerations_outward(&mut self, links: &[Link], state: &[LinkState]) -> Vec<Expr> {
        let ground = self.ground_acceleration();
        let mut acc_links: Vec<Vec<Expr>> = Vec::with_capacity(links.len());
        let mut out = vec![Expr::zero(); self.coordinates.len()];
        for (l, (link, st)) in links.iter().zip(state).enumerate() {
            let tag = l + 1;
            let from = link.parent.map_or(&ground, |p| &acc_links[p]);
            let a: Vec<Expr> = from.iter().zip(&st.bias).map(|(x, y)| x.add(y)).collect();
            let mut a = self.name_vec(&format!("Ap{tag}"), a);
            let k = link.joint.len();
            let r: Vec<Expr> = (0..k).map(|j| st.rest[j].sub(&dot(&st.u[j], &a))).collect();
            let mut qdd = Vec::with_capacity(k);
            for (j, &q) in link.joint.iter().enumerate() {
                let e = (0..k).fold(Expr::zero(), |acc, b| {
                    acc.add(&st.d_inverse[j][b].mul(&r[b]))
                });
                let e = self.name(format!("{}_dd", self.coordinates[q]), e);
                out[q] = e.clone();
                qdd.push(e);
            }
            for (axis, e) in st.axes.iter().zip(&qdd) {
                for (row, x) in a.iter_mut().zip(axis) {
                    *row = row.add(&x.mul(e));
                }
            }
            let a = self.name_vec(&format!("A{tag}"), a);
            acc_links.push(a);
        }
        out
    }

    /// The ground's spatial acceleration: −g, so that weights need no force.
    fn ground_acceleration(&self) -> Vec<Expr> {
        let mut a = vec![Expr::zero(); self.s / 2];
        let g = self
            .scene
            .bodies
            .iter()
            .find_map(|b| b.mass_properties.gravity.clone());
        match g {
            Some(g) => a.extend(g.iter().map(Expr::neg)),
            None => a.extend((0..self.s / 2).map(|_| Expr::zero())),
        }
        a
    }

    /// The inverse of a joint's D (symmetric, k×k) by Gauss–Jordan on
    /// named entries; D is positive definite for a joint whose
    /// coordinates carry inertia, and a zero pivot is refused.
    fn inverse(&mut self, d: &Sym, tag: usize) -> Result<Sym, String> {
        let k = d.len();
        let mut a = d.clone();
        let mut inv: Sym = (0..k)
            .map(|i| {
                (0..k)
                    .map(|j| if i == j { Expr::one() } else { Expr::zero() })
                    .collect()
            })
            .collect();
        for c in 0..k {
            if a[c][c].is_zero() {
                return Err("a joint's articulated inertia is zero".into());
            }
            let pivot = self.name(format!("Dp{tag}_{}", c + 1), a[c][c].clone());
            for j in 0..k {
                a[c][j] = a[c][j].div(&pivot).map_err(|e| e.message)?;
                inv[c][j] = inv[c][j].div(&pivot).map_err(|e| e.message)?;
                inv[c][j] = self.name(format!("Di{tag}_{}{}", c + 1, j + 1), inv[c][j].clone());
            }
            for r in 0..k {
                if r == c || a[r][c].is_zero() {
                    continue;
                }
                let f = a[r][c].clone();
                for j in 0..k {
                    a[r][j] = a[r][j].sub(&f.mul(&a[c][j]));
                    inv[r][j] = inv[r][j].sub(&f.mul(&inv[c][j]));
                }
            }
        }
        for (i, row) in inv.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e = self.name(format!("Dinv{tag}_{}{}", i + 1, j + 1), e.clone());
            }
        }
        Ok(inv)
    }
}

/// The spatial inertia at the origin of one body (see the module docs).
fn body_inertia(p: &crate::scene::MassProperties, s: usize) -> Sym {
    let m = &p.mass;
    let c = &p.centre;
    let mut i = vec![vec![Expr::zero(); s]; s];
    if s == 3 {
        let (x, y) = (&c[0], &c[1]);
        let j = match &p.turning {
            Some(Turning::Plane { inertia, .. }) => inertia.clone(),
            _ => Expr::zero(),
        };
        i[0][0] = j.add(&m.mul(&x.mul(x).add(&y.mul(y))));
        i[0][1] = m.mul(y).neg();
        i[0][2] = m.mul(x);
        i[1][1] = m.clone();
        i[2][2] = m.clone();
    } else {
        // I_g − m·[c]×[c]× = I_g + m·(|c|²·1 − c·cᵀ)
        let ig = match &p.turning {
            Some(Turning::Space { frame, inertia }) => {
                let r = frame.matrix();
                let mut out: [[Expr; 3]; 3] =
                    std::array::from_fn(|_| std::array::from_fn(|_| Expr::zero()));
                for a in 0..3 {
                    for b in 0..3 {
                        let mut e = Expr::zero();
                        for u in 0..3 {
                            for v in 0..3 {
                                if !inertia[u][v].is_zero() {
                                    e = e.add(&r[a][u].mul(&inertia[u][v]).mul(&r[b][v]));
                                }
                            }
                        }
                        out[a][b] = e;
                    }
                }
                out
            }
            _ => std::array::from_fn(|_| std::array::from_fn(|_| Expr::zero())),
        };
        let c2 = c.iter().fold(Expr::zero(), |s, x| s.add(&x.mul(x)));
        for a in 0..3 {
            for b in 0..3 {
                let mut e = ig[a][b].sub(&m.mul(&c[a]).mul(&c[b]));
                if a == b {
                    e = e.add(&m.mul(&c2));
                }
                i[a][b] = e;
            }
        }
        // m·[c]× above, its transpose below; m·1 at the bottom right
        let cx = skew(c);
        for a in 0..3 {
            for b in 0..3 {
                i[a][3 + b] = m.mul(&cx[a][b]);
                i[3 + b][a] = m.mul(&cx[a][b]);
            }
            i[3 + a][3 + a] = m.clone();
        }
    }
    i
}

/// [c]×, the matrix of c × ·.
fn skew(c: &[Expr]) -> [[Expr; 3]; 3] {
    let z = Expr::zero;
    [
        [z(), c[2].neg(), c[1].clone()],
        [c[2].clone(), z(), c[0].neg()],
        [c[1].neg(), c[0].clone(), z()],
    ]
}

/// ω × c (3D), or ω·(−c_y, c_x) in the plane (ω one component).
fn cross(w: &[Expr], c: &[Expr]) -> Vec<Expr> {
    if w.len() == 1 {
        return vec![w[0].mul(&c[1]).neg(), w[0].mul(&c[0])];
    }
    vec![
        w[1].mul(&c[2]).sub(&w[2].mul(&c[1])),
        w[2].mul(&c[0]).sub(&w[0].mul(&c[2])),
        w[0].mul(&c[1]).sub(&w[1].mul(&c[0])),
    ]
}

/// V ×* h: the rate of a momentum h carried by the velocity V.
fn force_cross(v: &[Expr], h: &[Expr]) -> Vec<Expr> {
    if v.len() == 3 {
        // (vx·fy − vy·fx, −ω·fy, ω·fx)
        return vec![
            v[1].mul(&h[2]).sub(&v[2].mul(&h[1])),
            v[0].mul(&h[2]).neg(),
            v[0].mul(&h[1]),
        ];
    }
    let (w, lin) = (&v[..3], &v[3..]);
    let (n, f) = (&h[..3], &h[3..]);
    let a = cross(w, n);
    let b = cross(lin, f);
    let mut out: Vec<Expr> = a.iter().zip(&b).map(|(x, y)| x.add(y)).collect();
    out.extend(cross(w, f));
    out
}

fn mat_vec(m: &Sym, v: &[Expr]) -> Vec<Expr> {
    m.iter().map(|row| dot(row, v)).collect()
}

fn dot(a: &[Expr], b: &[Expr]) -> Expr {
    a.iter().zip(b).fold(Expr::zero(), |s, (x, y)| {
        if x.is_zero() || y.is_zero() {
            s
        } else {
            s.add(&x.mul(y))
        }
    })
}

/// Compare the recursion's q̈ with M⁻¹·f at random states.
fn verify(tape: &Tape, lagrange: &Lagrange, acc: &[Expr]) -> Result<(), String> {
    let n = acc.len();
    let mut exprs: Vec<Expr> = lagrange.mass_matrix.iter().flatten().cloned().collect();
    exprs.extend(lagrange.forcing.iter().cloned());
    exprs.extend(acc.iter().cloned());
    let mut rng = crate::rng::SplitMix64::new(0xaba0_5eed);
    for _ in 0..PROBES {
        let seed = rng.next_u64();
        let values = tape
            .eval_many_f64(&exprs, &|a: &Atom| {
                Some(crate::rng::SplitMix64::keyed(seed, a).uniform(0.5, 1.5))
            })
            .ok_or("undefined at a random state")?;
        let m = nalgebra::DMatrix::from_row_slice(n, n, &values[..n * n]);
        let f = nalgebra::DVector::from_column_slice(&values[n * n..n * n + n]);
        let want = m.lu().solve(&f).ok_or("M is singular at a random state")?;
        let got = &values[n * n + n..];
        let scale = want.iter().fold(1.0f64, |s, x| s.max(x.abs()));
        let agree = want
            .iter()
            .zip(got)
            .all(|(a, b)| (a - b).abs() <= 1e-8 * scale);
        if !agree {
            return Err(
                "the recursion does not reproduce M⁻¹·f: the bodies are not a tree of rigid joints"
                    .into(),
            );
        }
    }
    Ok(())
}
