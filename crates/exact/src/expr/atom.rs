//! Atoms: the indeterminates of qdot's polynomials.
//!
//! Every expression is a rational function whose variables are *atoms*:
//! parameters, coordinates and their time derivatives, time, π, and the
//! transcendental or algebraic functions that cannot be expanded further
//! (`sin(θ)`, `cos(θ)`, `√3`, `√(k·m)`, `exp(x)`, …). Atoms are interned in
//! one process-wide table; a [`Var`] is the index of an atom, with its
//! algebraic *kind* packed in the two low bits so the hot paths
//! (reduction of `cos²`, `√3²`) never touch the table:
//!
//! * `PLAIN` — no relation;
//! * `TRIG_COS` — `cos(u)`, with `cos(u)² = 1 − sin(u)²` (kept, not rationalized);
//! * `RADICAL` — `√n` or `√P`, with `r² = n` / `r² = P` (rationalized out of denominators).

use crate::expr::Expr;
use crate::poly::{Poly, Var};
use rustc_hash::FxHashMap;
use std::sync::{Arc, OnceLock, RwLock};

pub const KIND_MASK: Var = 0b11;
pub const PLAIN: Var = 0;
pub const TRIG_COS: Var = 1;
pub const RADICAL: Var = 2;

/// The kind bits of a variable.
#[inline]
pub fn kind(v: Var) -> Var {
    v & KIND_MASK
}

/// True for variables `r` with a relation `r² = P`.
#[inline]
pub fn is_reducible(v: Var) -> bool {
    kind(v) != PLAIN
}

/// True for variables that are rationalized out of denominators.
#[inline]
pub fn is_radical(v: Var) -> bool {
    kind(v) == RADICAL
}

/// What an atom stands for.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Atom {
    /// A constant symbol (real, positive).
    Param(Arc<str>),
    /// An unknown of a `solve` block: a real constant with no sign assumed.
    Unknown(Arc<str>),
    /// A generalized coordinate's `order`-th time derivative.
    Coord(Arc<str>, u32),
    /// A given function of time's `order`-th derivative (`functions f`:
    /// a support's motion, a control input): prescribed, not a coordinate.
    Given(Arc<str>, u32),
    /// Time `t`.
    Time,
    /// π.
    Pi,
    /// √n for a square-free integer n > 1 (stored as its decimal digits).
    Root(Arc<str>),
    /// √P for a non-constant primitive polynomial P.
    SqrtOf(Expr),
    /// sin(u) for a canonical base angle u.
    Sin(Expr),
    /// cos(u); always interned right after `Sin(u)`.
    Cos(Expr),
    Exp(Expr),
    Ln(Expr),
    Atan(Expr),
    /// asin(u), principal value in [−π/2, π/2].
    Asin(Expr),
    /// acos(u), principal value in [0, π].
    Acos(Expr),
    /// A factor that exists only in printed output (`cos(q1 − q2)` folded
    /// back from its expansion). Never part of a canonical expression.
    Shown(Arc<Folded>),
    /// An intermediate of a [`super::tape::Tape`]: a name standing for an
    /// exact expression defined before it. The canonical form treats it as
    /// an independent real symbol; only its tape knows its value, so
    /// differentiation through it is the tape's (its chain rule), never
    /// [`Expr::dt`]'s, which sees a constant.
    Named(Arc<NamedAtom>),
    /// A sum kept as one factor in printed output, written in parentheses
    /// (`(R − r)²`, `(l²·m + A − C)·cos²(θ)`): what the compact forms of
    /// `expr::compact` group. Never part of a canonical expression.
    Group(Arc<Poly>),
}

/// The identity of an intermediate ([`Atom::Named`]): its name, unique in
/// its tape, and the tape's number, unique in the process, so two tapes
/// that both name a `B2_11` never share an atom.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct NamedAtom {
    /// The name as printed.
    pub name: Arc<str>,
    /// How many times it is differentiated in time (printed as dots or
    /// primes, like a coordinate's): `alpha` and its rate `alpha'`.
    pub order: u32,
    /// The tape's number.
    pub tape: u64,
    /// The highest time derivative of a coordinate its value depends on.
    pub highest: Option<(Arc<str>, u32)>,
    /// Whether its value changes with time.
    pub moving: bool,
}

