//! The work budget of exact computation: a bound on the size (terms) of the
//! polynomials qdot builds, so that an expression that explodes —
//! `(a+b+c+d)^200`, a 10×10 symbolic system, repeated squaring — stops with
//! a clear error instead of exhausting time and memory.
//!
//! A front end runs a computation [`within`] a budget. The hot spots of
//! polynomial arithmetic call [`check_terms`] with the size they reached;
//! past the budget the thread unwinds with a [`TooLarge`] payload (by
//! `resume_unwind`: no panic message), which `within` turns into an `Err`.
//! The [`Computation`] a thread declares ([`enter`]) (the statement being evaluated,
//! the phase of a command) is carried in the error.
//!
//! Where no budget is installed, the default one applies
//! ([`crate::limits::DEFAULT_MAX_TERMS`]): no work is unbounded because
//! nobody asked for a bound. The library's entry points that return a
//! `Result` run [`bounded`], so past the default they return the error;
//! an operation that has no `Result` (arithmetic on expressions), called
//! outside any budget, panics with the budget's message instead. A caller
//! who wants no bound asks for it: `within(UNLIMITED, …)`.

use std::cell::{Cell, RefCell};
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};

thread_local! {
    /// The budget [`within`] installed; `None`: none (the default applies).
    static LIMIT: Cell<Option<usize>> = const { Cell::new(None) };
    static CONTEXT: RefCell<Vec<Computation>> = const { RefCell::new(Vec::new()) };
    static BIG_WORK: Cell<u64> = const { Cell::new(0) };
}

/// What was being computed: a description and, for a statement, its byte
/// range in the source.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Computation {
    /// "evaluating `E`", "deriving Hamilton's equations".
    pub what: String,
    /// The statement's byte range in the source, if a statement.
    pub span: Option<(usize, usize)>,
}

/// The budget was exceeded: `terms` were reached with a limit of `limit`,
/// while computing `context` (the innermost one declared).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TooLarge {
    /// How much was reached, in the unit of `measure`.
    pub terms: usize,
    /// The budget, in terms.
    pub limit: usize,
    /// The innermost context declared ([`enter`]).
    pub context: Option<Computation>,
    /// What passed the budget.
    pub measure: Measure,
}

/// What passed the budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Measure {
    /// A polynomial's terms.
    Terms,
    /// A product of polynomials of these sizes, refused before it began
    /// (its work, not its result, was over budget).
    Product(usize, usize),
    /// An expression's symbols written out ([`check_printed`]): `terms`
    /// counts symbols.
    Printed,
    /// The term products of a whole elimination ([`WorkMeter`]): `terms`
    /// counts them.
    Work,
    /// The size of the terms a whole elimination built ([`WorkMeter`]):
    /// `terms` counts their variable powers.
    Built,
    /// The subsets of modular factors a factorization tried to recombine
    /// ([`check_subsets`]): `terms` counts them.
    Subsets,
    /// An exact division of polynomials of these sizes, stopped when its
    /// term products passed the budget's ([`check_division`]).
    Division(usize, usize),
    /// Arithmetic on numbers past machine size ([`charge_big_numbers`]):
    /// `terms` counts word products, the last operand had this many digits.
    Digits(usize),
}

