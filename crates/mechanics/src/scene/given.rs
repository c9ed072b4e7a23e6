//! Values given for a scene's names outside the scene: `--set m=1,g=9.81`
//! (parameters, as doubles), `--at th=pi` and `--init y=1/10,y'=0` (exact
//! expressions), the simulator's `--init th=0.5,th'=0` (doubles), and the
//! ranges of `--over` and `--vary` (`phi=0:360deg:73`). One reader of
//! `name=value,…` lists, one of ranges ([`parse_ranges`]) and one
//! evaluator of numeric values ([`constant_value`]: `30deg`, `2*pi`) serve
//! them all, so they accept the same syntax and refuse it with the same
//! messages.

use super::Scene;
use crate::algebra::sign::Values;
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::Expr;

/// How an option is written, for its messages.
#[derive(Clone, Copy, Debug)]
pub struct OptionSyntax {
    /// `--set`
    pub option: &'static str,
    /// A whole example: `--set m=1,g=9.81,l=0.5`.
    pub example: &'static str,
    /// The hint for a name given twice.
    pub once: Option<&'static str>,
}

/// The syntax of `--set m=1,g=9.81`: parameter values (doubles).
pub const SET: OptionSyntax = OptionSyntax {
    option: "--set",
    example: "--set m=1,g=9.81,l=0.5",
    once: Some("give each parameter one value"),
};
/// The syntax of `--at th=pi`: coordinate values (exact expressions).
pub const AT: OptionSyntax = OptionSyntax {
    option: "--at",
    example: "--at th=pi, --init y1=1/10,y1'=0",
    once: Some("give each coordinate one value"),
};
/// The syntax of `--init y=1/10,y'=0`: positions and velocities (exact expressions).
pub const INIT: OptionSyntax = OptionSyntax {
    option: "--init",
    example: "--at th=pi, --init y1=1/10,y1'=0",
    once: Some("give each position and velocity one value"),
};
/// The syntax of the simulator's `--init theta=0.5,theta'=0`: initial q and
/// q̇ (doubles).
pub const SIMULATE_INIT: OptionSyntax = OptionSyntax {
    option: "--init",
    example: "--init theta=0.5,theta'=0",
    once: Some("give each position and velocity one value"),
};

/// One `name=value` item: as written (trimmed), its name and its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NameValue<'s> {
    /// The whole item, trimmed (`y' = 0`).
    pub written: &'s str,
    /// The name before `=`, trimmed (`y'`).
    pub name: &'s str,
    /// The value after `=`, trimmed (`0`).
    pub value: &'s str,
}

/// `a=1, b = 2,,c=x` as its items, trimmed: empty items are skipped; an
/// item without `=` or without a name, or a name given twice, is refused.
/// A comma inside parentheses belongs to its value (`a=atan2(1, 2)`).
pub fn name_value_pairs(syntax: OptionSyntax, s: &str) -> Result<Vec<NameValue<'_>>, Diagnostic> {
    let mut out: Vec<NameValue<'_>> = Vec::new();
    for part in top_level_items(s)
        .into_iter()
        .map(str::trim)
        .filter(|p| !p.is_empty())
    {
        let Some((k, v)) = part.split_once('=').filter(|(k, _)| !k.trim().is_empty()) else {
            return Err(Diagnostic::global(format!(
                "`{} {part}`: expected name=value",
                syntax.option
            ))
            .with_hint(format!("for example {}", syntax.example))
            .with_kind(ErrorKind::bad_option(syntax.option)));
        };
        let k = k.trim();
        if out.iter().any(|nv| nv.name == k) {
            let d = Diagnostic::global(format!("`{}`: `{k}` is given twice", syntax.option))
                .with_kind(ErrorKind::bad_option(syntax.option));
            return Err(match syntax.once {
                Some(h) => d.with_hint(h),
                None => d,
            });
        }
        out.push(NameValue {
            written: part,
            name: k,
            value: v.trim(),
        });
    }
    Ok(out)
}

