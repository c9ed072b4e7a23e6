//! `qdot cycle` in other units (issue 46, acceptance 3): random
//! slider-cranks and four-bars (Grashof or not, with friction) in m, mm
//! and km, grams or tonnes, seconds or milliseconds give the same
//! verdicts (every note, numbers aside; which values are determined) and
//! the values scaled: lengths ×L, velocities ×L/T, forces ×M·L/T²,
//! moments ×M·L²/T².

use proptest::prelude::*;
use qdot::cycle::{cycle, CycleRequest, CycleTable, Over};
use qdot::Scene;

const SLIDER_CRANK: &str = "\
coordinates x1, y1, phi, x2, y2, th, xb, yb
parameters r, l, e, omega, m1, J1, m2, J2, m3, g, mu
body crank: mass m1, inertia J1, angle phi, at [x1, y1]
body rod: mass m2, inertia J2, angle th, at [x2, y2]
particle block: mass m3, at [xb, yb]
gravity [0, -g]
joint O: pin ground at [0, 0], crank at [x1, y1] - r/2*[cos(phi), sin(phi)]
joint A: pin crank at [x1, y1] + r/2*[cos(phi), sin(phi)], rod at [x2, y2] - l/2*[cos(th), sin(th)]
joint B: pin rod at [x2, y2] + l/2*[cos(th), sin(th)], block at [xb, yb]
joint G: slider ground at [0, e], block at [xb, yb] along [1, 0]
drive M: phi = omega*t
friction G: mu
";

const FOUR_BAR: &str = "\
coordinates x2, y2, th2, x3, y3, th3, x4, y4, th4
parameters a, b, c, d, omega, m, J, g, f
body crank: mass m, inertia J, angle th2, at [x2, y2]
body coupler: mass m, inertia J, angle th3, at [x3, y3]
body rocker: mass m, inertia J, angle th4, at [x4, y4]
gravity [0, -g]
joint O2: pin ground at [0, 0], crank at [x2, y2] - a/2*[cos(th2), sin(th2)]
joint A: pin crank at [x2, y2] + a/2*[cos(th2), sin(th2)], coupler at [x3, y3] - b/2*[cos(th3), sin(th3)]
joint B: pin coupler at [x3, y3] + b/2*[cos(th3), sin(th3)], rocker at [x4, y4] + c/2*[cos(th4), sin(th4)]
joint O4: pin ground at [d, 0], rocker at [x4, y4] - c/2*[cos(th4), sin(th4)]
drive M: th2 = omega*t
friction B: f
";

/// A unit system: the numbers of lengths ×l, of masses ×m, of times ×t.
#[derive(Clone, Copy, Debug)]
struct Units {
    l: f64,
    m: f64,
    t: f64,
}

const UNITS: [Units; 4] = [
    Units {
        l: 1.0,
        m: 1.0,
        t: 1.0,
    },
    Units {
        l: 1e3,
        m: 1e3,
        t: 1.0,
    },
    Units {
        l: 1e-3,
        m: 1e-3,
        t: 1e3,
    },
    Units {
        l: 1e3,
        m: 1.0,
        t: 1e-3,
    },
];

/// What a value is made of: lengths, masses and times to the powers.
#[derive(Clone, Copy, PartialEq)]
struct Dim(i32, i32, i32);

impl Dim {
    fn factor(self, u: Units) -> f64 {
        u.l.powi(self.0) * u.m.powi(self.1) * u.t.powi(self.2)
    }
}

const ONE: Dim = Dim(0, 0, 0);
const LENGTH: Dim = Dim(1, 0, 0);
const MASS: Dim = Dim(0, 1, 0);
const FORCE: Dim = Dim(1, 1, -2);
const MOMENT: Dim = Dim(2, 1, -2);
const INERTIA: Dim = Dim(2, 1, 0);
const RATE: Dim = Dim(0, 0, -1);
const ACCELERATION: Dim = Dim(1, 0, -2);

/// A mechanism: its scene, its parameters with their dimensions, its
/// angles, its guess (in SI), and its reactions' dimensions by column.
struct Mechanism {
    scene: &'static str,
    set: Vec<(&'static str, f64, Dim)>,
    angles: &'static [&'static str],
    guess: Vec<(&'static str, f64)>,
    moments: &'static [&'static str],
}

