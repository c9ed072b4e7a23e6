//! `solve` blocks: linear systems of any shape, solved exactly.
//!
//! A block's equations are linear in its unknowns with coefficients that are
//! rational functions (with radicals, trig atoms, …) of everything else. The
//! elimination (`echelon`) is fraction-free, like [`crate::algebra::linear::solve`],
//! but rectangular: a column with no pivot is a *free* unknown, and a row left
//! without a pivot is an equation implied by the others: a *check* that either
//! holds (the seed's kinetostatic systems of 22.2 have one more equation than
//! unknowns, and the extra one verifies the rest) or contradicts them.
//!
//! Accelerations q̈ in a block of a scene with dynamics are replaced by the
//! exact accelerations of Lagrange's equations, so a kinetostatic follow-up
//! (reactions once the accelerations are known) is written as in the book.

use crate::algebra::linear::SolveError;
use crate::diag::Diagnostic;
use crate::expr::atom;
use crate::expr::{Expr, MathError};
use crate::poly::{Poly, Var};

use crate::scene::{Scene, SolveSystem};
use rustc_hash::FxHashMap;

/// The row echelon form of `[A | b]` and what it says about the system.
#[derive(Clone, Debug)]
pub struct Echelon {
    /// Columns (unknowns) with a pivot, in order.
    pub pivots: Vec<usize>,
    /// Columns without a pivot: free unknowns.
    pub free: Vec<usize>,
    /// Rows (equations, original indices) used as pivot rows, one per pivot.
    pub pivot_rows: Vec<usize>,
    /// Rows left over: equations implied by the pivot rows if consistent.
    pub dependent_rows: Vec<usize>,
}

/// `x` for a rectangular system, with the free unknowns as given symbols.
#[derive(Clone, Debug)]
pub struct RectSolution {
    /// Which unknowns are pivots or free, and which equations are dependent.
    pub shape: Echelon,
    /// One value per unknown; a free unknown's value is its symbol.
    pub values: Vec<Expr>,
    /// For each dependent row: b_i − A_i·x (zero when the equation holds).
    pub residuals: Vec<(usize, Expr)>,
}

/// The refusal to call a dependent equation consistent or contradictory
/// when its residual is zero to 10^−[`crate::expr::hidden_zero::ZERO_DIGITS`]
/// but not provably either way.
fn undecided_residual(res: &Expr) -> crate::expr::MathError {
    crate::expr::MathError::new(format!(
        "cannot decide whether a dependent equation holds: with the others' solution it reads \
         0 = {}, which is 0 to {} digits but not provably (it holds atoms whose relations qdot \
         does not use: constants such as cos(π/7), or sin and cos of both x and x/2)",
        crate::expr::print::unicode(res),
        crate::expr::hidden_zero::ZERO_DIGITS
    ))
    .hint(
        "write a constant by its exact value if it has one, and an angle and its fraction on \
         one base (sin x as 2·sin(x/2)·cos(x/2))",
    )
}