/// `cos(a ∓ b)` or `sin(a ± b)`, folded back by the addition theorems for
/// display ([`Atom::Shown`]).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Folded {
    /// Cosine (else sine).
    pub cos: bool,
    pub a: Expr,
    pub b: Expr,
    /// `a − b` (else `a + b`).
    pub minus: bool,
}

impl Atom {
    /// The argument of a function atom (√P, sin, cos, exp, ln, atan, asin,
    /// acos); None for symbols, π and √n.
    pub fn argument(&self) -> Option<&Expr> {
        #[deny(
            clippy::wildcard_enum_match_arm,
            clippy::match_wildcard_for_single_variants
        )]
        match self {
            Atom::SqrtOf(u)
            | Atom::Sin(u)
            | Atom::Cos(u)
            | Atom::Exp(u)
            | Atom::Ln(u)
            | Atom::Atan(u)
            | Atom::Asin(u)
            | Atom::Acos(u) => Some(u),
            Atom::Param(_)
            | Atom::Unknown(_)
            | Atom::Named(_)
            | Atom::Coord(..)
            | Atom::Given(..)
            | Atom::Time
            | Atom::Pi
            | Atom::Root(_)
            | Atom::Shown(_)
            | Atom::Group(_) => None,
        }
    }
}

struct Entry {
    atom: Atom,
    /// How many function atoms are nested in this one, itself included
    /// (0 for symbols, π and √n): the depth every walk into arguments
    /// recurses to.
    depth: u32,
    /// The number of symbols the atom takes written out, its argument's
    /// shared atoms counted at every occurrence (saturating): what printing
    /// it costs. Definitions that each apply two functions to the previous
    /// one double it per line.
    size: u64,
    /// The highest time derivative of a coordinate in the atom (itself or
    /// its argument): what a walk into arguments would find, kept so that
    /// no walk re-enters shared arguments.
    highest: Option<(Arc<str>, u32)>,
    /// Whether the atom changes with time (a coordinate, t, or a function
    /// of them).
    moving: bool,
    /// Every atom inside the argument, at any depth, sorted: what the atom
    /// depends on, found without walking shared arguments again.
    inner: Arc<[Var]>,
    /// For reducible atoms: the polynomial P with atom² = P.
    square: Option<Poly>,
    /// The atom's place in the history-independent order ([`stable_cmp`]).
    key: Arc<str>,
    /// A number whose relations the canonical form may not know: a
    /// function atom of constants only (`sin(π/7)`, `√(5 − √5)`,
    /// `exp(1)`); see [`is_opaque_constant`].
    opaque: bool,
}

/// Whether an atom with an opaque constant has been interned in this
/// process: while none has, no zero test needs the numeric check.
static OPAQUE_SEEN: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

#[derive(Default)]
struct Table {
    entries: Vec<Entry>,
    index: FxHashMap<Atom, Var>,
    /// For each power product m of a trig base angle c·m, the first c.
    trig_bases: FxHashMap<crate::poly::Mono, crate::num::Q>,
}

/// Whether two trig base angles c·m and c'·m with c ≠ c' (x and x/2) have
/// been interned in this process: see [`any_commensurable_angles`].
static COMMENSURABLE_SEEN: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

fn table() -> &'static RwLock<Table> {
    static T: OnceLock<RwLock<Table>> = OnceLock::new();
    T.get_or_init(|| RwLock::new(Table::default()))
}

fn read() -> std::sync::RwLockReadGuard<'static, Table> {
    match table().read() {
        Ok(g) => g,
        Err(p) => p.into_inner(),
    }
}

fn write() -> std::sync::RwLockWriteGuard<'static, Table> {
    match table().write() {
        Ok(g) => g,
        Err(p) => p.into_inner(),
    }
}