/// Parse `--set m=1,g=9.81` into parameter values: finite, positive doubles.
pub fn parameter_values(s: &str) -> Result<Values, Diagnostic> {
    let out = parameter_values_any_sign(s)?;
    for (k, &v) in &out {
        if v <= 0.0 {
            return Err(not_positive(k, v));
        }
    }
    Ok(out)
}

/// The error for `--set k=v` with v ≤ 0 for a positive parameter.
fn not_positive(k: &str, v: f64) -> Diagnostic {
    let d = Diagnostic::global(format!(
        "`--set {k}={v}`: parameters are positive, and {v} is not"
    ))
    .with_kind(ErrorKind::bad_option(SET.option));
    if v == 0.0 {
        // the exact results were derived for k > 0 (a damping's verdict
        // "asymptotically stable" among them): k = 0 is re-derived only
        // when the scene lets k take any sign
        return d.with_hint(format!(
            "exact results are derived for {k} > 0; with `assume {k} real` in the scene they are derived for any {k}, its sign taken from the value (the numeric commands, `simulate`, `sweep`, `cycle`, `floquet`, `response --over`, take {k}=0 where {k} is not in the mass matrix)"
        ));
    }
    d.with_hint(format!(
        "qdot takes every parameter to be positive; write a negative quantity as −{k} in the scene, or `assume {k} real`"
    ))
}

/// The error for `--set k=0` in a numeric command, `k` being in the mass
/// matrix or a constraint (`where`).
fn zero_in_inertia(k: &str) -> Diagnostic {
    Diagnostic::global(format!(
        "`--set {k}=0`: {k} is in the mass matrix or a constraint, where 0 can make the equations singular (a massless body, a rod of no length)"
    ))
    .with_hint(format!(
        "give {k} a positive value, or write the scene without what it measures"
    ))
    .with_kind(ErrorKind::bad_option(SET.option))
}

/// The parameters a numeric run cannot take as 0: those of the mass matrix
/// and of the constraints' coefficients (read through `lag`'s
/// intermediates). At 0 the system can be singular, and the equations,
/// derived and cancelled for positive parameters, would give their limit
/// instead of saying so. Everywhere else (a damping, a stiffness, a load)
/// the compiled equations are rational in the parameter and their value
/// at 0 is the scene's.
pub fn inertial_parameters(scene: &Scene, lag: &crate::mechanics::Lagrange) -> Vec<String> {
    let roots: Vec<&Expr> = lag
        .mass_matrix
        .iter()
        .flatten()
        .chain(lag.constraints.matrix.iter().flatten())
        .collect();
    let used: Vec<&Expr> = match &lag.intermediates {
        Some(tape) => tape
            .used_by(roots.iter().copied())
            .into_iter()
            .map(|i| &tape.entries()[i].value)
            .collect(),
        None => Vec::new(),
    };
    scene
        .parameters
        .iter()
        .filter(|p| {
            let v = crate::expr::atom::param(&p.name);
            roots.iter().chain(&used).any(|e| e.depends_on(v))
        })
        .map(|p| p.name.clone())
        .collect()
}

/// `--set` names must be parameters of the scene: the one check every
/// command with `--set` makes.
pub fn set_names_are_parameters(scene: &Scene, set: &Values) -> Result<(), Diagnostic> {
    for name in set.keys() {
        if !scene.parameters.iter().any(|p| &p.name == name) {
            let list: Vec<&str> = scene.parameters.iter().map(|p| p.name.as_str()).collect();
            return Err(Diagnostic::global(format!(
                "`--set {name}=…`: `{name}` is not a parameter of the scene"
            ))
            .with_hint(if list.is_empty() {
                "the scene has no parameters".to_string()
            } else {
                format!("the parameters are {}", list.join(", "))
            })
            .with_kind(ErrorKind::bad_option("--set")));
        }
    }
    Ok(())
}