/// Solve `a·x = b` for `a` of any shape (m equations, n unknowns).
///
/// `symbols[j]` stands for unknown j if it turns out free. Pivot rows are
/// taken in equation order (the first equation with a nonzero entry), so an
/// equation reported as dependent is the *last* of a dependent set, as a
/// reader checks a system.
pub fn solve_rect(
    a: &[Vec<Expr>],
    b: &[Expr],
    symbols: &[Expr],
) -> Result<RectSolution, SolveError> {
    let m = a.len();
    let n = symbols.len();
    let mut rows = crate::algebra::linear::cleared_rows(a, b);
    let mut orig: Vec<usize> = (0..m).collect();
    let mut prev = Poly::one();
    // the whole elimination is charged to the work budget, not only each product
    let work = crate::budget::WorkMeter::new();
    let mut r = 0;
    let mut pivots = Vec::new();
    let mut free = Vec::new();
    for c in 0..n {
        let Some(p) = (r..m)
            .filter(|&i| crate::algebra::linear::nonzero(&rows[i][c]))
            .min_by_key(|&i| (crate::algebra::linear::may_be_zero(&rows[i][c]), orig[i]))
        else {
            // no pivot: the entries left are zero (modulo sin² + cos² = 1)
            for row in rows.iter_mut().skip(r) {
                row[c] = Poly::zero();
            }
            free.push(c);
            continue;
        };
        rows.swap(r, p);
        orig.swap(r, p);
        for i in r + 1..m {
            for j in c + 1..=n {
                rows[i][j] = crate::algebra::linear::bareiss_entry(
                    &work,
                    [&rows[r][c], &rows[i][j], &rows[i][c], &rows[r][j]],
                    &prev,
                )?;
            }
            rows[i][c] = Poly::zero();
        }
        prev = rows[r][c].clone();
        pivots.push(c);
        r += 1;
    }
    // Back-substitution over canonical expressions: x_c = (b − Σ a·x)/a_cc,
    // with free unknowns as symbols.
    let mut values: Vec<Option<Expr>> = vec![None; n];
    for &f in &free {
        values[f] = Some(symbols[f].clone());
    }
    for k in (0..r).rev() {
        let c = pivots[k];
        let mut t = Expr::from_poly(rows[k][n].clone());
        for j in c + 1..n {
            if rows[k][j].is_zero() {
                continue;
            }
            let x = values[j].clone().unwrap_or_else(Expr::zero);
            t = t.sub(&Expr::from_poly(rows[k][j].clone()).mul(&x));
        }
        let x = t
            .div(&Expr::from_poly(rows[k][c].clone()))
            .map_err(SolveError::Math)?;
        values[c] = Some(x);
    }
    let values: Vec<Expr> = values
        .into_iter()
        .map(|v| v.unwrap_or_else(Expr::zero))
        .collect();
    // Each dependent equation, checked on the original row.
    let mut residuals = Vec::new();
    for &i in &orig[r..] {
        let mut res = b[i].clone();
        for (aij, x) in a[i].iter().zip(&values) {
            if !aij.is_zero() {
                res = res.sub(&aij.mul(x));
            }
        }
        if !res.is_zero() && res.may_be_zero() {
            return Err(SolveError::Math(undecided_residual(&res)));
        }
        residuals.push((i, res));
    }
    let shape = Echelon {
        pivots,
        free,
        pivot_rows: orig[..r].to_vec(),
        dependent_rows: orig[r..].to_vec(),
    };
    Ok(RectSolution {
        shape,
        values,
        residuals,
    })
}

/// The solution of one `solve` block.
#[derive(Clone, Debug)]
pub struct BlockSolution {
    /// Every unknown with its value (a free unknown's value is itself).
    pub values: Vec<(String, Expr)>,
    /// Unknowns the equations leave free.
    pub free: Vec<String>,
    /// Equations (indices into the block's equations) implied by the others
    /// and verified to hold.
    pub checks: Vec<usize>,
    /// Whether the exact accelerations of Lagrange's equations were put in
    /// for q̈ in the equations.
    pub used_accelerations: bool,
    /// Whether `values` are in the order they are solved, each written
    /// through the unknowns before it (a block solved through
    /// intermediates, see [`solve_in_order`]); else in the block's order,
    /// each in the scene's names alone.
    pub in_order: bool,
}

/// The 1-based number of the source equation that scalar equation `i` of
/// `sys` comes from (a vector equation gives several scalar ones).
pub fn equation_number(sys: &SolveSystem, i: usize) -> usize {
    let mut n = 0;
    let mut last = None;
    for e in &sys.equations[..=i.min(sys.equations.len().saturating_sub(1))] {
        if last != Some(e.span) {
            n += 1;
            last = Some(e.span);
        }
    }
    n
}

/// Where equation `i` of `sys` is, for messages: "equation 3" or
/// "equation 3 (component y)".
pub fn equation_label(sys: &SolveSystem, i: usize) -> String {
    let eq = &sys.equations[i];
    let n = equation_number(sys, i);
    match eq.component {
        Some(k) => format!("equation {n} (component {})", ["x", "y", "z"][k.min(2)]),
        None => format!("equation {n}"),
    }
}