impl Table {
    fn push(&mut self, atom: Atom, kind: Var, square: Option<Poly>) -> Var {
        let v = ((self.entries.len() as Var) << 2) | kind;
        let mut inner: Vec<Var> = Vec::new();
        let (depth, size, highest, moving) = match (&atom, atom.argument()) {
            (_, Some(u)) => {
                let vars = u.vars();
                for &w in &vars {
                    inner.push(w);
                    if let Some(e) = self.entry(w) {
                        inner.extend_from_slice(&e.inner);
                    }
                }
                inner.sort_unstable();
                inner.dedup();
                let highest = vars
                    .iter()
                    .filter_map(|&w| self.entry(w).and_then(|e| e.highest.clone()))
                    .max_by_key(|(_, k)| *k);
                let moving = vars
                    .iter()
                    .any(|&w| self.entry(w).is_some_and(|e| e.moving));
                let depth = 1 + self.max_depth(vars.into_iter());
                (depth, 1 + self.written_size(u), highest, moving)
            }
            (Atom::Coord(name, k), None) => (0, 1, Some((name.clone(), *k)), true),
            (Atom::Time | Atom::Given(..), None) => (0, 1, None, true),
            (Atom::Named(n), None) => (0, 1, n.highest.clone(), n.moving),
            (Atom::Shown(f), None) => {
                let vars: Vec<Var> = f.a.vars().into_iter().chain(f.b.vars()).collect();
                (
                    0,
                    1 + self.written_size(&f.a) + self.written_size(&f.b),
                    None,
                    vars.iter()
                        .any(|&w| self.entry(w).is_some_and(|e| e.moving)),
                )
            }
            (Atom::Group(p), None) => {
                let vars = p.vars();
                let size = p.terms().iter().fold(1u64, |n, (m, _)| {
                    m.vars().fold(n.saturating_add(1), |n, w| {
                        n.saturating_add(self.entry(w).map_or(1, |e| e.size))
                    })
                });
                (
                    0,
                    size,
                    None,
                    vars.iter()
                        .any(|&w| self.entry(w).is_some_and(|e| e.moving)),
                )
            }
            _ => (0, 1, None, false),
        };
        // constants only inside: π, √n and other such atoms, at any depth
        let opaque = atom.argument().is_some()
            && inner.iter().all(|&w| {
                self.entry(w).is_some_and(|e| {
                    matches!(e.atom, Atom::Pi | Atom::Root(_)) || e.atom.argument().is_some()
                })
            });
        if opaque {
            OPAQUE_SEEN.store(true, std::sync::atomic::Ordering::Relaxed);
        }
        if let (Atom::Sin(_), Some((m, c))) = (&atom, single_term(atom.argument())) {
            match self.trig_bases.get(&m) {
                Some(first) if *first != c => {
                    COMMENSURABLE_SEEN.store(true, std::sync::atomic::Ordering::Relaxed)
                }
                Some(_) => {}
                None => {
                    self.trig_bases.insert(m, c);
                }
            }
        }
        let key = self.stable_key(&atom);
        self.entries.push(Entry {
            key,
            atom: atom.clone(),
            depth,
            size,
            highest,
            moving,
            inner: inner.into(),
            square,
            opaque,
        });
        self.index.insert(atom, v);
        v
    }

