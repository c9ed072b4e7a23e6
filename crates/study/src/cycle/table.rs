//! What `qdot cycle` computes: one row per position of a mechanism's
//! cycle, and what is needed to draw the mechanism at each.

/// A mechanism analysed over its cycle: positions, velocities,
/// accelerations, then every joint's reaction and every drive's force.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleTable {
    /// The varied quantity (`phi` or `t`): the first column.
    pub varied: String,
    /// Every column's name, in order: the varied one; the coordinates;
    /// their velocities (`th'`); their accelerations (`th''`); the
    /// reactions joint by joint (`O_x`, `O_y`, `G_n`, `G_m`); the drives
    /// (`M`).
    pub columns: Vec<String>,
    /// The number of coordinates n: columns 1..=n are the coordinates,
    /// n+1..=2n their velocities, 2n+1..=3n their accelerations.
    pub coordinates: usize,
    /// The joints, in the scene's order, with their reaction columns.
    pub joints: Vec<JointColumns>,
    /// The drives, in the scene's order.
    pub drives: Vec<DriveColumn>,
    /// One row per position, in the order of the varied quantity.
    pub rows: Vec<CycleRow>,
    /// How to draw the mechanism from a row's points.
    pub drawing: Drawing,
}

/// One position of the cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleRow {
    /// One value per column; `None` where the position does not determine
    /// it (at a dead point, where a friction force's sense is undefined,
    /// or where the friction iteration did not converge).
    pub values: Vec<Option<f64>>,
    /// What is special about this position, when something is: a dead
    /// point, a possible change of branch, a stick, no convergence; every
    /// one that applies, joined by "; ".
    pub note: Option<String>,
    /// The iterations the friction forces needed (0 without friction).
    pub iterations: u32,
    /// The drawing's points at this position, in ground coordinates
    /// (indexed by [`DrawnBody::points`] and [`DrawnJoint::point`]).
    pub points: Vec<[f64; 2]>,
    /// Where a friction's relative velocity vanishes (a stick: its force
    /// anywhere in |F| ≤ μ·|N|), the reactions at both ends of that
    /// interval, the one-sided limits of sliding; `values` leaves the
    /// reactions out there.
    pub limits: Option<Box<StickLimits>>,
}

impl CycleRow {
    /// Add `note` after the ones the row has.
    pub fn add_note(&mut self, note: impl Into<String>) {
        let note = note.into();
        self.note = Some(match self.note.take() {
            Some(n) => format!("{n}; {note}"),
            None => note,
        });
    }
}

/// The reactions at a stick, at the two ends of its friction's interval.
#[derive(Clone, Debug, PartialEq)]
pub struct StickLimits {
    /// The joint whose relative velocity vanishes.
    pub joint: String,
    /// The row's values (every column) in the limit v_rel → 0⁻, sliding
    /// backwards: the friction at +μ·|N| (or +μ₀·r₀·|R|).
    pub minus: Vec<Option<f64>>,
    /// The limit v_rel → 0⁺: the friction at −μ·|N|.
    pub plus: Vec<Option<f64>>,
}

pub use crate::parse::ast::JointKind;

/// A joint and the columns of its reaction.
#[derive(Clone, Debug, PartialEq)]
pub struct JointColumns {
    /// The joint's name.
    pub name: String,
    /// Pin or slider.
    pub kind: JointKind,
    /// The two bodies it joins (`None` for the ground), as written: the
    /// reaction is the force on the second from the first.
    pub bodies: [Option<String>; 2],
    /// Its reaction's columns in [`CycleTable::columns`]: `NAME_x`,
    /// `NAME_y` for a pin; `NAME_n` (and `NAME_m`) for a slider.
    pub columns: Vec<usize>,
    /// Whether the joint has Coulomb friction.
    pub friction: bool,
}

/// A drive and its column.
#[derive(Clone, Debug, PartialEq)]
pub struct DriveColumn {
    /// The drive's name: its column is the generalized force it applies.
    pub name: String,
    /// The driven coordinate.
    pub coordinate: String,
    /// Its column in [`CycleTable::columns`].
    pub column: usize,
}

/// The mechanism as lines and points, for diagrams and animation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Drawing {
    /// Every body and particle.
    pub bodies: Vec<DrawnBody>,
    /// Every joint.
    pub joints: Vec<DrawnJoint>,
}

/// A body drawn as the polygon through its points.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnBody {
    /// The body's name.
    pub name: String,
    /// True for a particle (drawn as a block), false for a rigid body.
    pub particle: bool,
    /// Its centre of mass first, then the points of its joints, as
    /// indices into [`CycleRow::points`].
    pub points: Vec<usize>,
}

/// A joint drawn at its point.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnJoint {
    /// The joint's name.
    pub name: String,
    /// Pin or slider.
    pub kind: JointKind,
    /// Its point (on the second body) in [`CycleRow::points`].
    pub point: usize,
    /// True when one of its bodies is the ground (drawn as a support).
    pub grounded: bool,
    /// A slider's guide: the index of the point one unit along the guide
    /// from the guide's point on the first body (the line is drawn
    /// through both); `None` for a pin.
    pub guide: Option<[usize; 2]>,
}