/// Solve every `solve` block of a scene, in order; a block may use the
/// unknowns of earlier blocks, whose solutions are put in.
pub fn solve_scene(scene: &Scene) -> Result<Vec<BlockSolution>, Diagnostic> {
    crate::diag::bounded(|| {
        let _context = crate::budget::enter(|| "solving the `solve` blocks".into(), None);
        let mut known: FxHashMap<Var, Expr> = FxHashMap::default();
        let mut acc: Option<FxHashMap<Var, Expr>> = None;
        let mut out = Vec::with_capacity(scene.systems.len());
        for sys in &scene.systems {
            let sol = solve_block(scene, sys, &known, &mut acc)?;
            // each value may use the unknowns before it (see `in_order`):
            // later blocks and the check see them resolved
            let mut resolved = Vec::with_capacity(sol.values.len());
            for (name, v) in &sol.values {
                let v = if sol.in_order {
                    v.subs_many(&known).map_err(|m| math(sys.span, m))?
                } else {
                    v.clone()
                };
                known.insert(atom::unknown(name), v.clone());
                resolved.push((name.clone(), v));
            }
            if let Some(tape) = scene.tape.as_ref().filter(|t| !t.is_empty()) {
                verify_through(tape, sys, &resolved, &known)?;
            }
            out.push(sol);
        }
        Ok(out)
    })
}

/// For a block solved through intermediates: every solution finite and
/// every equation satisfied at random states, evaluated through the tape.
/// The canonical form cannot see every relation between intermediates
/// (sin α = R·sin φ/L once α is a name), so an elimination could have
/// divided by what is zero once expanded; this refuses such a solution
/// instead of printing it.
fn verify_through(
    tape: &crate::expr::tape::Tape,
    sys: &SolveSystem,
    solution: &[(String, Expr)],
    values: &FxHashMap<Var, Expr>,
) -> Result<(), Diagnostic> {
    use crate::expr::atom::Atom;
    let refuse = || {
        Diagnostic::error(
            sys.span,
            "this block's solution through the intermediates does not check out numerically: an elimination may have divided by a quantity that is zero once the intermediates are expanded",
        )
        .with_hint("solve it expanded: drop `--keep` and `--structured`").with_kind(crate::diag::ErrorKind::Undefined)
    };
    let mut rng = crate::rng::SplitMix64::new(0x51_0e5);
    let roots: Vec<Expr> = solution.iter().map(|(_, v)| v.clone()).collect();
    let used = tape.used_by(&roots);
    let (mut probes, mut tries) = (0, 0);
    while probes < 3 {
        tries += 1;
        if tries > 64 {
            // no state found where the intermediates are all defined
            return Err(refuse());
        }
        let seed = rng.next_u64();
        let probe = |a: &Atom| -> Option<f64> {
            Some(crate::rng::SplitMix64::keyed(seed, a).uniform(0.3, 0.7))
        };
        // a state outside the intermediates' domain (asin of more than 1:
        // the scene's assumptions are not drawn) is no evidence
        let entries: Vec<Expr> = used.iter().map(|&i| tape.entries()[i].expr()).collect();
        let defined = tape
            .eval_many_f64(&entries, &probe)
            .is_some_and(|v| v.iter().all(|x| x.is_finite()));
        if !defined {
            continue;
        }
        probes += 1;
        let values_at = tape.eval_many_f64(&roots, &probe);
        if !values_at.is_some_and(|v| v.iter().all(|x| x.is_finite())) {
            return Err(refuse());
        }
        for eq in &sys.equations {
            let r = eq
                .residual
                .subs_many(values)
                .map_err(|m| math(eq.span, m))?;
            let size = scale_of(tape, &eq.residual, values, &probe);
            match tape.eval_f64(&r, &probe) {
                Some(x) if x.abs() <= 1e-8 * (1.0 + size) => {}
                _ => return Err(refuse()),
            }
        }
    }
    Ok(())
}