impl TooLarge {
    /// "expression too large: 2,000,001 terms while evaluating `a30`
    /// (the limit is 2,000,000)".
    pub fn message(&self) -> String {
        let what = match &self.context {
            Some(c) => format!(" while {}", c.what),
            None => String::new(),
        };
        match self.measure {
            Measure::Product(a, b) => format!(
                "expression too large: a product of {} by {} terms{what} (the limit is {} terms, and {} term products)",
                grouped(a),
                grouped(b),
                grouped(self.limit),
                grouped(self.limit.saturating_mul(PRODUCTS_PER_TERM))
            ),
            Measure::Terms => format!(
                "expression too large: {} terms{what} (the limit is {})",
                grouped(self.terms),
                grouped(self.limit)
            ),
            Measure::Work => format!(
                "expression too large: {} term products in all{what} (the limit is {} terms, and {} term products in all)",
                grouped(self.terms),
                grouped(self.limit),
                grouped(self.limit.saturating_mul(ELIMINATION_PRODUCTS_PER_TERM))
            ),
            Measure::Built => format!(
                "expression too large: {} variable powers in the terms built in all{what} (the limit is {} terms, and {} variable powers in the terms built in all)",
                grouped(self.terms),
                grouped(self.limit),
                grouped(self.limit.saturating_mul(ELIMINATION_POWERS_PER_TERM))
            ),
            Measure::Subsets => format!(
                "factoring too costly: {} subsets of modular factors tried{what} (the limit is {} terms, and {} subsets)",
                grouped(self.terms),
                grouped(self.limit),
                grouped(self.limit / TERMS_PER_SUBSET)
            ),
            Measure::Division(a, b) => format!(
                "expression too large: a division of {} by {} terms{what} (the limit is {} terms, and {} term products)",
                grouped(a),
                grouped(b),
                grouped(self.limit),
                grouped(self.limit.saturating_mul(PRODUCTS_PER_TERM))
            ),
            Measure::Digits(digits) => format!(
                "exact arithmetic too costly: {} word products on numbers of up to {} digits{what} (the limit is {} terms, and {} word products)",
                grouped(self.terms),
                grouped(digits),
                grouped(self.limit),
                grouped(self.limit.saturating_mul(WORD_PRODUCTS_PER_TERM))
            ),
            Measure::Printed => format!(
                "expression too large to print: {} symbols written out{what} (the limit is {})",
                grouped(self.terms),
                grouped(self.limit)
            ),
        }
    }
}