fn request(mech: &Mechanism, u: Units, phase: f64, count: usize) -> CycleRequest {
    let varied = if mech.scene == SLIDER_CRANK {
        "phi"
    } else {
        "th2"
    };
    CycleRequest {
        over: Over {
            name: varied.into(),
            from: phase,
            to: phase + std::f64::consts::TAU,
            count,
        },
        set: mech
            .set
            .iter()
            .map(|(k, v, d)| ((*k).to_string(), v * d.factor(u)))
            .collect(),
        guess: mech
            .guess
            .iter()
            .map(|(k, v)| {
                let scale = if mech.angles.contains(k) { 1.0 } else { u.l };
                ((*k).to_string(), v * scale)
            })
            .collect(),
    }
}

/// A column's dimension.
fn dimension(mech: &Mechanism, t: &CycleTable, k: usize) -> Dim {
    let n = t.coordinates;
    if k == 0 {
        return ONE;
    }
    let name = &t.columns[k];
    if k <= 3 * n {
        let q = name.trim_end_matches('\'');
        let order = (name.len() - q.len()) as i32;
        let base = if mech.angles.contains(&q) { 0 } else { 1 };
        return Dim(base, 0, -order);
    }
    if mech.moments.contains(&name.as_str()) {
        MOMENT
    } else {
        FORCE
    }
}

/// A note with its numbers left out.
fn words(note: &Option<String>) -> Option<String> {
    note.as_ref().map(|n| {
        n.split(' ')
            .map(|w| {
                if w.chars().any(|c| c.is_ascii_digit()) {
                    "#"
                } else {
                    w
                }
            })
            .collect::<Vec<_>>()
            .join(" ")
    })
}

fn run(mech: &Mechanism, u: Units, phase: f64, count: usize) -> Result<CycleTable, String> {
    let scene = Scene::parse(mech.scene).map_err(|d| d.message.clone())?;
    cycle(&scene, &request(mech, u, phase, count)).map_err(|d| d.message.clone())
}

/// The same verdicts and the values scaled, in every unit system.
fn check(mech: &Mechanism, phase: f64, count: usize) -> Result<(), TestCaseError> {
    let base = run(mech, UNITS[0], phase, count);
    for &u in &UNITS[1..] {
        let other = run(mech, u, phase, count);
        let (base, other) = match (&base, &other) {
            (Ok(b), Ok(o)) => (b, o),
            (Err(_), Err(_)) => continue,
            _ => {
                return Err(TestCaseError::fail(format!(
                    "{u:?}: one run refused: {:?} / {:?}",
                    base.as_ref().err(),
                    other.as_ref().err()
                )))
            }
        };
        prop_assert_eq!(base.rows.len(), other.rows.len());
        let columns = base.columns.len();
        // the largest of each column over the table, for rounding noise
        let largest: Vec<f64> = (0..columns)
            .map(|k| {
                base.rows
                    .iter()
                    .flat_map(|r| {
                        let l = r.limits.as_deref();
                        [
                            Some(r.values[k]),
                            l.map(|l| l.minus[k]),
                            l.map(|l| l.plus[k]),
                        ]
                    })
                    .flatten()
                    .flatten()
                    .fold(0.0f64, |m, x| m.max(x.abs()))
            })
            .collect();
        // rounding noise is measured against the values of the same kind
        let largest: Vec<f64> = (0..columns)
            .map(|k| {
                let d = dimension(mech, base, k);
                (0..columns)
                    .filter(|&j| dimension(mech, base, j) == d)
                    .fold(0.0f64, |m, j| m.max(largest[j]))
            })
            .collect();
        for (i, (b, o)) in base.rows.iter().zip(&other.rows).enumerate() {
            prop_assert_eq!(words(&b.note), words(&o.note), "{:?}, row {}", u, i);
            prop_assert_eq!(b.limits.is_some(), o.limits.is_some(), "{:?}, row {}", u, i);
            let mut pairs = vec![(&b.values, &o.values)];
            if let (Some(bl), Some(ol)) = (b.limits.as_deref(), o.limits.as_deref()) {
                pairs.push((&bl.minus, &ol.minus));
                pairs.push((&bl.plus, &ol.plus));
            }
            for (bv, ov) in pairs {
                for k in 0..columns {
                    prop_assert_eq!(
                        bv[k].is_some(),
                        ov[k].is_some(),
                        "{:?}, row {}, `{}`",
                        u,
                        i,
                        &base.columns[k]
                    );
                    if let (Some(x), Some(y)) = (bv[k], ov[k]) {
                        let f = dimension(mech, base, k).factor(u);
                        let want = x * f;
                        prop_assert!(
                            (y - want).abs() <= 1e-7 * largest[k] * f,
                            "{:?}, row {}, `{}`: {} against {} ×{}",
                            u,
                            i,
                            &base.columns[k],
                            y,
                            x,
                            f
                        );
                    }
                }
            }
        }
    }
    Ok(())
}