/// Every parameter's value from `--set` as the numeric commands take
/// them (`simulate`, `sweep`, `cycle`, `floquet`): signs checked
/// ([`numeric_parameter_signs`], 0 allowed but for the parameters
/// `inertial`), every parameter given, and no other name.
pub fn parameter_map(
    scene: &Scene,
    set: &Values,
    inertial: &[String],
) -> Result<rustc_hash::FxHashMap<crate::poly::Var, f64>, Diagnostic> {
    parameter_map_of(scene, set, inertial, &|_| true)
}

/// [`parameter_map`] of a command that needs only the parameters `needed`
/// says it does (`response --over`: those of its linearized system): the
/// same checks, but a parameter it does not need may be left out.
pub fn parameter_map_of(
    scene: &Scene,
    set: &Values,
    inertial: &[String],
    needed: &dyn Fn(&str) -> bool,
) -> Result<rustc_hash::FxHashMap<crate::poly::Var, f64>, Diagnostic> {
    numeric_parameter_signs(scene, set, inertial)?;
    let missing: Vec<&str> = scene
        .parameters
        .iter()
        .filter(|p| !set.contains_key(&p.name) && needed(&p.name))
        .map(|p| p.name.as_str())
        .collect();
    if !missing.is_empty() {
        let example: Vec<String> = missing.iter().map(|m| format!("{m}=1")).collect();
        return Err(Diagnostic::global(format!(
            "no value for the parameter{} {}",
            if missing.len() > 1 { "s" } else { "" },
            missing.join(", ")
        ))
        .with_hint(format!(
            "give every parameter a value: --set {}",
            example.join(",")
        ))
        .with_kind(ErrorKind::bad_option(SET.option)));
    }
    let mut out = rustc_hash::FxHashMap::default();
    for (k, &v) in set {
        if !scene.parameters.iter().any(|p| &p.name == k) {
            let names: Vec<&str> = scene.parameters.iter().map(|p| p.name.as_str()).collect();
            return Err(Diagnostic::global(format!(
                "`--set {k}=…`: `{k}` is not a parameter of the scene"
            ))
            .with_hint(format!("the parameters are {}", names.join(", ")))
            .with_kind(ErrorKind::bad_option(SET.option)));
        }
        out.insert(crate::expr::atom::param(k), v);
    }
    Ok(out)
}

/// An error unless every value of `set` for a parameter of `scene` is
/// positive, but for the parameters the scene assumes `real`, and unless
/// the values keep every order fact (`assume R > r`) whose parameters they
/// all give: the exact commands' check.
pub fn parameter_signs(scene: &Scene, set: &Values) -> Result<(), Diagnostic> {
    for (k, &v) in set {
        if v <= 0.0 && !assumed_real(scene, k) {
            return Err(not_positive(k, v));
        }
    }
    order_facts_hold(scene, set)
}

/// [`parameter_signs`] for a numeric command, which evaluates compiled
/// equations: a value may also be 0, but for the parameters `inertial`
/// ([`inertial_parameters`]).
pub fn numeric_parameter_signs(
    scene: &Scene,
    set: &Values,
    inertial: &[String],
) -> Result<(), Diagnostic> {
    for (k, &v) in set {
        if assumed_real(scene, k) {
            continue;
        }
        if v < 0.0 {
            return Err(not_positive(k, v));
        }
        if v == 0.0 && inertial.iter().any(|p| p == k) {
            return Err(zero_in_inertia(k));
        }
    }
    order_facts_hold(scene, set)
}

/// Whether the scene says `assume k real`.
fn assumed_real(scene: &Scene, k: &str) -> bool {
    scene
        .assumptions
        .real
        .contains(&crate::expr::atom::param(k))
}

/// Every order fact (`assume R > r`) holds at the values `set` gives.
fn order_facts_hold(scene: &Scene, set: &Values) -> Result<(), Diagnostic> {
    for fact in &scene.assumptions.positive {
        order_fact_holds(fact, set)?;
    }
    Ok(())
}

