//! Identifiers of the generated code: the scene's names made valid, and
//! distinct, in each target language. ASCII letters, digits and `_` are
//! kept; Greek letters are spelled out (θ → `theta`, Ω → `Omega`),
//! subscript digits become digits (x₁ → `x1`), anything else `_`; a
//! leading digit, or a form the language reserves (C's `M_…` macros),
//! gets a `v_` prefix; a name that is a keyword of the
//! language, a function the generated code calls, or one of its own
//! names (`t`, `y`, `dy`, temporaries `w12`, …) gets a `_` appended,
//! again until it is distinct from every other.

use rustc_hash::FxHashSet;

/// The Greek letters from α (U+03B1) to ω (U+03C9), ς (final sigma)
/// included.
const GREEK: [&str; 25] = [
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "omicron", "pi", "rho", "sigma", "sigma", "tau", "upsilon", "phi",
    "chi", "psi", "omega",
];

/// The ASCII spelling of one character of a name (None: dropped to `_`).
fn ascii(c: char, out: &mut String) {
    let u = c as u32;
    match c {
        'a'..='z' | 'A'..='Z' | '0'..='9' | '_' => out.push(c),
        '₀'..='₉' => out.push(char::from(b'0' + (u - 0x2080) as u8)),
        'ϑ' => out.push_str("theta"),
        'ϕ' => out.push_str("phi"),
        'ϵ' => out.push_str("epsilon"),
        _ if (0x3B1..=0x3C9).contains(&u) => out.push_str(GREEK[(u - 0x3B1) as usize]),
        _ if (0x391..=0x3A9).contains(&u) && u != 0x3A2 => {
            let g = GREEK[(u - 0x391) as usize];
            out.push_str(&g[..1].to_ascii_uppercase());
            out.push_str(&g[1..]);
        }
        '\'' => out.push_str("_dot"),
        _ => out.push('_'),
    }
}

/// The ASCII identifier of a scene name, before it is made distinct.
pub(super) fn base(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        ascii(c, &mut s);
    }
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert_str(0, "v_");
    }
    s
}

/// Whether a language reserves a name by its form (C's `M_…` macros).
pub(super) type ReservedForm = fn(&str) -> bool;

/// Hands out distinct identifiers.
pub(super) struct Namer {
    taken: FxHashSet<String>,
    /// Names a language reserves by their form, not one by one.
    reserved_form: ReservedForm,
}

impl Namer {
    /// A namer for which `reserved` (keywords, called functions, the
    /// generated code's own names) and the names `reserved_form` accepts
    /// are taken.
    pub(super) fn new(reserved: &[&str], reserved_form: ReservedForm) -> Namer {
        Namer {
            taken: reserved.iter().map(|s| s.to_string()).collect(),
            reserved_form,
        }
    }

    /// Take `name` itself (a name the generated code defines).
    pub(super) fn take(&mut self, name: &str) {
        self.taken.insert(name.to_string());
    }

    /// A distinct identifier for the scene name `name`.
    pub(super) fn fresh(&mut self, name: &str) -> String {
        let mut s = base(name);
        if (self.reserved_form)(&s) {
            // a suffix keeps the form (`M_E_` is still an `M_` name)
            s.insert_str(0, "v_");
        }
        while self.taken.contains(&s) || is_temporary(&s) {
            s.push('_');
        }
        self.taken.insert(s.clone());
        s
    }
}

/// `w` and digits: the name of a temporary.
fn is_temporary(s: &str) -> bool {
    s.strip_prefix('w')
        .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
}
