//! Scene generators for families of systems (used by the benchmarks, the
//! tests and the book): the n-link planar pendulum of ../shared/anchors,
//! and the list of bundled seed examples.

/// The seed problems bundled as `examples/NAME.qd` (../shared/problems.md).
pub const SEED_EXAMPLES: &[&str] = &[
    "seed_21_1",
    "seed_21_1_kinetostatic",
    "seed_21_2",
    "seed_21_2_kinetostatic",
    "seed_22_2",
    "seed_22_2_kinetostatic",
    "seed_22_2_lagrange",
    "seed_22_3",
    "seed_23_1",
    "seed_23_2",
    "seed_23_3",
    "seed_23_4",
    "seed_24_1",
    "seed_24_2",
];

/// The n-link planar pendulum chain with equal masses `m` and lengths `l`,
/// coordinates `q1 … qn` (angles from the downward vertical), written with
/// positions as a kinematic table — the scene of the anchors'
/// `sympy_npendulum.py` and `symengine_npendulum.py`.
pub fn pendulum_chain(n: usize) -> String {
    let mut s = String::new();
    let qs: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
    s.push_str(&format!("# {n}-link planar pendulum chain\n"));
    s.push_str(&format!("coordinates {}\n", qs.join(", ")));
    s.push_str("parameters m, l, g\n");
    for i in 1..=n {
        if i == 1 {
            s.push_str("x1 = l*sin(q1)\ny1 = -l*cos(q1)\n");
        } else {
            let p = i - 1;
            s.push_str(&format!(
                "x{i} = x{p} + l*sin(q{i})\ny{i} = y{p} - l*cos(q{i})\n"
            ));
        }
        s.push_str(&format!("kinetic E{i} = 1/2*m*(x{i}'^2 + y{i}'^2)\n"));
        s.push_str(&format!("potential V{i} = m*g*y{i}\n"));
    }
    s
}

/// The n-link planar pendulum chain of [`pendulum_chain`] written with
/// `particle` statements and `gravity`: the same equations, read by qdot
/// as a tree of bodies (the articulated-body recursion applies).
pub fn particle_chain(n: usize) -> String {
    let qs: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
    let mut s = format!("# {n}-link planar pendulum chain of particles\n");
    s.push_str(&format!("coordinates {}\n", qs.join(", ")));
    s.push_str("parameters m, l, g\n");
    for i in 1..=n {
        let link = format!("l*[sin(q{i}), -cos(q{i})]");
        if i == 1 {
            s.push_str(&format!("P1 = {link}\n"));
        } else {
            s.push_str(&format!("P{i} = P{} + {link}\n", i - 1));
        }
        s.push_str(&format!("particle p{i}: mass m, at P{i}\n"));
    }
    s.push_str("gravity [0, -g]\n");
    s
}

/// A chain of `n` rods in space, each hinged to the end of the one above
/// about an axis turned with it (x, y, x, y, …): n rigid bodies with
/// principal moments [A, A, C], the benchmark of frames and bodies
/// (`scripts/anchor_frames.py` builds the same system in SymPy).
pub fn rod_chain_3d(n: usize) -> String {
    let mut s = format!("# {n} rods in space, hinged about alternating x and y axes\n");
    let qs: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
    s.push_str(&format!("coordinates {}\n", qs.join(", ")));
    s.push_str("parameters m, A, C, l, g\n");
    for i in 1..=n {
        let axis = if i % 2 == 1 { "x" } else { "y" };
        if i == 1 {
            s.push_str(&format!("frame B1 = rot({axis}, q1)\n"));
            s.push_str("body b1: mass m, inertia [A, A, C], frame B1, at -l/2*axis(B1, 3)\n");
            s.push_str("P1 = -l*axis(B1, 3)\n");
        } else {
            let p = i - 1;
            s.push_str(&format!("frame B{i} = B{p} * rot({axis}, q{i})\n"));
            s.push_str(&format!(
                "body b{i}: mass m, inertia [A, A, C], frame B{i}, at P{p} - l/2*axis(B{i}, 3)\n"
            ));
            s.push_str(&format!("P{i} = P{p} - l*axis(B{i}, 3)\n"));
        }
    }
    s.push_str("gravity [0, 0, -g]\n");
    s
}