    /// The key of [`stable_cmp`]: a class (the printers' factor order), then
    /// the name, or the function and its argument written with the keys of
    /// its atoms; a long one is replaced by a hash of it, so that keys stay
    /// short however deeply atoms nest.
    fn stable_key(&self, atom: &Atom) -> Arc<str> {
        let fun = |name: &str, u: &Expr| format!("4{name}({})", self.expr_key(u));
        let named = |class: char, name: &str, tag: char, k: u32| {
            format!("{class}{}\u{1}{name}\u{1}{tag}{k:010}", name.to_lowercase())
        };
        let key = match atom {
            Atom::Param(n) => named('0', n, 'p', 0),
            Atom::Unknown(n) => named('0', n, 'u', 0),
            Atom::Pi => "1".into(),
            Atom::Root(n) => format!("2{:010}{n}", n.len()),
            Atom::SqrtOf(u) => format!("2sqrt({})", self.expr_key(u)),
            Atom::Time => "3".into(),
            Atom::Given(n, k) => named('3', n, 'g', *k),
            Atom::Named(n) => format!("{}\u{1}{}", named('3', &n.name, 'n', n.order), n.tape),
            Atom::Sin(u) => fun("sin", u),
            Atom::Cos(u) => fun("cos", u),
            Atom::Exp(u) => fun("exp", u),
            Atom::Ln(u) => fun("ln", u),
            Atom::Atan(u) => fun("atan", u),
            Atom::Asin(u) => fun("asin", u),
            Atom::Acos(u) => fun("acos", u),
            Atom::Shown(f) => format!(
                "4{}({}{}{})",
                if f.cos { "cos" } else { "sin" },
                self.expr_key(&f.a),
                if f.minus { '-' } else { '+' },
                self.expr_key(&f.b)
            ),
            Atom::Group(p) => format!("5({})", self.poly_key(p)),
            Atom::Coord(n, k) => named('6', n, 'c', *k),
        };
        if key.len() <= MAX_KEY {
            return key.into();
        }
        let hash = |seed: u64| {
            use std::hash::{Hash, Hasher};
            let mut h = rustc_hash::FxHasher::default();
            seed.hash(&mut h);
            key.hash(&mut h);
            h.finish()
        };
        let head: String = key.chars().take(8).collect();
        format!("{head}#{:016x}{:016x}", hash(1), hash(2)).into()
    }

    fn expr_key(&self, e: &Expr) -> String {
        format!("{}/{}", self.poly_key(e.num()), self.poly_key(e.den()))
    }

    /// A polynomial's terms, each its coefficient and its atoms' keys, in
    /// the order of those keys.
    fn poly_key(&self, p: &Poly) -> String {
        let mut terms: Vec<String> = p
            .terms()
            .iter()
            .map(|(m, c)| {
                let mut fs: Vec<String> = m
                    .pairs()
                    .iter()
                    .map(|&(v, e)| {
                        let k = self.entry(v).map_or("?", |e| &e.key);
                        format!("[{k}]{e}")
                    })
                    .collect();
                fs.sort();
                format!("{}{c}", fs.concat())
            })
            .collect();
        terms.sort();
        terms.join(";")
    }

    fn entry(&self, v: Var) -> Option<&Entry> {
        self.entries.get((v >> 2) as usize)
    }

    /// Symbols of `e` written out: per term its coefficient and each
    /// factor's atom (exponents are not counted).
    fn written_size(&self, e: &Expr) -> u64 {
        let mut n: u64 = 0;
        for p in [e.num(), e.den()] {
            for (m, _) in p.terms() {
                n = n.saturating_add(1);
                for w in m.vars() {
                    n = n.saturating_add(self.entry(w).map_or(1, |e| e.size));
                }
            }
        }
        n
    }

    fn max_depth(&self, vars: impl Iterator<Item = Var>) -> u32 {
        vars.filter_map(|v| self.entry(v))
            .map(|e| e.depth)
            .max()
            .unwrap_or(0)
    }
}

pub use crate::limits::MAX_FUNCTION_NESTING as MAX_NESTING;

/// How deeply function atoms nest in `e` (0 for a polynomial in symbols).
pub fn nesting_depth(e: &Expr) -> u32 {
    read().max_depth(e.vars().into_iter())
}

/// How many symbols `e` takes written out (saturating): what printing it
/// costs, shared arguments counted at each occurrence. Linear in the
/// size of `e`'s own polynomials.
pub fn written_size(e: &Expr) -> u64 {
    read().written_size(e)
}

/// The largest written size ([`written_size`]) of a function atom in `e`,
/// argument included; 0 when `e` has none.
pub fn largest_argument(e: &Expr) -> u64 {
    let t = read();
    e.vars()
        .into_iter()
        .filter_map(|v| t.entry(v))
        .filter(|e| e.atom.argument().is_some())
        .map(|e| e.size)
        .max()
        .unwrap_or(0)
}