/// A scale for a residual's rounding: the largest magnitude among its
/// terms at the probe.
fn scale_of(
    tape: &crate::expr::tape::Tape,
    residual: &Expr,
    values: &FxHashMap<Var, Expr>,
    probe: &dyn Fn(&crate::expr::atom::Atom) -> Option<f64>,
) -> f64 {
    residual
        .num()
        .terms()
        .iter()
        .filter_map(|(m, c)| {
            let term = Expr::from_poly(crate::poly::Poly::monomial(m.clone(), c.clone()));
            let term = term.subs_many(values).ok()?;
            tape.eval_f64(&term, probe).map(f64::abs)
        })
        .fold(0.0, f64::max)
}

/// Whether `e` mentions any q̈ of the scene's coordinates.
fn mentions_any(e: &Expr, vs: &[Var]) -> bool {
    let vars = e.vars();
    vs.iter()
        .any(|&v| crate::expr::diff::vars_depend_on(&vars, v))
}

fn solve_block(
    scene: &Scene,
    sys: &SolveSystem,
    known: &FxHashMap<Var, Expr>,
    acc: &mut Option<FxHashMap<Var, Expr>>,
) -> Result<BlockSolution, Diagnostic> {
    let unknowns: Vec<Var> = sys
        .unknowns
        .iter()
        .map(|u| atom::unknown(&u.name))
        .collect();
    let qdd: Vec<Var> = scene
        .coordinates
        .iter()
        .map(|c| atom::coord(&c.name, 2))
        .collect();
    let dynamics = scene.has_dynamics();
    let mut used_accelerations = false;
    let mut residuals = Vec::with_capacity(sys.equations.len());
    for (i, eq) in sys.equations.iter().enumerate() {
        let mut r = eq.residual.clone();
        if !known.is_empty() {
            r = r.subs_many(known).map_err(|m| math(eq.span, m))?;
        }
        if dynamics && mentions_any(&r, &qdd) {
            scene.expanded_only("a `solve` block that uses the accelerations")?;
            if acc.is_none() {
                let l = scene.lagrange()?;
                let a = l.accelerations()?;
                *acc = Some(
                    a.into_iter()
                        .map(|(name, v)| (atom::coord(&name, 2), v))
                        .collect(),
                );
            }
            if let Some(a) = acc.as_ref() {
                r = r.subs_many(a).map_err(|m| math(eq.span, m))?;
                used_accelerations = true;
            }
        }
        check_linear(&r, &unknowns).map_err(|why| {
            Diagnostic::error(
                eq.span,
                format!("{} is not linear in the unknowns: {why}", equation_label(sys, i)),
            )
            .with_hint("a `solve` block solves linear equations exactly; move nonlinear relations into definitions, or solve for other unknowns").with_kind(crate::diag::ErrorKind::InvalidScene)
        })?;
        residuals.push(r);
    }
    // residual = Σ a_j·x_j + rest = 0  →  A·x = −rest
    let mut a = Vec::with_capacity(residuals.len());
    let mut b = Vec::with_capacity(residuals.len());
    for r in &residuals {
        let (coefs, rest) =
            crate::mechanics::split_linear(r, &unknowns).map_err(|m| math(sys.span, m))?;
        a.push(coefs);
        b.push(rest.neg());
    }
    let symbols: Vec<Expr> = unknowns.iter().map(|&v| Expr::var(v)).collect();
    let sol = solve_rect(&a, &b, &symbols).map_err(|e| match e {
        SolveError::Math(m) => math(sys.span, m),
        SolveError::Singular { dependent } => Diagnostic::error(sys.span, "the system is singular")
            .with_kind(crate::diag::ErrorKind::SingularSystem {
                unknowns: dependent
                    .iter()
                    .filter_map(|&i| sys.unknowns.get(i).map(|u| u.name.clone()))
                    .collect(),
            }),
    })?;
    let mut checks = Vec::new();
    for (i, res) in &sol.residuals {
        if !res.is_zero() {
            let eq = &sys.equations[*i];
            let message = if a[*i].iter().all(Expr::is_zero) {
                format!(
                    "{} involves none of the unknowns and does not hold: it reads 0 = {}",
                    equation_label(sys, *i),
                    crate::expr::print::unicode(res)
                )
            } else {
                format!(
                    "{} contradicts the others: with their solution it reads 0 = {}",
                    equation_label(sys, *i),
                    crate::expr::print::unicode(res)
                )
            };
            return Err(Diagnostic::error(eq.span, message)
            .with_hint(if a[*i].iter().all(Expr::is_zero) {
                "an equation of a `solve` block should mention its unknowns; check the names and the data"
            } else if sys.equations.len() > sys.unknowns.len() {
                "the block has more equations than unknowns, and this one does not follow from the rest; check its signs and data"
            } else {
                "the equations are dependent on the left but not on the right; check signs and data"
            }).with_kind(crate::diag::ErrorKind::SingularSystem { unknowns: Vec::new() }));
        }
        checks.push(*i);
    }
    checks.sort_unstable();
    let ordered = if scene.tape.as_ref().is_some_and(|t| !t.is_empty())
        && sol.shape.free.is_empty()
        && sol.residuals.is_empty()
    {
        solve_in_order(&a, &b, &unknowns).map_err(|m| math(sys.span, m))?
    } else {
        None
    };
    let in_order = ordered.is_some();
    let values = match ordered {
        Some(order) => order
            .into_iter()
            .map(|(j, v)| (sys.unknowns[j].name.clone(), v))
            .collect(),
        None => sys
            .unknowns
            .iter()
            .map(|u| u.name.clone())
            .zip(sol.values)
            .collect(),
    };
    let free = sol
        .shape
        .free
        .iter()
        .map(|&j| sys.unknowns[j].name.clone())
        .collect();
    Ok(BlockSolution {
        values,
        free,
        checks,
        used_accelerations,
        in_order,
    })
}

