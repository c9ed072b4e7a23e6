//! Every limit qdot puts on its input and its work, in one place: what it
//! is, its default, and why that value. README's "Limits" section and the
//! book's limits page list the same table (a test checks they agree).
//!
//! Each limit stops a computation with a clear, positioned error instead
//! of a hang, a crash or memory exhaustion. The ones a user may need to
//! raise for a real problem can be raised (`--max-terms`, `--max-steps`);
//! the others bound input no scene needs.

/// The most substitutions the dimension check makes while it solves for
/// the dimensions of names nobody annotated (each found dimension is put
/// into the earlier ones that use it). Real scenes need a few per name;
/// only many names defined by chains of each other come near it.
pub const MAX_DIMENSION_WORK: u64 = 10_000_000;

/// The most elementary turns one rotation is made of (`rot(z, a) *
/// rot(x, b) * …`, through frames built on frames). Each composition
/// copies the sequence (its angular velocity is built from it); a chain
/// of a thousand frames is already far past any mechanism.
pub const MAX_ROTATION_TURNS: usize = 1_000;

/// Past how many terms the expanded mass matrix and forcing (together)
/// make `derive` and `solve` write their results through named
/// intermediates unless `--expand` is given. Every seed problem and
/// example stays below it (the largest, 31); the 3D chain of three rods
/// is at 118 and of four at 508, where the expanded accelerations no
/// longer fit the default budget.
pub const STRUCTURE_ABOVE_TERMS: usize = 256;

/// The most parameters of either sign (`assume e real`) one sign decision
/// splits into cases (3ᵏ of them: positive, negative, zero); past it the
/// sign is left undecided, which the solvers report as such.
pub const MAX_REAL_CASES: usize = 4;

/// Deepest nesting of functions in one value (`sin(sin(…))`, directly or
/// through definitions). Each level is an atom whose argument holds the
/// next, and walks over atoms recurse; no mechanics needs more than a few.
pub const MAX_FUNCTION_NESTING: u32 = 200;

/// The longest argument of one function, in symbols written out (each
/// term's coefficient and factors, an inner function's argument counted
/// again at each occurrence). Mechanics writes `sin(θ₁ − θ₂)`; definitions
/// that use the previous one twice inside functions double the length
/// per line, and printing, differentiating and evaluating pay it at every
/// occurrence.
pub const MAX_FUNCTION_ARGUMENT_SIZE: u64 = 2_000;

/// Deepest recursion of the parser: parentheses, call arguments, unary
/// signs and `^` chains each count one level (2 MiB stacks must hold it,
/// in debug builds too).
pub const MAX_PARSE_NESTING: u32 = 200;

/// Deepest expression tree the parser builds (a leaf has depth 1): long
/// `a + b + …` chains are parsed by a loop but must not build a tree too
/// deep to drop or walk.
pub const MAX_TREE_DEPTH: u32 = 1000;

/// Largest `|n|` of a scientific exponent `…e±n`: 10^1000 has 1,001
/// digits, far beyond any physical constant.
pub const MAX_DECIMAL_EXPONENT: u32 = 1000;

/// The most digits of a number: a literal, or an integer power of a number
/// (`7^100000`). Physical constants have tens of digits; past this,
/// exact arithmetic on the number alone would take seconds.
pub const MAX_NUMBER_DIGITS: usize = 10_000;

/// The highest time derivative of a coordinate an expression may take
/// (`x'''` is 3; `dt` and nested primes add up). A scene uses up to 2,
/// accelerations; the n-th derivative of `f(x)` has as many terms as n has
/// partitions (42 at 10, 966,467 at 60), so past this the work explodes.
pub const MAX_TIME_DERIVATIVE_ORDER: u32 = 10;

/// The highest order `taylor` expands to (each order differentiates once
/// more; the terms grow quickly).
pub const MAX_TAYLOR_ORDER: i64 = 30;

/// The most radicals rationalized out of one denominator (each step
/// multiplies by a conjugate and doubles the terms, so the work budget
/// stops long before); past it the division is refused, never left with
/// a radical in the denominator.
pub const MAX_RATIONALIZE_STEPS: u32 = 64;