/// The highest time derivative of a coordinate in the atom `v`, itself or
/// in its argument.
pub fn highest_time_derivative(v: Var) -> Option<(Arc<str>, u32)> {
    read().entry(v).and_then(|e| e.highest.clone())
}

/// Whether atom `a` is `v` or has `v` in its argument, at any depth.
pub fn contains(a: Var, v: Var) -> bool {
    a == v
        || read()
            .entry(a)
            .is_some_and(|e| e.inner.binary_search(&v).is_ok())
}

/// The atoms inside `a`'s argument, at any depth, sorted (empty for
/// symbols).
pub fn inner_atoms(a: Var) -> Arc<[Var]> {
    read()
        .entry(a)
        .map_or_else(|| Arc::from(Vec::new()), |e| e.inner.clone())
}

/// Whether the atom `v` changes with time: a coordinate or its
/// derivative, t, or a function of them.
pub fn is_moving(v: Var) -> bool {
    read().entry(v).is_some_and(|e| e.moving)
}

/// The variable of a plain atom (parameter, coordinate, time, π, exp, ln, atan).
pub fn intern(atom: Atom) -> Var {
    if let Some(&v) = read().index.get(&atom) {
        return v;
    }
    let mut t = write();
    if let Some(&v) = t.index.get(&atom) {
        return v;
    }
    debug_assert!(!matches!(
        atom,
        Atom::Sin(_) | Atom::Cos(_) | Atom::Root(_) | Atom::SqrtOf(_)
    ));
    t.push(atom, PLAIN, None)
}

/// The pair (sin u, cos u) for a canonical base angle `u`.
pub fn intern_trig(u: &Expr) -> (Var, Var) {
    let key = Atom::Sin(u.clone());
    {
        let t = read();
        if let (Some(&s), Some(&c)) = (t.index.get(&key), t.index.get(&Atom::Cos(u.clone()))) {
            return (s, c);
        }
    }
    let mut t = write();
    if let (Some(&s), Some(&c)) = (t.index.get(&key), t.index.get(&Atom::Cos(u.clone()))) {
        return (s, c);
    }
    let s = t.push(key, PLAIN, None);
    // 1 − s², built without arithmetic: nothing that may be cancelled
    // (crate::cancel) runs while the table is locked
    let square = Poly::from_terms(vec![
        (crate::poly::Mono::one(), crate::num::Q::one()),
        (
            crate::poly::Mono::var_pow(s, 2),
            crate::num::Q::from_i64(-1),
        ),
    ]);
    let c = t.push(Atom::Cos(u.clone()), TRIG_COS, Some(square));
    (s, c)
}

/// A radical atom: `Root(n)` with square n, or `SqrtOf(P)` with square P.
pub fn intern_radical(atom: Atom, square: Poly) -> Var {
    if let Some(&v) = read().index.get(&atom) {
        return v;
    }
    let mut t = write();
    if let Some(&v) = t.index.get(&atom) {
        return v;
    }
    t.push(atom, RADICAL, Some(square))
}

/// The atom behind a variable.
pub fn atom(v: Var) -> Atom {
    let t = read();
    match t.entries.get((v >> 2) as usize) {
        Some(e) => e.atom.clone(),
        None => Atom::Param(Arc::from(format!("?{v}"))),
    }
}

/// Keys longer than this are hashed ([`Table::stable_key`]).
const MAX_KEY: usize = 256;

/// The atoms in an order independent of the process's history (the ids
/// follow the order of first use): by kind as the printers order factors
/// (parameters, π, radicals, time, functions, coordinates), then by name,
/// a function by its argument. Every choice that reaches output and is not
/// the printers' own (the sign kept in `sin(u)`'s argument, the order of a
/// generated program's operands) is made by it.
pub fn stable_cmp(a: Var, b: Var) -> std::cmp::Ordering {
    if a == b {
        return std::cmp::Ordering::Equal;
    }
    let t = read();
    match (t.entry(a), t.entry(b)) {
        (Some(x), Some(y)) => x.key.cmp(&y.key).then(a.cmp(&b)),
        _ => a.cmp(&b),
    }
}