/// The largest set of equations [`solve_in_order`] looks for among the
/// unsolved ones before it solves the rest together.
const MAX_ORDERED_BLOCK: usize = 3;

/// The most sets of equations [`solve_in_order`] tries for one size in one
/// step: a large block is searched for single equations and pairs only,
/// so the search stays polynomial and small (C(100, 2) = 4,950).
const MAX_ORDERED_SUBSETS: usize = 10_000;

/// A square nonsingular `a·x = b` solved the way one solves a mechanism
/// body by body: repeatedly the smallest set of k equations (k ≤
/// `MAX_ORDERED_BLOCK`) in exactly k unknowns not yet solved, those
/// solved with the earlier unknowns kept as names (the block lower
/// triangular form, found greedily). Each value, in solving order, may
/// use the unknowns before it. `None` when no equation has a single
/// unknown left (nothing to gain over solving all at once).
pub fn solve_in_order(
    a: &[Vec<Expr>],
    b: &[Expr],
    unknowns: &[Var],
) -> Result<Option<Vec<(usize, Expr)>>, MathError> {
    let (m, n) = (a.len(), unknowns.len());
    let mut solved: Vec<bool> = vec![false; n];
    let mut used: Vec<bool> = vec![false; m];
    let mut out: Vec<(usize, Expr)> = Vec::with_capacity(n);
    while out.len() < n {
        let free_eqs: Vec<usize> = (0..m).filter(|&i| !used[i]).collect();
        let open = |i: usize| -> Vec<usize> {
            (0..n)
                .filter(|&j| !solved[j] && !a[i][j].is_zero())
                .collect()
        };
        let mut found: Option<(Vec<usize>, Vec<usize>)> = None;
        'sizes: for k in 1..=MAX_ORDERED_BLOCK.min(free_eqs.len()) {
            if binomial(free_eqs.len(), k) > MAX_ORDERED_SUBSETS {
                break;
            }
            for eqs in combinations(&free_eqs, k) {
                let mut cols: Vec<usize> = eqs.iter().flat_map(|&i| open(i)).collect();
                cols.sort_unstable();
                cols.dedup();
                if cols.len() == k {
                    found = Some((eqs, cols));
                    break 'sizes;
                }
            }
        }
        if found.is_none() && out.is_empty() {
            return Ok(None);
        }
        let (eqs, cols) = found.unwrap_or_else(|| {
            let cols = (0..n).filter(|&j| !solved[j]).collect();
            (free_eqs, cols)
        });
        let sub_a: Vec<Vec<Expr>> = eqs
            .iter()
            .map(|&i| cols.iter().map(|&j| a[i][j].clone()).collect())
            .collect();
        let sub_b: Vec<Expr> = eqs
            .iter()
            .map(|&i| {
                (0..n).filter(|&j| solved[j]).fold(b[i].clone(), |r, j| {
                    r.sub(&a[i][j].mul(&Expr::var(unknowns[j])))
                })
            })
            .collect();
        let symbols: Vec<Expr> = cols.iter().map(|&j| Expr::var(unknowns[j])).collect();
        let sol = match solve_rect(&sub_a, &sub_b, &symbols) {
            Ok(s) if s.shape.free.is_empty() && s.residuals.is_empty() => s,
            Ok(_) | Err(SolveError::Singular { .. }) => return Ok(None),
            Err(SolveError::Math(e)) => return Err(e),
        };
        for (&j, v) in cols.iter().zip(sol.values) {
            solved[j] = true;
            out.push((j, v));
        }
        for &i in &eqs {
            used[i] = true;
        }
    }
    Ok(Some(out))
}

