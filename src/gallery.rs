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
