//! The JSON of every command: its keys are a public contract (listed in
//! [`super`]'s documentation and in the book's CLI chapter).

use super::{as_input, position_strings};
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::scene::Scene;
use crate::solve::equilibrium::{self, Equilibria, Position, Values};
use crate::solve::system::{self, BlockSolution};
use serde_json::{json, Map, Value};

pub(super) fn json_string(m: Map<String, Value>) -> String {
    let mut s = serde_json::to_string_pretty(&Value::Object(m)).unwrap_or_default();
    s.push('\n');
    s
}

pub(super) fn named(names: &[String], es: &[Expr]) -> Value {
    let mut m = Map::new();
    for (n, e) in names.iter().zip(es) {
        m.insert(n.clone(), Value::String(as_input(e)));
    }
    Value::Object(m)
}

/// The JSON of `qdot derive`.
pub fn derive_json(l: &Lagrange) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(l.coordinates));
    m.insert(
        "equations".into(),
        Value::Array(
            l.equations
                .iter()
                .map(|e| json!({"coordinate": e.coordinate, "lhs": as_input(&e.lhs), "rhs": as_input(&e.rhs)}))
                .collect(),
        ),
    );
    m.insert(
        "mass_matrix".into(),
        json!(l
            .mass_matrix
            .iter()
            .map(|r| r.iter().map(as_input).collect::<Vec<_>>())
            .collect::<Vec<_>>()),
    );
    m.insert(
        "forcing".into(),
        json!(l.forcing.iter().map(as_input).collect::<Vec<_>>()),
    );
    m
}

/// The `bodies` key of a scene with `body`, `particle` or `gravity`
/// statements: one object per body in statement order, with the definition
/// that holds its kinetic energy and, under gravity, its potential.
pub fn bodies_json(scene: &Scene) -> Value {
    let line =
        |span: crate::diag::Span| crate::diag::Diagnostic::line_col(&scene.source, span.start).0;
    let energy = |name: &str| match scene.definition(name) {
        Some(value) => json!({"name": name, "value": as_input(value)}),
        None => Value::Null,
    };
    Value::Array(
        scene
            .bodies
            .iter()
            .map(|b| {
                json!({
                    "name": b.name,
                    "kind": b.kind.keyword(),
                    "line": line(b.span),
                    "kinetic": energy(&b.kinetic),
                    "potential": b.gravity.as_deref().map_or(Value::Null, energy),
                })
            })
            .collect(),
    )
}

/// The JSON of `qdot solve`: derive's keys plus `accelerations`.
pub fn solve_json(l: &Lagrange, acc: &crate::mechanics::Accelerations) -> Map<String, Value> {
    let mut m = derive_json(l);
    let mut a = Map::new();
    for (q, e) in acc {
        a.insert(q.to_string(), Value::String(as_input(e)));
    }
    m.insert("accelerations".into(), Value::Object(a));
    if !acc.multipliers().is_empty() {
        let mut mult = Map::new();
        for (name, e) in acc.multipliers() {
            mult.insert(name.clone(), Value::String(as_input(e)));
        }
        m.insert("multipliers".into(), Value::Object(mult));
    }
    m
}

/// The `constraints` key of a scene with `constraint` statements: one
/// object per constraint, in order.
pub fn constraints_json(scene: &Scene) -> Value {
    Value::Array(
        scene
            .constraints
            .iter()
            .map(|c| {
                json!({
                    "name": c.name,
                    "multiplier": c.multiplier,
                    "kind": if c.holonomic { "holonomic" } else { "velocity" },
                    "expression": as_input(&c.expression),
                    "coefficients": c.coefficients.iter().map(as_input).collect::<Vec<_>>(),
                    "rest": as_input(&c.rest),
                })
            })
            .collect(),
    )
}