/// C(n, k), saturating.
fn binomial(n: usize, k: usize) -> usize {
    (0..k).fold(1usize, |c, i| c.saturating_mul(n - i) / (i + 1))
}

/// The k-element subsets of `items`, in lexicographic order.
fn combinations(items: &[usize], k: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut pick: Vec<usize> = (0..k).collect();
    if k == 0 || k > items.len() {
        return out;
    }
    loop {
        out.push(pick.iter().map(|&p| items[p]).collect());
        let Some(i) = (0..k).rev().find(|&i| pick[i] < items.len() - k + i) else {
            return out;
        };
        pick[i] += 1;
        for j in i + 1..k {
            pick[j] = pick[j - 1] + 1;
        }
    }
}

fn math(span: crate::parse::ast::Span, m: MathError) -> Diagnostic {
    let d = Diagnostic::error(span, m.message).with_kind(crate::diag::ErrorKind::Undefined);
    match m.hint {
        Some(h) => d.with_hint(h),
        None => d,
    }
}

/// Ok if `e` is linear in `xs` (degree ≤ 1 jointly, none in a denominator
/// or inside a function); otherwise what is wrong.
fn check_linear(e: &Expr, xs: &[Var]) -> Result<(), String> {
    let name = |v: Var| crate::expr::print::atom_input(&atom::atom(v));
    for &v in e.den().vars().iter() {
        if xs.contains(&v) {
            return Err(format!("`{}` divides", name(v)));
        }
        if let Some(u) = inside_function(v, xs) {
            return Err(format!("`{}` appears inside a function", name(u)));
        }
    }
    for (m, _) in e.num().terms() {
        let mut deg = 0;
        let mut seen = Vec::new();
        for &(v, k) in m.0.iter() {
            if xs.contains(&v) {
                deg += k;
                seen.push(name(v));
            } else if let Some(u) = inside_function(v, xs) {
                return Err(format!("`{}` appears inside a function", name(u)));
            }
        }
        if deg > 1 {
            return Err(format!("the term has {}", seen.join("·")));
        }
    }
    Ok(())
}