/// An error when `fact` (assumed > 0) is not positive at the values of
/// `set`, or too close to 0 beside its terms' sizes for doubles to tell;
/// nothing when `set` does not give all its parameters.
fn order_fact_holds(fact: &Expr, set: &Values) -> Result<(), Diagnostic> {
    use crate::expr::atom::Atom;
    use crate::poly::Poly;
    let value_of = |a: &Atom| match a {
        Atom::Param(name) => set.get(name.as_ref()).copied(),
        _ => None,
    };
    let Some(value) = fact.eval_f64(&value_of) else {
        return Ok(());
    };
    let val = |v| crate::expr::func::eval_atom(v, &value_of).unwrap_or(f64::NAN);
    let terms: f64 = fact
        .num()
        .terms()
        .iter()
        .map(|(m, c)| Poly::monomial(m.clone(), c.clone()).eval_f64(&val).abs())
        .sum();
    let size = terms / fact.den().eval_f64(&val).abs();
    if value > 1e-12 * size {
        return Ok(());
    }
    let mut names: Vec<String> = fact
        .vars()
        .into_iter()
        .filter_map(|v| match crate::expr::atom::atom(v) {
            Atom::Param(n) => set.get(n.as_ref()).map(|x| format!("{n}={x}")),
            _ => None,
        })
        .collect();
    names.sort();
    let fact_text = crate::expr::print::unicode(fact);
    let is = if value > 0.0 {
        "too close to 0 to tell its sign in doubles".to_string()
    } else {
        format!("{value} there")
    };
    Err(Diagnostic::global(format!(
        "`--set {}` breaks the scene's assumption {fact_text} > 0: it is {is}",
        names.join(",")
    ))
    .with_hint("give values that keep every `assume` fact, or change the fact")
    .with_kind(ErrorKind::bad_option(SET.option)))
}

/// Parse `--set m=1,g=-9.81` into finite doubles of either sign (the
/// scene decides which may be negative: [`parameter_signs`]); each value
/// a number or a constant expression ([`constant_value`]).
pub fn parameter_values_any_sign(s: &str) -> Result<Values, Diagnostic> {
    numeric_values(SET, s)
}

/// The simulator's `--init q=0.5,q'=0` (finite doubles, signs allowed;
/// each value a number or a constant expression: [`constant_value`]).
pub fn numeric_initial_values(s: &str) -> Result<Values, Diagnostic> {
    numeric_values(SIMULATE_INIT, s)
}

/// `name=value,…` of a numeric option: each value read by
/// [`constant_value`], refused with its reason.
fn numeric_values(syntax: OptionSyntax, s: &str) -> Result<Values, Diagnostic> {
    let mut out = Values::new();
    for NameValue {
        written,
        name,
        value,
    } in name_value_pairs(syntax, s)?
    {
        let v = constant_value(value).map_err(|e| {
            Diagnostic::global(format!(
                "`{} {written}`: {}",
                syntax.option,
                e.message(value)
            ))
            .with_hint(e.hint(syntax))
            .with_kind(ErrorKind::bad_option(syntax.option))
        })?;
        out.insert(name.to_string(), v);
    }
    Ok(out)
}

/// Why a text is not a value of a numeric option ([`constant_value`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConstantError {
    /// Neither a number nor a constant expression with a real value.
    NotNumber,
    /// A value beyond the doubles (`1e400`).
    BeyondRange,
    /// A value not 0 below the smallest double (`1e-400`).
    BelowSmallest,
}

impl ConstantError {
    /// What is wrong with the value `text`.
    pub fn message(self, text: &str) -> String {
        match self {
            ConstantError::NotNumber => format!("`{text}` is not a number"),
            ConstantError::BeyondRange => {
                format!("`{text}` is beyond the range of double precision (about 1.8e308)")
            }
            ConstantError::BelowSmallest => {
                format!("`{text}` is below the smallest double (about 4.9e-324)")
            }
        }
    }