/// Add `solutions`, `free_unknowns` and `checks` to a JSON object.
pub fn solutions_json(scene: &Scene, blocks: &[BlockSolution], m: &mut Map<String, Value>) {
    let mut sols = Map::new();
    let mut free = Vec::new();
    let mut checks = Vec::new();
    for (b, (sys, sol)) in scene.systems.iter().zip(blocks).enumerate() {
        for (n, v) in &sol.values {
            if !sol.free.contains(n) {
                sols.insert(n.clone(), Value::String(as_input(v)));
            }
        }
        free.extend(sol.free.iter().cloned());
        for &i in &sol.checks {
            let mut c = json!({"block": b + 1, "equation": system::equation_number(sys, i)});
            if let Some(k) = sys.equations[i].component {
                c["component"] = json!(["x", "y", "z"][k.min(2)]);
            }
            checks.push(c);
        }
    }
    m.insert("solutions".into(), Value::Object(sols));
    m.insert("free_unknowns".into(), json!(free));
    m.insert("checks".into(), Value::Array(checks));
}

/// The JSON of `qdot equilibrium`.
pub fn equilibrium_json(eq: &Equilibria) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(eq.coordinates));
    m.insert(
        "generalized_forces".into(),
        named(&eq.coordinates, &eq.forces),
    );
    m.insert("conditions".into(), named(&eq.coordinates, &eq.conditions));
    m.insert("exact".into(), json!(eq.exact));
    let mut list = Vec::new();
    let mut stab = Vec::new();
    let mut multiplicity = Vec::new();
    let mut notes = Vec::new();
    let mut approx = Vec::new();
    let mut digits = Vec::new();
    let mut certified = Vec::new();
    let mut enclosure = Vec::new();
    for e in &eq.equilibria {
        let numeric = matches!(e.position, Position::Numeric(_));
        // the digits the text prints: certified, else 6 significant
        digits.push(match (&e.position, &e.certified) {
            (Position::Numeric(_), Some(d)) => json!(d),
            (Position::Numeric(xs), None) => json!(xs
                .iter()
                .map(|x| crate::solve::certify::significant(*x, 6))
                .collect::<Vec<_>>()),
            (Position::Exact(_), _) => Value::Null,
        });
        certified.push(if numeric {
            json!(e.certified.is_some())
        } else {
            Value::Null
        });
        enclosure.push(match (e.enclosure, eq.coordinates.first()) {
            (Some((lo, hi)), Some(c)) => json!({ c.clone(): [lo, hi] }),
            _ => Value::Null,
        });
        approx.push(match &e.approx {
            Some(a) => json!(a),
            None => Value::Null,
        });
        let mut o = Map::new();
        match &e.position {
            Position::Numeric(xs) => {
                for (c, x) in eq.coordinates.iter().zip(xs) {
                    o.insert(c.clone(), json!(x));
                }
            }
            Position::Exact(_) => {
                for (c, v) in eq
                    .coordinates
                    .iter()
                    .zip(position_strings(eq, e, &as_input))
                {
                    o.insert(c.clone(), Value::String(v));
                }
            }
        }
        list.push(Value::Object(o));
        stab.push(json!(e.stability.word()));
        multiplicity.push(json!(e.multiplicity));
        let mut n: Vec<String> = e
            .conditions
            .iter()
            .map(|c| format!("exists when {c}"))
            .collect();
        if let equilibrium::Stability::Undecided(why) = &e.stability {
            n.push(why.clone());
        }
        n.extend(super::uncertified_note(e).map(String::from));
        notes.push(json!(n.join("; ")));
    }
    m.insert("equilibria".into(), Value::Array(list));
    m.insert("stability".into(), Value::Array(stab));
    m.insert("notes".into(), Value::Array(notes));
    m.insert("approx".into(), Value::Array(approx));
    m.insert("multiplicity".into(), Value::Array(multiplicity));
    m.insert("digits".into(), Value::Array(digits));
    m.insert("certified".into(), Value::Array(certified));
    m.insert("enclosure".into(), Value::Array(enclosure));
    m.insert("complete".into(), json!(super::search_caveat(eq).is_none()));
    m.insert("caveat".into(), json!(super::search_caveat(eq)));
    // with constraints: each equilibrium's multipliers (name → λ)
    if eq.equilibria.iter().any(|e| !e.multipliers.is_empty()) {
        let lists = eq
            .equilibria
            .iter()
            .map(|e| {
                let mut o = Map::new();
                for (name, v) in &e.multipliers {
                    o.insert(name.clone(), Value::String(as_input(v)));
                }
                Value::Object(o)
            })
            .collect();
        m.insert("multipliers".into(), Value::Array(lists));
    }
    m
}