/// The key [`stable_cmp`] compares, to sort by once per atom.
pub fn stable_key(v: Var) -> Arc<str> {
    read()
        .entry(v)
        .map_or_else(|| Arc::from(format!("?{v}")), |e| e.key.clone())
}

/// A monomial's key in the history-independent order ([`stable_mono_key`]).
pub type MonoKey = Vec<(Arc<str>, u32)>;

/// A monomial's atoms with their exponents, in [`stable_cmp`]'s order: two
/// monomials compare by it as a history-independent order.
pub fn stable_mono_key(m: &crate::poly::Mono) -> MonoKey {
    let t = read();
    let mut k: Vec<(Arc<str>, u32)> = m
        .pairs()
        .iter()
        .map(|&(v, e)| {
            let key = t
                .entry(v)
                .map_or_else(|| Arc::from(format!("?{v}")), |x| x.key.clone());
            (key, e)
        })
        .collect();
    k.sort();
    k
}

/// `p`'s terms as ([`stable_mono_key`], coefficient), in that key's
/// order: polynomials compare by it independently of the ids.
pub fn stable_poly_key(p: &Poly) -> Vec<(MonoKey, crate::num::Q)> {
    let mut k: Vec<_> = p
        .terms()
        .iter()
        .map(|(m, c)| (stable_mono_key(m), c.clone()))
        .collect();
    k.sort();
    k
}

/// `f` with each factor's sign (its first term positive,
/// [`leads_negative_stable`]) and the factors' order (degree, terms, then
/// [`stable_poly_key`]) history-independent, the unit adjusted: what a
/// printed factorization shows. [`crate::poly::factor`] itself orders by
/// the ids, as a polynomial library over bare variables must.
pub fn stable_factorization(
    mut f: crate::poly::factor::Factorization,
) -> crate::poly::factor::Factorization {
    for (g, e) in f.factors.iter_mut() {
        if leads_negative_stable(g) {
            *g = -&*g;
            if *e % 2 == 1 {
                f.unit = -f.unit.clone();
            }
        }
    }
    f.factors
        .sort_by_cached_key(|(g, e)| (g.total_degree(), g.len(), stable_poly_key(g), *e));
    f
}

/// `p` factored over ℚ within `subsets` recombination trials
/// ([`crate::poly::factor::factor_within`]) as [`stable_factorization`]
/// prints it, by a search independent of the ids: the factorization
/// chooses its main variable, evaluation points and lifting order by the
/// variables' order, so it runs on `p` with its atoms renamed by rank in
/// [`stable_cmp`]'s order. Otherwise whether it fits the allowance (a
/// result printed factored or expanded) would follow the process's history.
pub fn stable_factor_within(
    p: &Poly,
    subsets: usize,
) -> Option<crate::poly::factor::Factorization> {
    let mut vars = p.vars();
    vars.sort_by(|&a, &b| stable_cmp(a, b));
    let rank: FxHashMap<Var, Var> = vars
        .iter()
        .enumerate()
        .map(|(i, &v)| (v, i as Var))
        .collect();
    let ranked = p.map_vars(&|v| rank.get(&v).copied().unwrap_or(v));
    let mut f = crate::poly::factor::factor_within(&ranked, subsets)?;
    let back = |v: Var| vars.get(v as usize).copied().unwrap_or(v);
    for (g, _) in f.factors.iter_mut() {
        *g = g.map_vars(&back);
    }
    Some(stable_factorization(f))
}

/// Whether `p`'s first term in the history-independent order (the
/// highest degree, then [`stable_mono_key`]) has a negative coefficient:
/// the sign the canonical forms normalize (`sin(u)` keeps `u` or `−u`)
/// without reference to the ids.
pub fn leads_negative_stable(p: &Poly) -> bool {
    stable_leading_coeff(p).is_some_and(|c| c.is_negative())
}