/// `1234567` as `1,234,567`.
pub fn grouped(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::with_capacity(s.len() + s.len() / 3);
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// The budget of no bound at all: `within(UNLIMITED, f)` runs `f` to its
/// end whatever it costs.
pub const UNLIMITED: usize = usize::MAX;

/// Run `f` with at most `max_terms` terms in any polynomial it builds
/// ([`UNLIMITED`]: no bound). Budgets nest: the inner one applies, and
/// the outer is restored after.
pub fn within<T>(max_terms: usize, f: impl FnOnce() -> T) -> Result<T, TooLarge> {
    let outer = LIMIT.with(|l| l.replace(Some(max_terms)));
    // the work of big numbers is counted from the outermost budget on: a
    // nested one goes on counting (a fresh count would allow it its limit
    // again on top of the outer's)
    let outermost = outer.is_none();
    if outermost {
        BIG_WORK.with(|w| w.set(0));
    }
    let depth = CONTEXT.with(|c| c.borrow().len());
    let r = catch_unwind(AssertUnwindSafe(f));
    LIMIT.with(|l| l.set(outer));
    if outermost {
        BIG_WORK.with(|w| w.set(0));
    }
    CONTEXT.with(|c| c.borrow_mut().truncate(depth));
    match r {
        Ok(v) => Ok(v),
        Err(payload) => match payload.downcast::<TooLarge>() {
            Ok(t) => Err(*t),
            Err(other) => resume_unwind(other),
        },
    }
}

/// Run `f` within the budget in force, or, where none is installed,
/// within the default one; the budget's error becomes `f`'s by `error`.
/// The library's entry points run so: a caller who installed no budget
/// gets the default's error, never a computation without end.
pub fn bounded<T, E>(
    f: impl FnOnce() -> Result<T, E>,
    error: impl FnOnce(TooLarge) -> E,
) -> Result<T, E> {
    if installed() {
        return f();
    }
    within(crate::limits::DEFAULT_MAX_TERMS, f).unwrap_or_else(|e| Err(error(e)))
}

/// Whether a budget is installed on this thread ([`within`]).
pub fn installed() -> bool {
    LIMIT.with(Cell::get).is_some()
}

/// Try `f` within at most `max_terms` terms, as one step of an algorithm
/// that falls back when it fails (expanded, else structured): nested in
/// the budget in force, so the smaller of the two applies and the work of
/// big numbers goes on counting toward the outer one; past it, the error
/// is a value for the caller to fall back on. The one nested budget of
/// the engine (the context that runs a command installs the outer one).
pub fn probe<T>(max_terms: usize, f: impl FnOnce() -> T) -> Result<T, TooLarge> {
    within(max_terms.min(limit()), f)
}

/// Declare what the thread computes until the guard is dropped (for the
/// error of [`within`]). `what` is only built under a bound.
pub fn enter(what: impl FnOnce() -> String, span: Option<(usize, usize)>) -> ComputationGuard {
    // no bound, no bookkeeping
    if limit() == UNLIMITED {
        return ComputationGuard { active: false };
    }
    CONTEXT.with(|c| c.borrow_mut().push(Computation { what: what(), span }));
    ComputationGuard { active: true }
}

/// Ends the context of [`enter`] when dropped.
#[must_use = "the context lasts as long as the guard"]
pub struct ComputationGuard {
    active: bool,
}

impl Drop for ComputationGuard {
    fn drop(&mut self) {
        if self.active {
            CONTEXT.with(|c| c.borrow_mut().pop());
        }
    }
}

/// The budget of this thread: the one installed, else the default
/// ([`UNLIMITED`]: none).
#[inline]
pub fn limit() -> usize {
    LIMIT
        .with(Cell::get)
        .unwrap_or(crate::limits::DEFAULT_MAX_TERMS)
}

/// Unwind with [`TooLarge`] if `terms` exceeds this thread's budget.
#[inline]
pub fn check_terms(terms: usize) {
    let limit = limit();
    if terms > limit {
        exceeded(terms, limit);
    }
}

/// How many term-by-term products one multiplication may take per term of
/// the budget: the work of a product grows as the product of the sizes
/// even when the result stays small (squaring a 700,000-term polynomial).
pub const PRODUCTS_PER_TERM: usize = 8;

/// Unwind with [`TooLarge`] if multiplying polynomials of `a` and `b`
/// terms would take more than the budget's term products.
#[inline]
pub fn check_product(a: usize, b: usize) {
    let limit = limit();
    if a.saturating_mul(b) > limit.saturating_mul(PRODUCTS_PER_TERM) {
        exceeded_with(a.saturating_mul(b), limit, Measure::Product(a, b));
    }
}

/// How many term-by-term products a whole elimination ([`WorkMeter`]) may
/// take per term of the budget. Its n³ products can each stay under
/// [`PRODUCTS_PER_TERM`] and still add up to minutes.
pub const ELIMINATION_PRODUCTS_PER_TERM: usize = 64;

/// How many variable powers (a variable and its exponent in one term's
/// monomial) the terms a whole elimination builds may hold in all, per
/// term of the budget. Term products do not see a term's width: a term of
/// 30 masses, lengths and angles is hashed, stored, sorted and divided at
/// the cost of its powers, and when few products cancel every product is a
/// new term: the planar chains of 30 rods took 20 to 50 s (and 1.5 GB)
/// within their term products. At 16, the default budget allows 32
/// million powers, 1 to 4 s on those chains; the examples and the book's
/// scenes build at most 7 million.
pub const ELIMINATION_POWERS_PER_TERM: usize = 16;

/// The work of a computation made of many products (an elimination): each
/// [`charge`](WorkMeter::charge) adds one product's term products, and past
/// [`ELIMINATION_PRODUCTS_PER_TERM`] × the budget it unwinds; each
/// [`charge_built`](WorkMeter::charge_built) adds the variable powers of the
/// terms a product or a quotient built, and past
/// [`ELIMINATION_POWERS_PER_TERM`] × the budget it unwinds.
#[derive(Debug, Default)]
pub struct WorkMeter {
    used: Cell<usize>,
    built: Cell<usize>,
}

impl WorkMeter {
    /// A meter at zero.
    pub fn new() -> WorkMeter {
        WorkMeter::default()
    }

    /// Charge a product of polynomials of `a` and `b` terms (or a division
    /// of an `a`-term by a `b`-term one).
    #[inline]
    pub fn charge(&self, a: usize, b: usize) {
        let used = self.used.get().saturating_add(a.saturating_mul(b));
        self.used.set(used);
        let limit = limit();
        if used > limit.saturating_mul(ELIMINATION_PRODUCTS_PER_TERM) {
            exceeded_with(used, limit, Measure::Work);
        }
    }

    /// Charge terms built (a product's, a quotient's) that hold `powers`
    /// variable powers in all.
    #[inline]
    pub fn charge_built(&self, powers: usize) {
        let built = self.built.get().saturating_add(powers);
        self.built.set(built);
        let limit = limit();
        if built > limit.saturating_mul(ELIMINATION_POWERS_PER_TERM) {
            exceeded_with(built, limit, Measure::Built);
        }
    }

    /// The term products charged so far.
    pub fn used(&self) -> usize {
        self.used.get()
    }

    /// The variable powers of the terms built so far.
    pub fn built(&self) -> usize {
        self.built.get()
    }
}

/// How many terms of the budget one subset of modular factors tried in a
/// factorization's recombination stands for: a trial multiplies the
/// subset's factors and divides, so each costs many coefficient products,
/// and the subsets of r factors number 2^(r−1) (Swinnerton-Dyer
/// polynomials split into halves of their degree modulo every prime).
pub const TERMS_PER_SUBSET: usize = 8;

/// Unwind with [`TooLarge`] once a factorization has tried more than
/// budget / [`TERMS_PER_SUBSET`] subsets of modular factors.
#[inline]
pub fn check_subsets(tried: usize) {
    let limit = limit();
    if tried > limit / TERMS_PER_SUBSET {
        exceeded_with(tried, limit, Measure::Subsets);
    }
}

/// Unwind with [`TooLarge`] once an exact division of an `a`-term by a
/// `b`-term polynomial has taken `work` term products, more than a
/// product may ([`PRODUCTS_PER_TERM`] × the budget).
#[inline]
pub fn check_division(work: usize, a: usize, b: usize) {
    let limit = limit();
    if work > limit.saturating_mul(PRODUCTS_PER_TERM) {
        exceeded_with(work, limit, Measure::Division(a, b));
    }
}

/// How many word products (64-bit limb by limb) of arithmetic on big
/// numbers one term of the budget stands for, over a whole [`within`].
/// Terms do not see a coefficient's size: `1e308·ẋ²` keeps the terms of
/// `ẋ²`, yet each product of its 1,000-digit powers costs thousands of
/// word products, and a rational's gcd more (a Hamiltonian of such a
/// scene took half a minute under a budget it never passed). At 50, the
/// default budget allows 10⁸ (about 2 s); the test suite's scenes take
/// at most 8·10⁵.
pub const WORD_PRODUCTS_PER_TERM: usize = 50;

/// Charge one arithmetic operation on numbers of `a` and `b` 64-bit words
/// (numerator and denominator together), the larger having `digits`
/// digits; unwind with [`TooLarge`] once the outermost [`within`] has charged more
/// than [`WORD_PRODUCTS_PER_TERM`] × the budget. Only operations past
/// machine size call it. The count starts with the outermost [`within`]:
/// outside one (and without a bound) nothing is charged.
#[inline]
pub fn charge_big_numbers(a: usize, b: usize, digits: impl FnOnce() -> usize) {
    let limit = match LIMIT.with(Cell::get) {
        Some(l) if l != UNLIMITED => l,
        _ => return,
    };
    let cost = (a.max(1) as u64).saturating_mul(b.max(1) as u64);
    let used = BIG_WORK.with(|w| {
        let used = w.get().saturating_add(cost);
        w.set(used);
        used
    });
    if used > (limit as u64).saturating_mul(WORD_PRODUCTS_PER_TERM as u64) {
        exceeded_with(
            usize::try_from(used).unwrap_or(usize::MAX),
            limit,
            Measure::Digits(digits()),
        );
    }
}

/// The word products [`charge_big_numbers`] has counted in this thread
/// since its outermost [`within`] began (0 outside one).
pub fn big_number_work() -> u64 {
    BIG_WORK.with(Cell::get)
}

/// Unwind with [`TooLarge`] if an expression of `symbols` symbols written
/// out ([`crate::expr::atom::written_size`]) is too large to print: more
/// symbols than the budget has terms. Shared arguments nested in
/// definitions print at each occurrence, so a small expression can print
/// as millions of symbols.
#[inline]
pub fn check_printed(symbols: u64) {
    let limit = limit();
    if symbols > limit as u64 {
        exceeded_with(
            usize::try_from(symbols).unwrap_or(usize::MAX),
            limit,
            Measure::Printed,
        );
    }
}

#[cold]
#[inline(never)]
fn exceeded(terms: usize, limit: usize) -> ! {
    exceeded_with(terms, limit, Measure::Terms)
}

#[cold]
#[inline(never)]
fn exceeded_with(terms: usize, limit: usize, measure: Measure) -> ! {
    let context = CONTEXT.with(|c| c.borrow().last().cloned());
    let e = TooLarge {
        terms,
        limit,
        context,
        measure,
    };
    if !installed() {
        // nobody to return the error to: an operation without a `Result`
        // called outside any budget (see the module's doc)
        panic!( // ok: arithmetic without a Result, outside any budget (module doc); within() makes it a value
            "{} (outside any work budget, the default one applies: run it in qdot::budget::within for the error as a value)",
            e.message()
        );
    }
    resume_unwind(Box::new(e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn within_a_budget_a_check_past_it_is_an_error_with_its_context() {
        let r = within(10, || {
            let _c = enter(|| "evaluating `E`".into(), Some((3, 7)));
            check_terms(10);
            check_terms(11);
            unreachable!("stopped at 11 terms")
        });
        let e: TooLarge = r.expect_err("over budget");
        assert_eq!(e.terms, 11);
        assert_eq!(e.limit, 10);
        assert_eq!(e.context.as_ref().map(|c| c.span), Some(Some((3, 7))));
        assert_eq!(
            e.message(),
            "expression too large: 11 terms while evaluating `E` (the limit is 10)"
        );
        // unlimited when asked for
        within(UNLIMITED, || check_terms(usize::MAX - 1)).expect("no bound");
        assert_eq!(within(5, || 7), Ok(7));
    }

    /// Outside any budget the default applies: an entry point that runs
    /// `bounded` returns its error, and one inside a budget keeps that
    /// budget.
    #[test]
    fn without_a_budget_the_default_applies() {
        assert!(!installed());
        assert_eq!(limit(), crate::limits::DEFAULT_MAX_TERMS);
        let r: Result<(), TooLarge> = bounded(
            || {
                check_terms(crate::limits::DEFAULT_MAX_TERMS + 1);
                Ok(())
            },
            |e| e,
        );
        let e = r.expect_err("past the default");
        assert_eq!(e.limit, crate::limits::DEFAULT_MAX_TERMS);
        let r = within(10, || bounded(|| Ok::<_, TooLarge>(limit()), |e| e));
        assert_eq!(r, Ok(Ok(10)));
        assert!(!installed());
        // an operation without a `Result` outside any budget panics, with
        // the budget's message
        let p = catch_unwind(|| check_terms(crate::limits::DEFAULT_MAX_TERMS + 1))
            .expect_err("past the default");
        let m = p.downcast_ref::<String>().expect("a message");
        assert!(
            m.starts_with("expression too large: 2,000,001 terms (the limit is 2,000,000) (outside any work budget"),
            "{m}"
        );
    }

    /// A nested budget goes on counting the outer's work on big numbers:
    /// a parse and a derivation in two nested budgets share one allowance.
    #[test]
    fn nested_budgets_share_the_work_on_big_numbers() {
        let limit = 10; // 500 word products
        let r = within(limit, || {
            charge_big_numbers(20, 20, || 100); // 400
            assert_eq!(big_number_work(), 400);
            within(limit, || {
                assert_eq!(big_number_work(), 400);
                charge_big_numbers(10, 10, || 100); // 500 in all: at the limit
                charge_big_numbers(1, 1, || 100); // 501: past it
            })
        });
        let e = r
            .expect("the inner budget's error is its value")
            .expect_err("past 500");
        assert_eq!(e.terms, 501);
        assert_eq!(e.measure, Measure::Digits(100));
    }

    /// The terms an elimination builds are charged by their variable
    /// powers, apart from its term products: wide terms stop it though
    /// their products are few.
    #[test]
    fn the_terms_built_are_charged_by_their_powers() {
        let limit = 10; // 640 term products, 160 powers
        let r = within(limit, || {
            let work = WorkMeter::new();
            work.charge(10, 10);
            work.charge_built(100);
            assert_eq!((work.used(), work.built()), (100, 100));
            work.charge_built(60); // 160: at the limit
            work.charge_built(1);
        });
        let e = r.expect_err("past 160 powers");
        assert_eq!((e.terms, e.measure), (161, Measure::Built));
        assert_eq!(
            e.message(),
            "expression too large: 161 variable powers in the terms built in all (the limit is 10 terms, and 160 variable powers in the terms built in all)"
        );
    }

    #[test]
    fn numbers_are_grouped_by_thousands() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(2_000_000), "2,000,000");
    }
}