/// `forced_response`: for f = F·cos(p·t), the undamped amplitudes
/// (K − p²M)⁻¹·F, or for one damped coordinate X and tan ψ.
fn forced_json(
    md: &crate::solve::oscillations::Modes,
    sf: Option<&crate::solve::oscillations::StandardForm>,
) -> Value {
    use crate::solve::oscillations as osc;
    let damped = md.damping.iter().flatten().any(|e| !e.is_zero());
    if !damped {
        return osc::forced_amplitudes(md)
            .map(|(p, x)| json!({"p": as_input(&p), "amplitudes": named(&md.coordinates, &x)}))
            .unwrap_or(Value::Null);
    }
    sf.and_then(|sf| osc::damped_steady_state(md, sf))
        .map(|(p, x, t)| json!({"p": as_input(&p), "amplitude": as_input(&x), "tan_psi": as_input(&t)}))
        .unwrap_or(Value::Null)
}

/// The JSON of `qdot modes`.
pub fn modes_json(
    md: &crate::solve::oscillations::Modes,
    set: &Values,
    free: Option<&[Expr]>,
    numeric: Option<&crate::solve::oscillations::NumericFree>,
) -> Map<String, Value> {
    let mat = |m: &[Vec<Expr>]| {
        json!(m
            .iter()
            .map(|r| r.iter().map(as_input).collect::<Vec<_>>())
            .collect::<Vec<_>>())
    };
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(md.coordinates));
    m.insert("at".into(), named(&md.coordinates, &md.at));
    if !md.dependent.is_empty() {
        let (c, v): (Vec<String>, Vec<Expr>) = md.dependent.iter().cloned().unzip();
        m.insert("dependent".into(), named(&c, &v));
    }
    m.insert("mass_matrix".into(), mat(&md.mass));
    m.insert("stiffness_matrix".into(), mat(&md.stiffness));
    m.insert("damping_matrix".into(), mat(&md.damping));
    m.insert(
        "forcing".into(),
        json!(md.forcing.iter().map(as_input).collect::<Vec<_>>()),
    );
    m.insert(
        "characteristic_polynomial".into(),
        // expanded: the factored form is `characteristic_factors`
        json!(crate::expr::compact::canonical_only(|| as_input(
            &md.characteristic
        ))),
    );
    m.insert(
        "characteristic_factors".into(),
        json!(md.factors.iter().map(as_input).collect::<Vec<_>>()),
    );
    m.insert("gyroscopic".into(), json!(md.gyroscopic));
    m.insert(
        "omega_squared".into(),
        // term by term over a monomial denominator, as the text shows them
        json!(md
            .omega_squared
            .iter()
            .map(crate::expr::print::expanded_input)
            .collect::<Vec<_>>()),
    );
    m.insert(
        "modes".into(),
        json!(md
            .modes
            .iter()
            .map(|v| v.iter().map(as_input).collect::<Vec<_>>())
            .collect::<Vec<_>>()),
    );
    m.insert("no_closed_form".into(), json!(md.no_closed_form));
    m.insert("stability".into(), json!(md.stability.word()));
    // why, when undecided (the text's parenthesis)
    let note = match &md.stability {
        crate::solve::oscillations::Stability::Undecided(why) => Some(why),
        _ => None,
    };
    m.insert("stability_note".into(), json!(note));
    let standard = crate::solve::oscillations::standard_form(md, set);
    let sf = standard.as_ref().map(|sf| {
        json!({
            "omega_squared": crate::expr::print::expanded_input(&sf.omega_squared),
            "alpha": crate::expr::print::expanded_input(&sf.alpha),
            "zeta": sf.zeta.as_ref().map(as_input),
            "forcing": as_input(&sf.forcing),
            "regime": sf.regime,
        })
    });
    m.insert("standard_form".into(), sf.unwrap_or(Value::Null));
    let eigen_or_why = crate::solve::oscillations::numeric_modes_or_why(md, set);
    let eigen = eigen_or_why.as_ref().ok().and_then(Option::as_ref);
    m.insert(
        "numeric_omega_squared".into(),
        eigen.map(|g| json!(g.values)).unwrap_or(Value::Null),
    );
    m.insert(
        "numeric_modes".into(),
        eigen.map(|g| json!(g.vectors)).unwrap_or(Value::Null),
    );
    m.insert(
        "numeric_modes_note".into(),
        eigen_or_why
            .as_ref()
            .err()
            .map_or(Value::Null, |why| json!(why)),
    );
    m.insert(
        "free_response".into(),
        free.map(|f| named(&md.coordinates, f))
            .unwrap_or(Value::Null),
    );
    // without closed forms: q(t) with decimal numbers (10 significant
    // digits), computed numerically at the --set values
    m.insert(
        "numeric_free_response".into(),
        numeric
            .map(|nf| {
                let q: Map<String, Value> = md
                    .coordinates
                    .iter()
                    .enumerate()
                    .map(|(j, c)| {
                        (
                            c.clone(),
                            json!(super::modes::numeric_response(nf, j, false)),
                        )
                    })
                    .collect();
                Value::Object(q)
            })
            .unwrap_or(Value::Null),
    );
    m.insert("forced_response".into(), forced_json(md, standard.as_ref()));
    m
}