    /// How to write a value of the option `syntax`.
    fn hint(self, syntax: OptionSyntax) -> String {
        match self {
            ConstantError::NotNumber if syntax.option == SET.option => {
                "write numbers or constant expressions: --set m=1.5,g=9.81,Omega=2*pi".to_string()
            }
            ConstantError::NotNumber => {
                "write numbers or constant expressions: --init x=0.1,x'=-2.5,theta=30deg"
                    .to_string()
            }
            _ => "numeric work is done in doubles; rescale the units".to_string(),
        }
    }
}

/// The one evaluator of every numeric option's values (`--set`, the
/// simulator's `--init`, the ends of `--over` and `--vary`, `--guess`): a
/// decimal number (read as Rust reads a double), `deg` (or `°`) after a
/// value for degrees, `pi` (`2pi`, `-pi`, `π`), or a constant expression
/// of the scene language (`pi/6`, `2*pi`, `sqrt(2)`, `1/3`). A value that
/// is not a real number, or that the doubles cannot hold, is refused.
pub fn constant_value(text: &str) -> Result<f64, ConstantError> {
    use std::f64::consts::PI;
    let s = text.trim();
    let (body, scale) = match s.strip_suffix("deg").or_else(|| s.strip_suffix('°')) {
        Some(n) => (n.trim(), PI / 180.0),
        None => (s, 1.0),
    };
    let x = match body.parse::<f64>() {
        Ok(x) if x.is_finite() => {
            if x == 0.0 && has_nonzero_digit(body) {
                return Err(ConstantError::BelowSmallest);
            }
            x
        }
        // `inf`, `NaN` are words, not numbers; `1e400` a number too large
        Ok(_) => {
            let lower = body.to_ascii_lowercase();
            return Err(if lower.contains("inf") || lower.contains("nan") {
                ConstantError::NotNumber
            } else {
                ConstantError::BeyondRange
            });
        }
        Err(_) => match body.strip_suffix("pi").or_else(|| body.strip_suffix('π')) {
            Some(n) => {
                let k: f64 = match n.trim() {
                    "" => 1.0,
                    "-" => -1.0,
                    n => match n.trim_end_matches('*').trim().parse() {
                        Ok(k) => k,
                        Err(_) => constant(body)? / PI,
                    },
                };
                k * PI
            }
            None => constant(body)?,
        },
    };
    let v = x * scale;
    if !v.is_finite() {
        return Err(ConstantError::BeyondRange);
    }
    if v == 0.0 && x != 0.0 {
        return Err(ConstantError::BelowSmallest);
    }
    Ok(v)
}

/// A constant expression's value (`pi/2`, `sqrt(2)`): no names but `pi`.
fn constant(text: &str) -> Result<f64, ConstantError> {
    let e = Scene::default()
        .expr(text)
        .map_err(|_| ConstantError::NotNumber)?;
    match e.eval_f64(&|_| None) {
        Some(v) if v.is_nan() => Err(ConstantError::NotNumber),
        Some(v) if !v.is_finite() => Err(ConstantError::BeyondRange),
        Some(v) if v == 0.0 && !e.is_zero() => Err(ConstantError::BelowSmallest),
        Some(v) => Ok(v),
        None => Err(ConstantError::NotNumber),
    }
}

/// Whether a decimal number's text has a nonzero digit before any exponent
/// (`1e-400` does, `0.0e5` does not).
fn has_nonzero_digit(t: &str) -> bool {
    t.split(['e', 'E'])
        .next()
        .is_some_and(|m| m.chars().any(|c| c.is_ascii_digit() && c != '0'))
}

/// `--at` about a steady motion: the positions, and the rates given.
#[derive(Clone, Debug)]
pub struct MotionValues {
    /// One exact value per coordinate (0 where not given).
    pub positions: Vec<Expr>,
    /// The rates given (`phi'=w`): coordinate index and rate.
    pub rates: Vec<(usize, Expr)>,
}

