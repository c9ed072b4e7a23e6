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
    /// point, a possible change of branch, a stick, no convergence.
    pub note: Option<String>,
    /// The iterations the friction forces needed (0 without friction).
    pub iterations: u32,
    /// The drawing's points at this position, in ground coordinates
    /// (indexed by [`DrawnBody::points`] and [`DrawnJoint::point`]).
    pub points: Vec<[f64; 2]>,
}

/// Which kind of joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// A pin: two points of two bodies kept together.
    Pin,
    /// A slider: a point of one body kept on a line of the other.
    Slider,
}

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
