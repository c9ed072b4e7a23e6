//! Misspellings: the distance between two words and the nearest of a list,
//! for every "did you mean …?" hint (keywords, names, units, REPL commands).

/// The optimal-string-alignment distance of `a` and `b` over characters
/// (Damerau–Levenshtein without edits inside a transposed pair):
/// insertions, deletions, substitutions and swaps of two neighbours each
/// cost 1.
pub fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let n = b.len();
    // three rows: two back (for swaps), one back, current
    let mut two: Vec<usize> = vec![0; n + 1];
    let mut one: Vec<usize> = (0..=n).collect();
    let mut cur: Vec<usize> = vec![0; n + 1];
    for i in 1..=a.len() {
        cur[0] = i;
        for j in 1..=n {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (one[j] + 1).min(cur[j - 1] + 1).min(one[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(two[j - 2] + 1);
            }
            cur[j] = d;
        }
        std::mem::swap(&mut two, &mut one);
        std::mem::swap(&mut one, &mut cur);
    }
    one[n]
}

/// The candidate `word` is most likely a misspelling of: within distance 1
/// of a candidate of up to 6 letters, 2 of a longer one, case ignored; the
/// nearest, ties to the first in alphabetical order. `None` when `word` is
/// a candidate itself, or is shorter than 3 letters (too short to guess).
pub fn nearest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    if word.chars().count() < 3 || word.len() > 40 {
        return None;
    }
    let lower = word.to_lowercase();
    let mut best: Option<(usize, &'a str)> = None;
    for k in candidates {
        if k == word {
            return None;
        }
        let limit = if k.chars().count() <= 6 { 1 } else { 2 };
        let d = distance(&lower, k);
        if d <= limit && best.is_none_or(|(b, bk)| d < b || (d == b && k < bk)) {
            best = Some((d, k));
        }
    }
    best.map(|(_, k)| k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(distance("", ""), 0);
        assert_eq!(distance("abc", ""), 3);
        assert_eq!(distance("kitten", "sitting"), 3);
        // a swap of neighbours is one edit
        assert_eq!(distance("sovle", "solve"), 1);
        assert_eq!(distance("ca", "abc"), 3);
        assert_eq!(distance("θ1", "θ2"), 1);
        assert_eq!(distance("rayliegh", "rayleigh"), 1);
        assert_eq!(distance("kinectic", "kinetic"), 1);
        assert_eq!(distance("potental", "potential"), 1);
    }

    #[test]
    fn nearest_names_the_likely_word_or_nothing() {
        let commands = ["solve", "modes", "equilibrium", "equations", "latex"];
        assert_eq!(nearest("sovle", commands), Some("solve"));
        assert_eq!(nearest("Solve", commands), Some("solve"));
        assert_eq!(nearest("equilibirum", commands), Some("equilibrium"));
        assert_eq!(nearest("mode", commands), Some("modes"));
        assert_eq!(nearest("solve", commands), None);
        assert_eq!(nearest("xyzzy", commands), None);
        assert_eq!(nearest("so", commands), None);
        // ties go to the first alphabetically, whatever the list's order
        assert_eq!(nearest("abd", ["abe", "abc"]), Some("abc"));
    }
}
