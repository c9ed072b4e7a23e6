//! The book shows qdot's real output, each block under the command that
//! printed it: every ```text (or ```latex) block whose first line is
//! `$ qdot ARGS` must continue with what that command prints, run from the
//! repository root. The line is the one source of truth: it is read as
//! bash reads it ([`shell_words`]: blanks, '…', "…", backslash), run, and
//! must be written with the quoting bash needs and no more ([`quote`]), so
//! it pastes into a shell as it is. `… < FILE` feeds FILE to stdin (REPL
//! transcripts); `… 2>&1` shows an error: stdout then stderr, and qdot must
//! fail. Interactive sessions, typed by hand, are ```console blocks.
//! The text between `<!-- qdot-math ARGS -->` and `<!-- /qdot-math -->`
//! must be qdot's LaTeX output made into Markdown that the book's KaTeX
//! renders ([`tex_markdown`]).
//! `QDOT_BLESS=1 cargo test --release --test it book::` rewrites the blocks
//! (never the command lines) from the current output.

use std::process::Command;

/// What starts a checked block's first line.
const PROMPT: &str = "$ qdot ";

/// A shell word, or one of the two redirections the book uses.
#[derive(Debug, PartialEq)]
enum Token {
    Word(String),
    /// `<`: the next word is a file for stdin
    Stdin,
    /// `2>&1`
    MergeStderr,
}

/// Characters bash takes literally outside quotes (letters and digits of
/// any script, and these); anything else in a word must be quoted.
fn is_plain(c: char) -> bool {
    c.is_alphanumeric() || "_-+=:,./@%^".contains(c)
}

/// `line` split into words as bash splits it: on unquoted blanks; `'…'`
/// literal; `"…"` literal but for `\` before `$`, `` ` ``, `"`, `\`;
/// `\c` outside quotes is `c`. An unquoted `<` or `2>&1` is a redirection.
/// Any other character bash would read specially (`|&;()<>$*?[]{}~#!`
/// and the backquote) is an error unless quoted, and so is an open quote.
fn shell_words(line: &str) -> Result<Vec<Token>, String> {
    let mut tokens = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        while chars.next_if(|c| *c == ' ' || *c == '\t').is_some() {}
        let Some(&first) = chars.peek() else {
            return Ok(tokens);
        };
        let rest: String = chars.clone().collect();
        let ends_word = |n: usize| rest[n..].starts_with([' ', '\t']) || rest.len() == n;
        if first == '<' && ends_word(1) {
            chars.next();
            tokens.push(Token::Stdin);
            continue;
        }
        if rest.starts_with("2>&1") && ends_word(4) {
            chars.nth(3);
            tokens.push(Token::MergeStderr);
            continue;
        }
        let mut word = String::new();
        while let Some(c) = chars.next_if(|c| *c != ' ' && *c != '\t') {
            match c {
                '\'' => loop {
                    match chars.next() {
                        Some('\'') => break,
                        Some(c) => word.push(c),
                        None => return Err(format!("an unclosed ' in `{line}`")),
                    }
                },
                '"' => loop {
                    match chars.next() {
                        Some('"') => break,
                        Some('\\') => match chars.next() {
                            Some(c @ ('$' | '`' | '"' | '\\')) => word.push(c),
                            Some(c) => {
                                word.push('\\');
                                word.push(c);
                            }
                            None => return Err(format!("an unclosed \" in `{line}`")),
                        },
                        Some(c @ ('$' | '`')) => {
                            return Err(format!("bash expands {c} inside \"…\" in `{line}`"));
                        }
                        Some(c) => word.push(c),
                        None => return Err(format!("an unclosed \" in `{line}`")),
                    }
                },
                '\\' => match chars.next() {
                    Some(c) => word.push(c),
                    None => return Err(format!("a \\ ends `{line}`")),
                },
                c if is_plain(c) => word.push(c),
                c => return Err(format!("bash reads {c} specially: quote it in `{line}`")),
            }
        }
        tokens.push(Token::Word(word));
    }
}

/// `word` as bash needs it written, quoted only when it must be: bare if
/// every character is plain, else `'…'`, else (it has a `'`) `"…"`, else
/// `'…'\''…'`.
fn quote(word: &str) -> String {
    if !word.is_empty() && word.chars().all(is_plain) {
        word.to_string()
    } else if !word.contains('\'') {
        format!("'{word}'")
    } else if !word.contains(['"', '$', '`', '\\', '!']) {
        format!("\"{word}\"")
    } else {
        word.split('\'')
            .map(|p| {
                if p.is_empty() {
                    String::new()
                } else {
                    format!("'{p}'")
                }
            })
            .collect::<Vec<_>>()
            .join("\\'")
    }
}