/// The JSON of `qdot hamilton`: `coordinates`, `momenta` (q → p_q in q,
/// q̇), `velocities` (q → q̇ in q, p), `hamiltonian`, `equations` (one
/// `{"coordinate", "momentum", "qdot", "pdot"}` per coordinate) and
/// `other_forces` (q → Q̃, the generalized forces outside H).
pub fn hamilton_json(h: &crate::mechanics::Hamiltonian) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(h.coordinates));
    m.insert("momenta".into(), named(&h.coordinates, &h.momenta));
    m.insert("velocities".into(), named(&h.coordinates, &h.velocities));
    m.insert(
        "hamiltonian".into(),
        Value::String(as_input(&h.hamiltonian)),
    );
    let equations = (0..h.coordinates.len())
        .map(|k| {
            json!({
                "coordinate": h.coordinates[k],
                "momentum": h.momentum_names[k],
                "qdot": as_input(&h.velocities[k]),
                "pdot": as_input(&h.momentum_rates[k]),
            })
        })
        .collect();
    m.insert("equations".into(), Value::Array(equations));
    m.insert(
        "other_forces".into(),
        named(&h.coordinates, &h.other_forces),
    );
    m
}

/// The JSON of `qdot integrals`: `coordinates`, `cyclic` (a list),
/// `momenta` (cyclic coordinate → p in q, q̇), `energy` (h, or null),
/// `energy_is_e_plus_v`, `routhian`, `effective_potential` and
/// `reduced_accelerations` (null without Routh's reduction), `notes`.
pub fn integrals_json(i: &crate::mechanics::Integrals) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(i.coordinates));
    let cyclic: Vec<String> = i.cyclic.iter().map(|(q, _)| q.clone()).collect();
    let momenta: Vec<Expr> = i.cyclic.iter().map(|(_, p)| p.clone()).collect();
    m.insert("momenta".into(), named(&cyclic, &momenta));
    m.insert("cyclic".into(), json!(cyclic));
    m.insert("energy".into(), json!(i.energy.as_ref().map(as_input)));
    m.insert("energy_is_e_plus_v".into(), json!(i.energy_is_e_plus_v));
    let r = i.routh.as_ref();
    m.insert("routhian".into(), json!(r.map(|r| as_input(&r.routhian))));
    m.insert(
        "effective_potential".into(),
        json!(r.map(|r| as_input(&r.effective_potential))),
    );
    m.insert(
        "reduced_accelerations".into(),
        match r {
            Some(r) => {
                let (q, a): (Vec<String>, Vec<Expr>) = r.accelerations.iter().cloned().unzip();
                named(&q, &a)
            }
            None => Value::Null,
        },
    );
    m.insert("notes".into(), json!(i.notes));
    m
}

/// The `reactions` key of `solve`: one `{"constraint", "point", "force"}`
/// per `reaction` statement (the force a list of components).
pub fn reactions_json(scene: &Scene, forces: &[Vec<Expr>]) -> Value {
    Value::Array(
        scene
            .reactions
            .iter()
            .zip(forces)
            .map(|(r, f)| {
                json!({
                    "constraint": scene.constraints[r.constraint].name,
                    "point": r.written,
                    "force": f.iter().map(as_input).collect::<Vec<_>>(),
                })
            })
            .collect(),
    )
}
