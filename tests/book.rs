//! The book shows qdot's real output: every ```text (or ```latex) block
//! preceded by a `<!-- qdot ARGS -->` comment must equal what `qdot ARGS`
//! prints (run from the repository root; `ARGS < FILE` feeds FILE to
//! stdin, for REPL transcripts; `ARGS 2>&1` shows an error, and qdot
//! must fail), and the text between
//! `<!-- qdot-math ARGS -->` and `<!-- /qdot-math -->` must be qdot's LaTeX
//! output made into Markdown that MathJax renders ([`mathjax`]).
//! `QDOT_BLESS=1 cargo test --release --test it book::` rewrites the blocks from the
//! current output.

use std::process::Command;

/// `qdot ARGS`; `ARGS < FILE` feeds the file to stdin (a REPL session);
/// `ARGS 2>&1` shows an error: stdout then stderr, and exit status 1.
fn run(args: &str) -> String {
    if let Some(args) = args.strip_suffix("2>&1") {
        let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
            .args(args.split_whitespace())
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdin(std::process::Stdio::null())
            .output()
            .expect("qdot runs");
        assert_eq!(
            out.status.code(),
            Some(1),
            "qdot {args}: an error was expected"
        );
        return String::from_utf8_lossy(&out.stdout).into_owned()
            + &String::from_utf8_lossy(&out.stderr);
    }
    let (args, input) = match args.split_once(" < ") {
        Some((a, f)) => (a, Some(f.trim())),
        None => (args, None),
    };
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_qdot"));
    cmd.args(args.split_whitespace())
        .current_dir(env!("CARGO_MANIFEST_DIR"));
    let stdin = match input {
        Some(f) => std::fs::File::open(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(f))
            .expect("the REPL script")
            .into(),
        None => std::process::Stdio::null(),
    };
    let out = cmd.stdin(stdin).output().expect("qdot runs");
    // a transcript may show an error on purpose (exit status 1), but
    // nothing may go to stderr: `--echo` writes everything to stdout
    assert!(
        out.status.success() || (input.is_some() && out.stderr.is_empty()),
        "qdot {args} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The page with every marked block replaced by the current output, and
/// the number of blocks.
fn regenerate(page: &str) -> (String, usize) {
    let (page, n) = regenerate_math(page);
    let mut out = String::with_capacity(page.len());
    let mut rest = page.as_str();
    let mut n = n;
    while let Some(at) = rest.find("<!-- qdot ") {
        let end = rest[at..]
            .find("-->")
            .map(|e| at + e)
            .expect("marker closed");
        let args = rest[at + "<!-- qdot ".len()..end].trim();
        let fence = rest[end..]
            .find("```")
            .map(|f| end + f)
            .expect("a code block follows the marker");
        let info_end = rest[fence..]
            .find('\n')
            .map(|e| fence + e)
            .expect("fence line");
        let info = &rest[fence + 3..info_end];
        assert!(
            info == "text" || info == "latex",
            "the block after `qdot {args}` must be ```text or ```latex, not ```{info}"
        );
        let body = info_end + 1;
        let close = rest[body..]
            .find("```")
            .map(|c| body + c)
            .expect("block closed");
        out.push_str(&rest[..body]);
        out.push_str(&run(args));
        rest = &rest[close..];
        n += 1;
    }
    out.push_str(rest);
    (out, n)
}

/// The `<!-- qdot-math ARGS -->` regions, regenerated.
fn regenerate_math(page: &str) -> (String, usize) {
    const OPEN: &str = "<!-- qdot-math ";
    const CLOSE: &str = "<!-- /qdot-math -->";
    let mut out = String::with_capacity(page.len());
    let mut rest = page;
    let mut n = 0;
    while let Some(at) = rest.find(OPEN) {
        let end = rest[at..]
            .find("-->")
            .map(|e| at + e)
            .expect("marker closed");
        let args = rest[at + OPEN.len()..end].trim();
        let close = rest[end..]
            .find(CLOSE)
            .map(|c| end + c)
            .expect("region closed");
        out.push_str(&rest[..end + 3]);
        out.push_str("\n\n");
        out.push_str(&mathjax(&run(args)));
        out.push('\n');
        rest = &rest[close..];
        n += 1;
    }
    out.push_str(rest);
    (out, n)
}

/// qdot's LaTeX as Markdown for mdBook's MathJax: display environments
/// become `\\[\begin{aligned}…\end{aligned}\\]`, `$…$` becomes `\\(…\\)`,
/// `\paragraph{X}` bold text, `enumerate` a list; inside mathematics the
/// characters Markdown would eat are escaped (`\\` → `\\\\`, `_` → `\_`).
fn mathjax(tex: &str) -> String {
    fn math(s: &str) -> String {
        let mut o = String::with_capacity(s.len() + 8);
        let mut chars = s.chars().peekable();
        while let Some(c) = chars.next() {
            match c {
                '\\' => match chars.peek() {
                    Some(&d) if d.is_ascii_punctuation() => {
                        // `\\` gives `\`, then `\d` gives d
                        o.push_str("\\\\\\");
                        o.push(d);
                        chars.next();
                    }
                    _ => o.push('\\'),
                },
                '_' | '*' => {
                    o.push('\\');
                    o.push(c);
                }
                c => o.push(c),
            }
        }
        o
    }
    fn inline(line: &str) -> String {
        // $…$ → \\(…\\)
        let mut o = String::new();
        let mut parts = line.split('$');
        if let Some(first) = parts.next() {
            o.push_str(first);
        }
        for (i, p) in parts.enumerate() {
            if i % 2 == 0 {
                o.push_str("\\\\(");
                o.push_str(&math(p));
                o.push_str("\\\\)");
            } else {
                o.push_str(p);
            }
        }
        o
    }
    let mut out = String::new();
    let mut display: Option<String> = None;
    for line in tex.lines() {
        if let Some(buf) = display.as_mut() {
            if line.starts_with("\\end{") {
                let body = buf.replace(" \\nonumber", "");
                let env = if line.contains("align") {
                    "aligned"
                } else {
                    ""
                };
                out.push_str("\\\\[");
                if env.is_empty() {
                    out.push_str(&math(body.trim()));
                } else {
                    out.push_str(&format!(
                        "\\begin{{aligned}}\n{}\\end{{aligned}}",
                        math(&body)
                    ));
                }
                out.push_str("\\\\]\n\n");
                display = None;
            } else {
                buf.push_str(line);
                buf.push('\n');
            }
            continue;
        }
        if line.starts_with("\\begin{align") || line.starts_with("\\begin{equation") {
            display = Some(String::new());
        } else if line == "\\begin{enumerate}" || line == "\\end{enumerate}" {
            out.push('\n');
        } else if let Some(item) = line.trim_start().strip_prefix("\\item ") {
            out.push_str(&format!("1. {}\n", inline(item)));
        } else if let Some(p) = line.strip_prefix("\\paragraph{") {
            // the `}` that closes `\paragraph{`, braces inside counted
            let mut depth = 0i32;
            let close = p
                .char_indices()
                .find(|&(_, c)| {
                    depth += match c {
                        '{' => 1,
                        '}' => -1,
                        _ => 0,
                    };
                    depth < 0
                })
                .map_or(p.len(), |(i, _)| i);
            let (title, text) = (&p[..close], p.get(close + 1..).unwrap_or(""));
            out.push_str(&format!("**{}**{}\n\n", inline(title), inline(text)));
        } else {
            out.push_str(&inline(line));
            out.push_str("\n\n");
        }
    }
    out
}

#[test]
fn book_output_is_qdots_real_output() {
    let dir = format!("{}/book/src", env!("CARGO_MANIFEST_DIR"));
    let bless = std::env::var_os("QDOT_BLESS").is_some();
    let mut blocks = 0;
    for entry in std::fs::read_dir(&dir).expect("book/src") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let page = std::fs::read_to_string(&path).expect("page");
        let (fresh, n) = regenerate(&page);
        blocks += n;
        if bless {
            std::fs::write(&path, &fresh).expect("write page");
        } else {
            pretty_assertions::assert_eq!(
                page,
                fresh,
                "{} drifted; run QDOT_BLESS=1 cargo test --release --test it book::",
                path.display()
            );
        }
    }
    assert!(blocks >= 5, "only {blocks} checked blocks");
}