/// A command line of the book, as run.
#[derive(Debug, PartialEq)]
struct Invocation {
    /// qdot's arguments
    args: Vec<String>,
    /// `< FILE`
    stdin: Option<String>,
    /// `2>&1`
    merge_stderr: bool,
}

impl Invocation {
    /// `qdot ARGS [< FILE] [2>&1]`, as [`shell_words`] reads it.
    fn parse(line: &str) -> Result<Invocation, String> {
        let mut tokens = shell_words(line)?.into_iter();
        if tokens.next() != Some(Token::Word("qdot".into())) {
            return Err(format!("`{line}` does not run qdot"));
        }
        let mut inv = Invocation {
            args: Vec::new(),
            stdin: None,
            merge_stderr: false,
        };
        while let Some(t) = tokens.next() {
            if inv.merge_stderr {
                return Err(format!("2>&1 must end `{line}`"));
            }
            match t {
                Token::Word(w) if inv.stdin.is_none() => inv.args.push(w),
                Token::Word(_) => return Err(format!("words after `< FILE` in `{line}`")),
                Token::Stdin => match tokens.next() {
                    Some(Token::Word(f)) if inv.stdin.is_none() => inv.stdin = Some(f),
                    _ => return Err(format!("`<` wants one file in `{line}`")),
                },
                Token::MergeStderr => inv.merge_stderr = true,
            }
        }
        Ok(inv)
    }

    /// The line that shows this invocation, quoted by [`quote`].
    fn line(&self) -> String {
        let mut s = String::from("qdot");
        for a in &self.args {
            s.push(' ');
            s.push_str(&quote(a));
        }
        if let Some(f) = &self.stdin {
            s.push_str(" < ");
            s.push_str(&quote(f));
        }
        if self.merge_stderr {
            s.push_str(" 2>&1");
        }
        s
    }
}

/// `line` (`qdot …`) read and checked: written as [`quote`] writes it, and
/// split into the same words by bash itself where bash is installed.
fn command(line: &str) -> Invocation {
    let inv = Invocation::parse(line).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        line,
        inv.line(),
        "the book shows the line on the left; quoted as bash needs it and no more, it is the one on the right"
    );
    // bash's own reading (the redirections apply to printf, from the root)
    if let Ok(out) = Command::new("bash")
        .args(["--norc", "--noprofile", "-c"])
        .arg(format!("printf '%s\\0' {}", &line["qdot".len()..]))
        .current_dir(env!("QDOT_ROOT"))
        .stdin(std::process::Stdio::null())
        .output()
    {
        let words: Vec<String> = String::from_utf8_lossy(&out.stdout)
            .split_terminator('\0')
            .map(str::to_string)
            .collect();
        assert!(out.status.success(), "bash could not run `{line}`");
        assert_eq!(words, inv.args, "bash splits `{line}` otherwise");
    }
    inv
}