impl Scene {
    /// `name=expr,…`: each value an exact expression in the scene's names.
    fn exact_values(
        &self,
        syntax: OptionSyntax,
        s: &str,
    ) -> Result<Vec<(String, Expr)>, Diagnostic> {
        let mut out = Vec::new();
        for NameValue {
            written,
            name,
            value,
        } in name_value_pairs(syntax, s)?
        {
            out.push((name.to_string(), self.exact_value(syntax, written, value)?));
        }
        Ok(out)
    }

    /// One item `written` (`name=value`) of an exact option: `value` read
    /// in the scene.
    fn exact_value(
        &self,
        syntax: OptionSyntax,
        written: &str,
        value: &str,
    ) -> Result<Expr, Diagnostic> {
        self.expr(value).map_err(|d| {
            Diagnostic::global(format!("`{} {written}`: {}", syntax.option, d.message))
                .with_hint("values are exact expressions in the scene's parameters: 1/10, pi, 2*r")
                .with_kind(ErrorKind::bad_option(syntax.option))
        })
    }

    fn coordinate_index(&self, option: &str, name: &str) -> Result<usize, Diagnostic> {
        self.coordinates
            .iter()
            .position(|c| c.name == name)
            .ok_or_else(|| {
                let list: Vec<&str> = self.coordinates.iter().map(|c| c.name.as_str()).collect();
                Diagnostic::global(format!(
                    "`{option}`: `{name}` is not a coordinate of the scene"
                ))
                .with_hint(format!("the coordinates are {}", list.join(", ")))
                .with_kind(ErrorKind::bad_option(option))
            })
    }

    /// `--at q=value,…`: one exact value per coordinate (0 where not given).
    pub fn coordinate_values(&self, s: &str) -> Result<Vec<Expr>, Diagnostic> {
        let MotionValues { positions, rates } = self.motion_values(s)?;
        if let Some((k, _)) = rates.first() {
            return Err(Diagnostic::global(format!(
                "`--at {}'=…`: a rate belongs to a steady motion, and this command linearizes about an equilibrium",
                self.coordinates[*k].name
            ))
            .with_hint("`qdot modes --steady q` linearizes about a steady motion")
            .with_kind(ErrorKind::bad_option(AT.option)));
        }
        Ok(positions)
    }

    /// `--at q=value,…,c'=rate,…`: one exact value per coordinate (0 where
    /// not given) and the rates given (coordinate index, rate). A value
    /// written as the coordinate's name followed by 0 (`theta=theta0`),
    /// when no such name is declared, is a symbol of its own: the reference
    /// position left general.
    pub fn motion_values(&self, s: &str) -> Result<MotionValues, Diagnostic> {
        let mut vals = vec![Expr::zero(); self.coordinates.len()];
        let mut rates = Vec::new();
        for NameValue {
            written,
            name,
            value,
        } in name_value_pairs(AT, s)?
        {
            if let Some(c) = name.strip_suffix('\'') {
                let k = self.coordinate_index(AT.option, c)?;
                rates.push((k, self.exact_value(AT, written, value)?));
                continue;
            }
            let k = self.coordinate_index(AT.option, name)?;
            let symbol = format!("{name}0");
            vals[k] = if value.trim() == symbol && self.expr(&symbol).is_err() {
                Expr::unknown(&symbol)
            } else {
                self.exact_value(AT, written, value)?
            };
        }
        Ok(MotionValues {
            positions: vals,
            rates,
        })
    }

    /// `--steady q,…`: the steady coordinates' indices.
    pub fn steady_coordinates(&self, s: &str) -> Result<Vec<usize>, Diagnostic> {
        let mut out = Vec::new();
        for name in s.split(',').map(str::trim) {
            let k = self.coordinate_index("--steady", name)?;
            if out.contains(&k) {
                return Err(
                    Diagnostic::global(format!("`--steady`: `{name}` is named twice"))
                        .with_hint("name each steady coordinate once")
                        .with_kind(ErrorKind::bad_option("--steady")),
                );
            }
            out.push(k);
        }
        Ok(out)
    }

