//! A hand-built cycle table for the pictures' tests: the slider-crank
//! of issue 36 (crank R = 1 about O, rod L = 3, block on a horizontal
//! guide through O, a spring k (xb − l0) on the block), its links
//! massless, so each reaction follows from statics in a few lines.
// A test module: compiled only under #[cfg(test)] (its parent's `mod` line).

use crate::cycle::*;

const R: f64 = 1.0;
const L: f64 = 3.0;
const K: f64 = 10.0;
const L0: f64 = 3.0;

/// The varied column, the 8 coordinates, their velocities and
/// accelerations (unused by the pictures: `None`), the reactions, the
/// drive.
fn columns() -> Vec<String> {
    let q = ["x1", "y1", "phi", "x2", "y2", "th", "xb", "yb"];
    let mut c = vec!["phi".to_string()];
    c.extend(q.iter().map(|s| s.to_string()));
    c.extend(q.iter().map(|s| format!("{s}'")));
    c.extend(q.iter().map(|s| format!("{s}''")));
    for r in ["O_x", "O_y", "A_x", "A_y", "B_x", "B_y", "G_n", "M"] {
        c.push(r.into());
    }
    c
}

/// One position: its values and its drawing's points.
fn row(phi: f64) -> CycleRow {
    let a = [R * phi.cos(), R * phi.sin()];
    let xb = a[0] + (L * L - a[1] * a[1]).sqrt();
    let th = (-a[1]).atan2(xb - a[0]);
    let (ex, ey) = (th.cos(), th.sin());
    // the spring pushes the block: the rod (a two-force member) holds it
    // along e, the guide across
    let bx = K * (xb - L0);
    let by = bx / ex * ey;
    let (gn, (ax, ay), (ox, oy)) = (-by, (bx, by), (bx, by));
    let m = a[0] * ay - a[1] * ax;
    let mid = [(a[0] + xb) / 2.0, a[1] / 2.0];
    let mut values = vec![Some(phi)];
    let q = [0.0, 0.0, phi, mid[0], mid[1], th, xb, 0.0];
    values.extend(q.iter().map(|v| Some(*v)));
    values.extend(std::iter::repeat_n(None, 16));
    values.extend([ox, oy, ax, ay, bx, by, gn, m].map(Some));
    let b = [xb, 0.0];
    CycleRow {
        values,
        note: None,
        iterations: 0,
        limits: None,
        // crank: centre, O, A; rod: centre, A, B; block: centre, B, G;
        // the guide: its point and one unit along it
        points: vec![
            [0.0, 0.0],
            [0.0, 0.0],
            a,
            mid,
            a,
            [a[0] + L * ex, a[1] + L * ey],
            b,
            b,
            b,
            [0.0, 0.0],
            [1.0, 0.0],
        ],
    }
}

fn joint(
    name: &str,
    kind: JointKind,
    bodies: [Option<&str>; 2],
    columns: &[usize],
) -> JointColumns {
    JointColumns {
        name: name.into(),
        kind,
        bodies: bodies.map(|b| b.map(str::to_string)),
        columns: columns.to_vec(),
        friction: false,
    }
}

fn drawn(
    name: &str,
    kind: JointKind,
    point: usize,
    grounded: bool,
    guide: Option<[usize; 2]>,
) -> DrawnJoint {
    DrawnJoint {
        name: name.into(),
        kind,
        point,
        grounded,
        guide,
    }
}

/// The slider-crank over φ = 0…360° in steps of 30°.
pub fn slider_crank() -> CycleTable {
    slider_crank_at(13)
}

/// The slider-crank at `rows` evenly spaced φ from 0 to 360°.
pub fn slider_crank_at(rows: usize) -> CycleTable {
    use JointKind::{Pin, Slider};
    let body = |name: &str, particle, points: &[usize]| DrawnBody {
        name: name.into(),
        particle,
        points: points.to_vec(),
    };
    CycleTable {
        varied: "phi".into(),
        columns: columns(),
        coordinates: 8,
        joints: vec![
            joint("O", Pin, [None, Some("crank")], &[25, 26]),
            joint("A", Pin, [Some("crank"), Some("rod")], &[27, 28]),
            joint("B", Pin, [Some("rod"), Some("block")], &[29, 30]),
            joint("G", Slider, [None, Some("block")], &[31]),
        ],
        drives: vec![DriveColumn {
            name: "M".into(),
            coordinate: "phi".into(),
            column: 32,
        }],
        rows: (0..rows)
            .map(|k| row(k as f64 * std::f64::consts::TAU / (rows - 1) as f64))
            .collect(),
        drawing: Drawing {
            bodies: vec![
                body("crank", false, &[0, 1, 2]),
                body("rod", false, &[3, 4, 5]),
                body("block", true, &[6, 7, 8]),
            ],
            joints: vec![
                drawn("O", Pin, 1, true, None),
                drawn("A", Pin, 4, false, None),
                drawn("B", Pin, 7, false, None),
                drawn("G", Slider, 8, true, Some([9, 10])),
            ],
        },
    }
}

/// The same with the reactions and the drive unknown at row `k` (a dead
/// point), noted.
pub fn with_dead_point(k: usize) -> CycleTable {
    let mut t = slider_crank();
    for v in &mut t.rows[k].values[25..] {
        *v = None;
    }
    t.rows[k].note = Some("dead point: the constraints' Jacobian is singular".into());
    t
}

#[test]
fn the_fixture_closes_its_loop_and_balances_the_crank() {
    let t = slider_crank();
    assert_eq!(t.columns.len(), 33);
    assert_eq!(t.columns[32], "M");
    for r in &t.rows {
        assert_eq!(r.values.len(), 33);
        // the rod's far end is the block's point
        let (b, on_rod) = (r.points[6], r.points[5]);
        assert!((b[0] - on_rod[0]).abs() < 1e-12 && (b[1] - on_rod[1]).abs() < 1e-12);
    }
    // at φ = 90°: A = (0, 1), xb = √8, the spring's force 10(√8 − 3)
    let r = &t.rows[3];
    let bx = 10.0 * (8f64.sqrt() - 3.0);
    assert!((r.values[29].unwrap() - bx).abs() < 1e-12);
    // M = −A_x (the rod pulls A sideways at the crank's top)
    assert!((r.values[32].unwrap() + bx).abs() < 1e-12);
}