/// Where each quantity goes in a row.
pub(super) struct Layout {
    /// Every column's name.
    pub columns: Vec<String>,
    /// The column of each constraint's multiplier, by constraint index.
    pub multiplier: Vec<usize>,
    /// The column of each friction, in the order of the joints that have one.
    pub friction: Vec<usize>,
    /// The joints' columns.
    pub joints: Vec<JointColumns>,
    /// The drives' columns.
    pub drives: Vec<DriveColumn>,
}

impl Layout {
    /// The columns of `scene` varied over `varied`: the varied name; q,
    /// q̇, q̈; the joints' reactions; the drives; the multipliers of the
    /// `constraint` statements; the frictions.
    pub fn of(scene: &crate::scene::Scene, varied: &str) -> Layout {
        let mut columns = vec![varied.to_string()];
        for order in ["", "'", "''"] {
            columns.extend(
                scene
                    .coordinates
                    .iter()
                    .map(|c| format!("{}{order}", c.name)),
            );
        }
        let mut multiplier = vec![usize::MAX; scene.constraints.len()];
        let body = |b: Option<usize>| b.map(|b| scene.bodies[b].name.clone());
        let mut joints = Vec::new();
        for jt in &scene.joints {
            let mut cols = Vec::new();
            for (&j, name) in jt.constraints.iter().zip(jt.reaction_names()) {
                multiplier[j] = columns.len();
                cols.push(columns.len());
                columns.push(name);
            }
            joints.push(JointColumns {
                name: jt.name.clone(),
                kind: jt.kind,
                bodies: [body(jt.bodies[0]), body(jt.bodies[1])],
                columns: cols,
                friction: jt.friction.is_some(),
            });
        }
        let mut drives = Vec::new();
        for d in &scene.drives {
            multiplier[d.constraint] = columns.len();
            drives.push(DriveColumn {
                name: d.name.clone(),
                coordinate: scene.coordinates[d.coordinate].name.clone(),
                column: columns.len(),
            });
            columns.push(d.name.clone());
        }
        for (j, c) in scene.constraints.iter().enumerate() {
            if multiplier[j] == usize::MAX {
                multiplier[j] = columns.len();
                columns.push(c.multiplier.clone());
            }
        }
        let mut friction = Vec::new();
        for jt in &scene.joints {
            if let Some(f) = &jt.friction {
                friction.push(columns.len());
                columns.push(f.unknown.clone());
            }
        }
        Layout {
            columns,
            multiplier,
            friction,
            joints,
            drives,
        }
    }
}

impl CycleTable {
    /// The table with only the columns `names` after the varied one, in
    /// the order given (`--columns O_x,O_y,M`).
    pub fn select(&self, names: &[String]) -> Result<CycleTable, crate::diag::Diagnostic> {
        let mut keep = vec![0];
        for name in names {
            let Some(k) = self.columns.iter().skip(1).position(|c| c == name) else {
                return Err(crate::diag::Diagnostic::global(format!(
                    "`--columns {name}`: the table has no column `{name}`"
                ))
                .with_hint(format!("the columns are {}", self.columns[1..].join(", ")))
                .with_kind(crate::diag::ErrorKind::bad_option("--columns")));
            };
            keep.push(k + 1);
        }
        let mut out = self.clone();
        out.columns = keep.iter().map(|&k| self.columns[k].clone()).collect();
        for row in &mut out.rows {
            row.values = keep.iter().map(|&k| row.values[k]).collect();
            if let Some(l) = row.limits.as_mut() {
                l.minus = keep.iter().map(|&k| l.minus[k]).collect();
                l.plus = keep.iter().map(|&k| l.plus[k]).collect();
            }
        }
        Ok(out)
    }

    /// The table with every stick row written as two rows at the same
    /// position, its two limits of sliding (the one that continues the
    /// previous row first), each row's note saying which: what a
    /// diagram draws (a jump, not a hole) and CSV writes.
    pub fn stick_rows_split(&self) -> CycleTable {
        let mut out = self.clone();
        out.rows.clear();
        let mut previous: Option<&Vec<Option<f64>>> = None;
        for row in &self.rows {
            let Some(limits) = &row.limits else {
                out.rows.push(row.clone());
                previous = Some(&row.values);
                continue;
            };
            // the side nearer the previous row in the columns where the
            // sides differ (the reactions) comes first
            let distance = |side: &[Option<f64>]| -> f64 {
                let Some(p) = previous else { return 0.0 };
                (0..side.len())
                    .filter(|&k| limits.minus.get(k) != limits.plus.get(k))
                    .filter_map(|k| Some((p.get(k).copied().flatten()?, side[k]?)))
                    .map(|(a, b)| (a - b).abs() / a.abs().max(b.abs()).max(f64::MIN_POSITIVE))
                    .sum()
            };
            let mut sides = [("v → 0⁻", &limits.minus), ("v → 0⁺", &limits.plus)];
            if distance(&limits.plus) < distance(&limits.minus) {
                sides.swap(0, 1);
            }
            for (name, values) in sides {
                let mut line = row.clone();
                line.values = values.clone();
                line.limits = None;
                line.add_note(format!("this line: the limit {name}"));
                out.rows.push(line);
            }
            previous = Some(sides[1].1);
        }
        out
    }
}