    /// `--init q=…,q'=…`: exact positions and velocities (0 where not given).
    pub fn initial_conditions(&self, s: &str) -> Result<(Vec<Expr>, Vec<Expr>), Diagnostic> {
        let n = self.coordinates.len();
        let mut q0 = vec![Expr::zero(); n];
        let mut v0 = vec![Expr::zero(); n];
        for (k, e) in self.exact_values(INIT, s)? {
            match k.strip_suffix('\'') {
                Some(name) => v0[self.coordinate_index(INIT.option, name)?] = e,
                None => q0[self.coordinate_index(INIT.option, &k)?] = e,
            }
        }
        Ok((q0, v0))
    }
}

/// One axis of a grid, `NAME=FROM:TO:COUNT`: COUNT evenly spaced values of
/// NAME from FROM to TO, both ends included (`--over` of `cycle`,
/// `response` and `floquet`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GridAxis {
    /// The varied name: a parameter, a driven coordinate, `t` or `Omega`.
    pub name: String,
    /// The first value.
    pub from: f64,
    /// The last value.
    pub to: f64,
    /// How many values (1: FROM alone).
    pub count: usize,
}

impl GridAxis {
    /// Parse one range as `cycle --over` takes it (`phi=0:360deg:73`):
    /// [`parse_ranges`] with [`CYCLE_OVER`].
    pub fn parse(s: &str) -> Result<GridAxis, Diagnostic> {
        let mut axes = parse_ranges(&CYCLE_OVER, s)?;
        Ok(axes.remove(0))
    }

    /// The k-th value.
    pub fn value(&self, k: usize) -> f64 {
        if self.count <= 1 {
            return self.from;
        }
        self.from + (self.to - self.from) * k as f64 / (self.count - 1) as f64
    }
}

/// The most points of one `--over` grid: `cycle`'s positions, `response`'s
/// frequencies, `floquet`'s grid points. Each row is kept in memory until
/// printed.
pub const MAX_GRID_POINTS: usize = 1_000_000;

/// How a range option is written and bounded, for [`parse_ranges`].
#[derive(Clone, Copy, Debug)]
pub struct RangeSyntax {
    /// `--over`, `--vary`.
    pub option: &'static str,
    /// The hint of every error: how the option is written.
    pub hint: &'static str,
    /// How many ranges one option may give, comma-separated.
    pub max_ranges: usize,
    /// The error when more are given: what varies.
    pub too_many: &'static str,
    /// Whether COUNT may be left out (`NAME=FROM:TO`: then the axis's
    /// count is 0, for a random design to fill).
    pub count_optional: bool,
    /// The most points: the product of the counts.
    pub max_points: usize,
}

/// `cycle --over phi=0:360deg:73`: `t` or a driven coordinate.
pub const CYCLE_OVER: RangeSyntax = RangeSyntax {
    option: "--over",
    hint: "write the varied quantity, its first and last values and the number of positions: --over phi=0:360deg:73 or --over t=0:2:101",
    max_ranges: 1,
    too_many: "one quantity varies, not more",
    count_optional: false,
    max_points: MAX_GRID_POINTS,
};

/// `response --over Omega=0:3:600`: the forcing frequency.
pub const RESPONSE_OVER: RangeSyntax = RangeSyntax {
    hint: "--over Omega=0:3:600: the first and last frequencies, and how many",
    ..CYCLE_OVER
};

/// `floquet --over delta=-1:3:81,eps=0:2:41`: one or two parameters.
pub const FLOQUET_OVER: RangeSyntax = RangeSyntax {
    hint:
        "--over NAME=FROM:TO:COUNT, or two of them for a chart: --over \"delta=-1:3:81,eps=0:2:41\"",
    max_ranges: 2,
    too_many: "one or two parameters vary, not more",
    ..CYCLE_OVER
};

