//! The book reads as plain Markdown: a prose line that happens to start
//! with `+ `, `- ` or `* ` (a wrapped formula, `+ F_s·sin(p·t)`) would
//! become a bullet, since a list item may interrupt a paragraph (a list
//! meant so follows a line ending in `:`). Worked output sits in fenced
//! blocks, where no line is a list.

use std::path::Path;

/// The chapters under `dir`, recursively.
fn chapters(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("book/src is readable")
        .flatten()
        .map(|e| e.path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            chapters(&p, out);
        } else if p.extension().is_some_and(|e| e == "md") {
            out.push(p);
        }
    }
}

/// Whether `line` opens a bullet list item (up to 3 spaces of indent).
fn bullet(line: &str) -> bool {
    let t = line.trim_start_matches(' ');
    line.len() - t.len() <= 3 && ["- ", "+ ", "* "].iter().any(|m| t.starts_with(m))
}

/// `line N: text` for every prose line of `text` that starts a bullet in
/// the middle of a paragraph.
fn stray_bullets(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut fence: Option<&str> = None;
    // the kind of the block the previous line belongs to: None after a
    // blank line, Some(true) in a list, Some(false) in a paragraph
    let mut block: Option<bool> = None;
    let mut previous = "";
    for (i, line) in text.lines().enumerate() {
        let after = std::mem::replace(&mut previous, line);
        let t = line.trim_start();
        if let Some(f) = fence {
            if t.starts_with(f) {
                fence = None;
                block = None;
            }
            continue;
        }
        if let Some(f) = ["```", "~~~"].into_iter().find(|f| t.starts_with(f)) {
            fence = Some(f);
            continue;
        }
        if t.is_empty() {
            block = None;
            continue;
        }
        let heading_or_table = t.starts_with('#') || t.starts_with('|');
        block = match block {
            _ if heading_or_table => None,
            None => Some(bullet(line)),
            Some(false) if bullet(line) && after.trim_end().ends_with(':') => Some(true),
            Some(false) if bullet(line) => {
                found.push(format!("line {}: {line}", i + 1));
                Some(false)
            }
            kind => kind,
        };
    }
    found
}

#[test]
fn no_prose_line_turns_into_a_bullet() {
    let mut files = Vec::new();
    chapters(Path::new("book/src"), &mut files);
    assert!(files.len() > 10, "{files:?}");
    let mut found = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("a chapter is UTF-8");
        for s in stray_bullets(&text) {
            found.push(format!("{}: {s}", f.display()));
        }
    }
    assert!(
        found.is_empty(),
        "prose lines Markdown reads as bullets:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_check_finds_a_wrapped_sum_and_passes_lists_and_code() {
    assert_eq!(
        stray_bullets("takes the load f(t) = F_c·cos(p·t)\n+ F_s·sin(p·t), and\n"),
        ["line 2: + F_s·sin(p·t), and"]
    );
    assert!(stray_bullets("A list:\n\n- one\n- two\n  wrapped\n").is_empty());
    assert!(stray_bullets("```text\nx\n- 1\n```\n").is_empty());
    assert_eq!(stray_bullets("prose\n- a list after prose\n").len(), 1);
    assert!(stray_bullets("Two cases:\n- one\n- two\n").is_empty());
}