/// The coefficient of `p`'s first term in the history-independent order
/// of [`leads_negative_stable`]; `None` for 0. Dividing a quotient's both
/// sides by its denominator's makes it the same whatever the ids (the
/// canonical form makes the denominator monic in the ids' order).
pub fn stable_leading_coeff(p: &Poly) -> Option<&crate::num::Q> {
    p.terms()
        .iter()
        .map(|(m, c)| ((std::cmp::Reverse(m.total_degree()), stable_mono_key(m)), c))
        .min_by(|a, b| a.0.cmp(&b.0))
        .map(|(_, c)| c)
}

/// Whether `v` is a function of constants alone (`sin(π/7)`, `cos(1)`,
/// `√(5 − √5)`, `exp(1)`): a real number that the canonical form relates to
/// others only by r² = P and sin² + cos² = 1 and the multiple-angle
/// formulas, so a polynomial in such atoms can be zero without its
/// canonical form being zero (cos(π/7) − cos(2π/7) + cos(3π/7) − 1/2). π and √n are not
/// opaque: polynomials in them are zero exactly when their canonical form is.
pub fn is_opaque_constant(v: Var) -> bool {
    read().entry(v).is_some_and(|e| e.opaque)
}

/// The power product and coefficient of a one-term polynomial argument
/// with at least one atom (`x/2` → (x, 1/2)).
pub fn single_term(u: Option<&Expr>) -> Option<(crate::poly::Mono, crate::num::Q)> {
    let u = u?;
    match (u.is_poly(), u.num().terms()) {
        (true, [(m, c)]) if !m.is_one() => Some((m.clone(), c.clone())),
        _ => None,
    }
}

/// Whether sin and cos of two rationally related angles c·m and c'·m
/// (x and x/2, π/7 and π/14) have been interned. They are independent
/// atoms, so sin x − 2·sin(x/2)·cos(x/2) is zero without a zero canonical
/// form ([`super::hidden_zero`]).
pub fn any_commensurable_angles() -> bool {
    COMMENSURABLE_SEEN.load(std::sync::atomic::Ordering::Relaxed)
}

/// Whether any opaque constant ([`is_opaque_constant`]) has been interned.
pub fn any_opaque_constant() -> bool {
    OPAQUE_SEEN.load(std::sync::atomic::Ordering::Relaxed)
}

/// For a reducible variable r, the polynomial P with r² = P.
pub fn square_of(v: Var) -> Option<Poly> {
    let t = read();
    t.entries
        .get((v >> 2) as usize)
        .and_then(|e| e.square.clone())
}

/// Shorthands.
pub fn param(name: &str) -> Var {
    intern(Atom::Param(Arc::from(name)))
}
/// A tape's intermediate (see [`Atom::Named`]).
pub fn named(n: NamedAtom) -> Var {
    intern(Atom::Named(Arc::new(n)))
}
pub fn unknown(name: &str) -> Var {
    intern(Atom::Unknown(Arc::from(name)))
}
pub fn coord(name: &str, order: u32) -> Var {
    intern(Atom::Coord(Arc::from(name), order))
}
pub fn given(name: &str, order: u32) -> Var {
    intern(Atom::Given(Arc::from(name), order))
}
pub fn time() -> Var {
    intern(Atom::Time)
}
pub fn pi() -> Var {
    intern(Atom::Pi)
}

/// The sine partner of a cosine variable (they are interned consecutively).
pub fn sin_partner(cos: Var) -> Var {
    // cos was pushed right after sin: index − 1, kind PLAIN.
    (((cos >> 2) - 1) << 2) | PLAIN
}

/// The cosine partner of a sine variable, if `v` is `Sin(u)`.
pub fn cos_partner(sin: Var) -> Option<Var> {
    let t = read();
    match t.entries.get((sin >> 2) as usize) {
        Some(Entry {
            atom: Atom::Sin(_), ..
        }) => Some((((sin >> 2) + 1) << 2) | TRIG_COS),
        _ => None,
    }
}