/// What `inv` prints: stdout, and for `2>&1` stdout then stderr, and exit
/// status 1.
fn run(inv: &Invocation) -> String {
    let root = std::path::Path::new(env!("QDOT_ROOT"));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_qdot"));
    cmd.args(&inv.args).current_dir(root);
    let shown = inv.line();
    let stdin = match &inv.stdin {
        Some(f) => std::fs::File::open(root.join(f))
            .unwrap_or_else(|e| panic!("{shown}: {f}: {e}"))
            .into(),
        None => std::process::Stdio::null(),
    };
    let out = cmd.stdin(stdin).output().expect("qdot runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    if inv.merge_stderr {
        assert_eq!(out.status.code(), Some(1), "{shown}: an error was expected");
        return stdout + &String::from_utf8_lossy(&out.stderr);
    }
    // a transcript may show an error on purpose (exit status 1), but
    // nothing may go to stderr: `--echo` writes everything to stdout
    assert!(
        out.status.success() || (inv.stdin.is_some() && out.stderr.is_empty()),
        "{shown} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

/// The page with every checked block's output replaced by the current
/// output of the command on its first line, and the number of blocks.
fn regenerate(page: &str) -> (String, usize) {
    assert!(
        !page.contains("<!-- qdot "),
        "a `<!-- qdot ARGS -->` marker: the command is now the block's first line, `$ qdot ARGS`"
    );
    let (page, mut n) = regenerate_math(page);
    let mut out = String::with_capacity(page.len());
    let mut lines = page.split_inclusive('\n');
    while let Some(line) = lines.next() {
        out.push_str(line);
        let Some(info) = line.trim_end().strip_prefix("```") else {
            continue;
        };
        let mut body = Vec::new();
        let mut close = None;
        for l in lines.by_ref() {
            if l.trim_end() == "```" {
                close = Some(l);
                break;
            }
            body.push(l);
        }
        let close = close.expect("code block closed");
        match body.first() {
            Some(first) if (info == "text" || info == "latex") && first.starts_with(PROMPT) => {
                out.push_str(first);
                out.push_str(&run(&command(first["$ ".len()..].trim_end())));
                n += 1;
            }
            _ => {
                assert!(
                    info == "console" || !body.first().is_some_and(|f| f.starts_with(PROMPT)),
                    "```{info} under `{}`: a checked block is ```text or ```latex; an interactive session is ```console",
                    body[0].trim_end()
                );
                out.extend(body);
            }
        }
        out.push_str(close);
    }
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
        out.push_str(&tex_markdown(&run(&command(&format!("qdot {args}")))));
        out.push('\n');
        rest = &rest[close..];
        n += 1;
    }
    out.push_str(rest);
    (out, n)
}

/// qdot's LaTeX as Markdown for the book's KaTeX (book/theme/head.hbs,
/// which typesets `\[…\]` and `\(…\)`): display environments
/// become `\\[\begin{aligned}…\end{aligned}\\]`, `$…$` becomes `\\(…\\)`,
/// `\paragraph{X}` bold text, `enumerate` a list; inside mathematics the
/// characters Markdown would eat are escaped (`\\` → `\\\\`, `_` → `\_`).
fn tex_markdown(tex: &str) -> String {
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
    let dir = format!("{}/book/src", env!("QDOT_ROOT"));
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

#[test]
fn shell_words_read_as_bash_reads() {
    let words = |line: &str| {
        shell_words(line)
            .unwrap()
            .into_iter()
            .map(|t| match t {
                Token::Word(w) => w,
                Token::Stdin => "<".into(),
                Token::MergeStderr => "2>&1".into(),
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(
        words(r#"qdot  --init "th=2.5,th'=0" 's=sin(2*t)' a\ b "x\"\$\\y\z" '' < f.repl 2>&1"#),
        [
            "qdot",
            "--init",
            "th=2.5,th'=0",
            "s=sin(2*t)",
            "a b",
            r#"x"$\y\z"#,
            "",
            "<",
            "f.repl",
            "2>&1"
        ]
    );
    // quoted, < and 2>&1 are words
    assert_eq!(words("qdot '<' \"2>&1\""), ["qdot", "<", "2>&1"]);
    for bad in [
        "qdot a;b",
        "qdot $HOME",
        "qdot *.qd",
        "qdot s=sin(t)",
        "qdot 'open",
        "qdot \"$x\"",
        "qdot a|b",
        "qdot x>y",
    ] {
        assert!(shell_words(bad).is_err(), "{bad}");
    }
}

#[test]
fn quote_only_where_bash_needs_it() {
    for (word, shown) in [
        ("examples/seed_23_4.qd", "examples/seed_23_4.qd"),
        ("m=1,g=9.81,l=1", "m=1,g=9.81,l=1"),
        ("θ=π/2", "θ=π/2"),
        ("theta=3,theta'=0", "\"theta=3,theta'=0\""),
        ("s=1/10*sin(2*t)", "'s=1/10*sin(2*t)'"),
        ("a b", "'a b'"),
        ("", "''"),
        ("x'=\"$y\"", "'x'\\''=\"$y\"'"),
        ("'a'", "\"'a'\""),
    ] {
        assert_eq!(quote(word), shown);
        let line = format!("qdot {shown}");
        let inv = Invocation::parse(&line).unwrap();
        assert_eq!(inv.args, [word], "{line}");
        assert_eq!(inv.line(), line);
    }
    // a command shown with needless or wrong quoting fails the book test
    for line in [
        "qdot solve 'examples/first.qd'",
        "qdot simulate x.qd --init 'theta=1'",
    ] {
        let r = std::panic::catch_unwind(|| command(line));
        assert!(r.is_err(), "{line} accepted");
    }
}