/// The one reader of ranges and grids: `NAME=FROM:TO:COUNT`, or several
/// comma-separated (a grid, the first varying fastest). FROM and TO are
/// values of [`constant_value`] (`0.5`, `360deg`, `2pi`, `pi/2`,
/// `sqrt(2)`); COUNT a whole number
/// from 1 (FROM alone) to the syntax's limit, the product of the counts
/// too.
pub fn parse_ranges(syntax: &RangeSyntax, text: &str) -> Result<Vec<GridAxis>, Diagnostic> {
    let error = |message: String, hint: &str| {
        Diagnostic::global(message)
            .with_hint(hint)
            .with_kind(ErrorKind::bad_option(syntax.option))
    };
    let items = top_level_items(text);
    let several = items.len() > 1;
    let bad = |item: &str, why: String| {
        let item = if several {
            format!("`{}`: ", item.trim())
        } else {
            String::new()
        };
        error(
            format!("`{} {text}`: {item}{why}", syntax.option),
            syntax.hint,
        )
    };
    if items.len() > syntax.max_ranges {
        return Err(error(
            format!("`{} {text}`: {}", syntax.option, syntax.too_many),
            syntax.hint,
        ));
    }
    let mut axes: Vec<GridAxis> = Vec::new();
    for item in items {
        let (name, range) = item
            .split_once('=')
            .ok_or_else(|| bad(item, "no `=`".into()))?;
        let name = name.trim();
        if name.is_empty() {
            return Err(bad(item, "no name before `=`".into()));
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let takes = if syntax.count_optional {
            "2 or 3 (FROM:TO or FROM:TO:COUNT)"
        } else {
            "3 (FROM:TO:COUNT)"
        };
        let (from, to, count) = match parts[..] {
            [from, to, count] => (from, to, Some(count)),
            [from, to] if syntax.count_optional => (from, to, None),
            _ => {
                return Err(bad(
                    item,
                    format!("{} parts after `=`, and it takes {takes}", parts.len()),
                ))
            }
        };
        let number = |s: &str| constant_value(s).map_err(|e| bad(item, e.message(s)));
        let (from, to) = (number(from)?, number(to)?);
        let count = match count {
            Some(c) => c
                .parse::<usize>()
                .ok()
                .filter(|c| (1..=syntax.max_points).contains(c))
                .ok_or_else(|| {
                    bad(
                        item,
                        format!(
                            "COUNT `{c}` must be a whole number from 1 to {}",
                            crate::budget::grouped(syntax.max_points)
                        ),
                    )
                })?,
            None => 0,
        };
        if axes.iter().any(|a| a.name == name) {
            return Err(error(
                format!("`{} {name}`: `{name}` is varied twice", syntax.option),
                "vary each parameter once",
            ));
        }
        axes.push(GridAxis {
            name: name.to_string(),
            from,
            to,
            count,
        });
    }
    let total = axes
        .iter()
        .try_fold(1usize, |t, a| t.checked_mul(a.count.max(1)));
    match total {
        Some(t) if t <= syntax.max_points => Ok(axes),
        _ => Err(error(
            format!(
                "`{} {text}`: {} points, more than {}",
                syntax.option,
                total.map_or_else(|| "too many".to_string(), crate::budget::grouped),
                crate::budget::grouped(syntax.max_points)
            ),
            syntax.hint,
        )),
    }
}

/// `text` split at its commas outside parentheses (an expression's
/// `atan2(1, 2)` stays whole).
fn top_level_items(text: &str) -> Vec<&str> {
    let mut items = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&text[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&text[start..]);
    items
}

/// A value of a range or a guess: [`constant_value`], `None` where it
/// refuses the text.
pub fn range_value(s: &str) -> Option<f64> {
    constant_value(s).ok()
}