fn slider_crank(r: f64, l: f64, e: f64, mu: f64, masses: [f64; 3], phase: f64) -> Mechanism {
    // the first position on the branch with the block to the right
    let a = [r * phase.cos(), r * phase.sin()];
    let h = e - a[1];
    let xb = a[0] + (l * l - h * h).max(0.0).sqrt();
    let th = h.atan2(xb - a[0]);
    Mechanism {
        scene: SLIDER_CRANK,
        set: vec![
            ("r", r, LENGTH),
            ("l", l, LENGTH),
            ("e", e, LENGTH),
            ("omega", 10.0, RATE),
            ("m1", masses[0], MASS),
            ("J1", masses[0] * r * r / 12.0, INERTIA),
            ("m2", masses[1], MASS),
            ("J2", masses[1] * l * l / 12.0, INERTIA),
            ("m3", masses[2], MASS),
            ("g", 9.81, ACCELERATION),
            ("mu", mu, ONE),
        ],
        angles: &["phi", "th"],
        guess: vec![
            ("phi", phase),
            ("x1", a[0] / 2.0),
            ("y1", a[1] / 2.0),
            ("th", th),
            ("x2", (a[0] + xb) / 2.0),
            ("y2", (a[1] + e) / 2.0),
            ("xb", xb),
            ("yb", e),
        ],
        moments: &["M"],
    }
}

fn four_bar(len: [f64; 4], f: f64, phase: f64) -> Option<Mechanism> {
    let [a, b, c, d] = len;
    let pa = [a * phase.cos(), a * phase.sin()];
    let v = [d - pa[0], -pa[1]];
    let dist = v[0].hypot(v[1]);
    let along = (b * b - c * c + dist * dist) / (2.0 * dist);
    let h2 = b * b - along * along;
    if h2 <= 1e-4 * b * b {
        return None;
    }
    let h = h2.sqrt();
    let u = [v[0] / dist, v[1] / dist];
    let pb = [
        pa[0] + along * u[0] - h * u[1],
        pa[1] + along * u[1] + h * u[0],
    ];
    let th3 = (pb[1] - pa[1]).atan2(pb[0] - pa[0]);
    let th4 = pb[1].atan2(pb[0] - d);
    Some(Mechanism {
        scene: FOUR_BAR,
        set: vec![
            ("a", a, LENGTH),
            ("b", b, LENGTH),
            ("c", c, LENGTH),
            ("d", d, LENGTH),
            ("omega", 10.0, RATE),
            ("m", 1.0, MASS),
            ("J", 0.01, INERTIA),
            ("g", 9.81, ACCELERATION),
            ("f", f, LENGTH),
        ],
        angles: &["th2", "th3", "th4"],
        guess: vec![
            ("th2", phase),
            ("x2", pa[0] / 2.0),
            ("y2", pa[1] / 2.0),
            ("th3", th3),
            ("x3", (pa[0] + pb[0]) / 2.0),
            ("y3", (pa[1] + pb[1]) / 2.0),
            ("th4", th4),
            ("x4", (pb[0] + d) / 2.0),
            ("y4", pb[1] / 2.0),
        ],
        moments: &["M", "B_f"],
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// Slider-cranks: a rod longer than crank and offset (a whole turn)
    /// or shorter (positions that cannot be assembled), with friction on
    /// the guide (sticks at the dead centres).
    #[test]
    fn a_slider_crank_has_the_same_verdicts_in_every_unit(
        r in 0.05f64..0.2,
        ratio in 0.6f64..4.0,
        offset in -0.3f64..0.3,
        mu in prop_oneof![Just(0.0), 0.05f64..0.6],
        masses in prop::array::uniform3(0.2f64..3.0),
        phase in 0.01f64..0.3,
    ) {
        let (l, e) = (r * ratio, r * offset);
        prop_assume!(l > (e.abs() + r * phase.sin().abs()) * 1.05);
        check(&slider_crank(r, l, e, mu, masses, phase), phase, 9)?;
    }

    /// Four-bars, Grashof or not, with a friction couple in the pin B.
    #[test]
    fn a_four_bar_has_the_same_verdicts_in_every_unit(
        len in prop::array::uniform4(0.05f64..0.3),
        f in prop_oneof![Just(0.0), 0.0005f64..0.01],
        phase in 0.01f64..0.3,
    ) {
        let mech = four_bar(len, f, phase);
        prop_assume!(mech.is_some());
        check(&mech.unwrap(), phase, 9)?;
    }
}