/// The most terms (numerator and denominator together) of an expression
/// whose compact form is searched for printing (`expr::compact`: each
/// candidate is a gcd and a printing); larger results print in the
/// canonical form with the addition theorems folded.
pub const MAX_COMPACT_TERMS: usize = 400;

/// The work the compact search of one expression may always take: the
/// terms of the rewritings it builds (each reduction choice, the Fourier
/// form, estimated before any is made), as many as one rewriting may
/// expand into ([`MAX_TRIG_EXPANSION`]). Beyond it the search takes at most
/// [`COMPACT_WORK_PER_TERM`] per term of the expression; an expression
/// whose rewritings would take more prints in the canonical form with its
/// addition theorems folded. Without it a sum of two terms could build
/// 32,400 (eight rewritings of 4,000 terms).
pub const COMPACT_WORK_BASE: usize = 4_000;

/// The work the compact search of one expression may take per term of the
/// expression, beyond [`COMPACT_WORK_BASE`]: so a result's searches, like
/// its printing, take time proportional to its size. The examples' and
/// the book's searches take at most 1,300 beyond 16 per term; the 3D rod
/// chains' about 2 per term in all.
pub const COMPACT_WORK_PER_TERM: usize = 16;

/// The most terms a rewriting of the compact forms may expand a result
/// into (estimated before it is made: sinᵃθ as a Fourier series has a + 1
/// terms, sin²ᵏθ as a polynomial in cos θ has k + 1); a rewriting past it
/// is not tried. sin¹⁰(a)·…·sin¹⁰(e) would otherwise expand into 11⁵ terms.
pub const MAX_TRIG_EXPANSION: usize = 4_000;

/// The most terms of a sum the compact forms try to factor over ℚ for
/// printing ((R − r)²); factoring is exact but its cost grows quickly.
pub const MAX_FACTORED_TERMS: usize = 40;

/// The most cases the exact search for equilibria splits into (each root
/// of one equation put into the others is a case; a branch that dies is
/// one too). n uncoupled angles with two roots each make 2ⁿ equilibria and
/// 2ⁿ⁺¹ − 1 cases, each listed and classified: 12 angles fit, 13 do not;
/// past that the listing is more than anyone reads, and 30 angles took
/// minutes and gigabytes.
pub const MAX_EQUILIBRIUM_CASES: usize = 10_000;

/// The most subsets of modular factors the factoring of one printed sum
/// may try to recombine (the sums of [`MAX_FACTORED_TERMS`] terms); past
/// it the sum prints expanded. A sum of 33 terms (a Swinnerton-Dyer
/// polynomial of degree 64) splits into 32 factors modulo every prime and
/// has 2³¹ subsets; printing it hung.
pub const MAX_PRINTED_FACTOR_SUBSETS: usize = 10_000;

/// The most output times `qdot simulate --points` records: each row keeps
/// t, q and q̇ (and the energy) in memory until printed.
pub const MAX_POINTS: usize = 1_000_000;

/// The default of `qdot simulate --max-steps` and `qdot floquet --max-steps`: steps (accepted and
/// rejected) before a run gives up with "too many steps". A second or two
/// of integration for small systems; raise it for long runs.
pub const DEFAULT_MAX_STEPS: usize = 1_000_000;

/// The default of `--max-terms`: the most terms one polynomial of an exact
/// computation may have ([`crate::budget`]). The textbook scenes stay
/// under a few thousand; the 10-link pendulum's equations under 100,000.
pub const DEFAULT_MAX_TERMS: usize = 2_000_000;

/// The smallest relative tolerance `qdot simulate` accepts: ten units in
/// the last place of f64 (RADAU5's own floor); below it no method can
/// meet the tolerance, and the step shrinks without end.
pub const MIN_RTOL: f64 = 10.0 * f64::EPSILON;

/// The largest size (terms, estimated from the text) of a definition that
/// nothing in its scene uses and that is evaluated when the scene is read,
/// to report its errors as warnings; a larger one is evaluated only when
/// something asks for it (`(a+b+x)^30` is estimated at 3³⁰).
pub const LAZY_CHECK_SIZE: u64 = 256;

/// The work budget (terms) of evaluating one such unused definition when
/// the scene is read: past it the definition is left for later, without a
/// warning.
pub const LAZY_CHECK_BUDGET: usize = 4_096;