/// The unknown of `xs` that function atom `v` has in its argument, if any.
fn inside_function(v: Var, xs: &[Var]) -> Option<Var> {
    let a = atom::atom(v);
    let u = a.argument()?;
    xs.iter().copied().find(|&x| u.depends_on(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn e(s: &str) -> Expr {
        let scene = Scene::parse("parameters a, b, c").expect("scene");
        scene.expr(s).expect("expr")
    }

    fn syms(n: usize) -> Vec<Expr> {
        (0..n).map(|i| Expr::unknown(&format!("x{i}"))).collect()
    }

    #[test]
    fn ordered_solving_takes_one_equation_at_a_time_and_bounds_its_search() {
        assert_eq!(
            (binomial(10, 3), binomial(100, 2), binomial(100, 3)),
            (120, 4_950, 161_700)
        );
        // x1 = b, then x0 + x1 = a: x1 first, x0 through it
        let a = vec![vec![e("1"), e("1")], vec![e("0"), e("1")]];
        let xs: Vec<Var> = (0..2).map(|i| atom::unknown(&format!("x{i}"))).collect();
        let order = solve_in_order(&a, &[e("a"), e("b")], &xs).unwrap().unwrap();
        assert_eq!(order[0].0, 1);
        assert!(order[0].1.equals(&e("b")));
        assert_eq!(order[1].0, 0);
        assert!(order[1].1.equals(&e("a").sub(&Expr::unknown("x1"))));
        // a dense block of 100: no equation alone or pair closes, the
        // triples are not tried (161,700 > MAX_ORDERED_SUBSETS), no order
        let n = 100;
        let dense: Vec<Vec<Expr>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| Expr::int(((i * 7 + j * 3) % 11 + 1) as i64))
                    .collect()
            })
            .collect();
        let xs: Vec<Var> = (0..n).map(|i| atom::unknown(&format!("y{i}"))).collect();
        let rhs = vec![Expr::one(); n];
        assert!(solve_in_order(&dense, &rhs, &xs).unwrap().is_none());
    }

    #[test]
    fn square_system() {
        // a·x0 + x1 = b, x0 − x1 = c
        let a = vec![vec![e("a"), e("1")], vec![e("1"), e("-1")]];
        let b = vec![e("b"), e("c")];
        let s = solve_rect(&a, &b, &syms(2)).expect("solve");
        assert!(s.values[0].equals(&e("(b + c)/(a + 1)")));
        assert!(s.values[1].equals(&e("(b - a*c)/(a + 1)")));
        assert!(s.shape.free.is_empty() && s.residuals.is_empty());
    }

    #[test]
    fn overdetermined_consistent_and_not() {
        // x0 = a, x1 = b, x0 + x1 = a + b (a check that holds)
        let a = vec![
            vec![e("1"), e("0")],
            vec![e("0"), e("1")],
            vec![e("1"), e("1")],
        ];
        let s = solve_rect(&a, &[e("a"), e("b"), e("a + b")], &syms(2)).expect("solve");
        assert_eq!(s.shape.dependent_rows, vec![2]);
        assert!(s.residuals[0].1.is_zero());
        let s = solve_rect(&a, &[e("a"), e("b"), e("a + c")], &syms(2)).expect("solve");
        assert!(s.residuals[0].1.equals(&e("c - b")));
    }

    #[test]
    fn underdetermined_has_free_unknowns() {
        // x0 + x1 + x2 = a, x1 − x2 = b: x2 free
        let a = vec![vec![e("1"), e("1"), e("1")], vec![e("0"), e("1"), e("-1")]];
        let s = solve_rect(&a, &[e("a"), e("b")], &syms(3)).expect("solve");
        assert_eq!(s.shape.free, vec![2]);
        let x2 = Expr::unknown("x2");
        assert!(s.values[1].equals(&e("b").add(&x2)));
        assert!(s.values[0].equals(&e("a - b").sub(&x2.scale(&crate::num::Q::from_i64(2)))));
    }

    #[test]
    fn a_zero_column_is_free() {
        // 0·x0 + x1 = a: x0 is free
        let a = vec![vec![Expr::zero(), e("1")]];
        let s = solve_rect(&a, &[e("a")], &syms(2)).expect("solve");
        assert_eq!(s.shape.free, vec![0]);
        assert!(s.values[1].equals(&e("a")));
    }
}
