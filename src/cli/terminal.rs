//! The REPL in a terminal (rustyline), or over a pipe.
//!
//! On a terminal: line editing, history kept in the user's data directory
//! (`$XDG_DATA_HOME/qdot/history.txt` on Linux), tab completion of names,
//! commands and functions, highlighting, `  ...` continuation prompts for
//! unfinished entries (an open bracket or `{`, a trailing operator). Every
//! entry runs on a worker thread: Ctrl-C while it computes abandons it
//! (and asks it to stop, see [`qdot::engine::cancel`]) and leaves the session as
//! it was; Ctrl-C while typing drops the entry; Ctrl-D or `:quit` leave.
//!
//! Lines typed ahead (a fast paste, a script driving the terminal) are all
//! read, in order: rustyline's `buffer-redux` feature keeps the bytes read
//! past one line for the next `readline` (without it they were dropped), and
//! a bracketed paste of several lines is split into lines here.
//!
//! When stdin is not a terminal, entries are read from it with no prompts:
//! results go to stdout, errors to stderr, and the exit status is 1 when
//! any entry failed. With `echo`, each entry is printed after its prompt
//! and errors go to stdout too: a transcript, as the terminal would show.
//! Errors point at the script's lines: `--> stdin:12:5`.

use qdot::repl::editing::{completions, highlight};
use qdot::repl::{is_complete, Response, Session};
use rustyline::completion::{Completer, Pair};
use rustyline::error::ReadlineError;
use rustyline::highlight::{CmdKind, Highlighter};
use rustyline::hint::Hinter;
use rustyline::history::DefaultHistory;
use rustyline::validate::Validator;
use rustyline::{CompletionType, Config, Context, Editor, Helper};
use std::borrow::Cow;
use std::io::{BufRead, IsTerminal, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

const PROMPT: &str = "qdot> ";
const MORE: &str = "  ... ";
/// The name errors give the entries read from a pipe: their lines are the
/// script's.
const SCRIPT: &str = "stdin";

/// Set by the SIGINT handler while an entry computes.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Run the REPL, first loading `file` if given; the process exit code.
pub fn run(file: Option<&str>, echo: bool, max_terms: usize) -> i32 {
    let mut session = Session::new();
    session.max_terms = max_terms;
    let interactive_mode = std::io::stdin().is_terminal();
    if interactive_mode {
        println!(
            "qdot {} — :help for help, Ctrl-D to leave",
            env!("CARGO_PKG_VERSION")
        );
    }
    let mut failed = false;
    if let Some(f) = file {
        let r = session.execute(&format!(":load {f}"));
        failed |= r.failed;
        print_response(&r);
    }
    if interactive_mode {
        interactive(session);
        0
    } else {
        i32::from(piped(session, std::io::stdin().lock(), echo) || failed)
    }
}

/// Entries from a reader, no prompts (with `echo`, a transcript):
/// whether any failed.
pub fn piped(mut session: Session, input: impl BufRead, echo: bool) -> bool {
    let mut failed = false;
    let mut entry = String::new();
    let show = |entry: &str, r: &Response| {
        if echo {
            let mut t = String::new();
            for (i, line) in entry.trim_end_matches('\n').lines().enumerate() {
                t.push_str(if i == 0 { PROMPT } else { MORE });
                t.push_str(line);
                t.push('\n');
            }
            t.push_str(&r.out);
            t.push_str(&r.err);
            print_response(&Response::out(t));
        } else {
            print_response(r);
        }
    };
    // the line of the input each entry starts on, for its errors
    let mut start = 1;
    for (i, line) in input.lines().enumerate() {
        let Ok(line) = line else { break };
        if !entry.is_empty() && starts_a_command(&line) {
            // the unfinished entry is executed alone: its error says why
            let r = session.execute_from(&entry, SCRIPT, start);
            show(&entry, &r);
            entry.clear();
            failed |= r.failed;
        }
        if entry.is_empty() {
            start = i + 1;
        }
        entry.push_str(&line);
        entry.push('\n');
        if !is_complete(&entry) {
            continue;
        }
        let r = session.execute_from(&entry, SCRIPT, start);
        show(&entry, &r);
        entry.clear();
        failed |= r.failed;
        if r.quit {
            return failed;
        }
    }
    if !entry.trim().is_empty() {
        let r = session.execute_from(&entry, SCRIPT, start);
        show(&entry, &r);
        failed |= r.failed;
    }
    failed
}

/// A line that starts with `:` is a command: it never continues an
/// unfinished entry (`x +` then `:solve`), which is executed alone first.
fn starts_a_command(line: &str) -> bool {
    line.trim_start().starts_with(':')
}

fn print_response(r: &Response) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(r.out.as_bytes());
    let _ = out.flush();
    let mut err = std::io::stderr().lock();
    let _ = err.write_all(r.err.as_bytes());
    let _ = err.flush();
}

/// The history file: `$XDG_DATA_HOME/qdot/history.txt` (or the platform's
/// data directory), created on demand.
pub fn history_path() -> Option<PathBuf> {
    let dir = dirs::data_dir()?.join("qdot");
    std::fs::create_dir_all(&dir).ok()?;
    Some(dir.join("history.txt"))
}

fn interactive(mut session: Session) {
    let config = Config::builder()
        .auto_add_history(false)
        .completion_type(CompletionType::List)
        .history_ignore_dups(true)
        .and_then(|b| b.max_history_size(10_000))
        .map(|b| b.build())
        .unwrap_or_default();
    let mut rl: Editor<ReplHelper, DefaultHistory> = match Editor::with_config(config) {
        Ok(rl) => rl,
        Err(e) => {
            eprintln!("error: cannot start the line editor: {e}");
            return;
        }
    };
    let mut helper = ReplHelper::new(&session);
    // https://no-color.org, and terminals that can't show colour
    helper.colour = std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
        && std::env::var("TERM").map_or(true, |t| t != "dumb");
    rl.set_helper(Some(helper));
    let history = history_path();
    if let Some(h) = &history {
        let _ = rl.load_history(h);
    }
    // Ctrl-C outside line editing (while an entry computes) is a signal.
    let _ = ctrlc::set_handler(|| INTERRUPTED.store(true, Ordering::SeqCst));
    let mut entry = String::new();
    'read: loop {
        let prompt = if entry.is_empty() { PROMPT } else { MORE };
        match rl.readline(prompt) {
            Ok(text) => {
                // A bracketed paste returns several lines at once: each is
                // taken as if typed on its own, in order.
                for line in text.split('\n') {
                    if !entry.is_empty() && starts_a_command(line) {
                        let pending = std::mem::take(&mut entry);
                        let (s, r) = execute_cancellable(session, &pending);
                        session = s;
                        print_response(&r);
                    }
                    entry.push_str(line.strip_suffix('\r').unwrap_or(line));
                    entry.push('\n');
                    if !is_complete(&entry) {
                        continue;
                    }
                    let text = std::mem::take(&mut entry);
                    let trimmed = text.trim_end();
                    if !trimmed.is_empty() {
                        let _ = rl.add_history_entry(trimmed);
                        if let Some(h) = &history {
                            let _ = rl.save_history(h);
                        }
                    }
                    let (s, r) = execute_cancellable(session, &text);
                    session = s;
                    print_response(&r);
                    if let Some(h) = rl.helper_mut() {
                        h.refresh(&session);
                    }
                    if r.quit {
                        break 'read;
                    }
                }
            }
            Err(ReadlineError::Interrupted) => {
                if entry.is_empty() {
                    println!("(Ctrl-D or :quit leaves)");
                } else {
                    entry.clear();
                    println!("(entry dropped)");
                }
            }
            Err(ReadlineError::Eof) => break,
            Err(e) => {
                eprintln!("error: {e}");
                break;
            }
        }
    }
    if let Some(h) = &history {
        let _ = rl.save_history(h);
    }
}

/// Run an entry on a worker thread on a copy of the session: the new
/// session and the response, or the old session if Ctrl-C interrupted it.
fn execute_cancellable(session: Session, entry: &str) -> (Session, Response) {
    let mut work = session.clone();
    let original = entry;
    let entry = entry.to_string();
    let ticket = qdot::engine::cancel::ticket();
    INTERRUPTED.store(false, Ordering::SeqCst);
    let (tx, rx) = mpsc::channel();
    let spawned = std::thread::Builder::new()
        .name("qdot-entry".into())
        .stack_size(64 << 20)
        .spawn(move || {
            qdot::engine::cancel::enter(ticket);
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                let r = work.execute(&entry);
                (work, r)
            }));
            let _ = tx.send(r.ok());
        });
    if spawned.is_err() {
        // no thread to be had: run it here, without Ctrl-C
        let mut s = session;
        let r = s.execute(original);
        return (s, r);
    }
    loop {
        match rx.recv_timeout(Duration::from_millis(25)) {
            Ok(Some((s, r))) => return (s, r),
            Ok(None) => {
                let r = Response {
                    err: "error: internal error while computing this entry (the session is as it was)\n".into(),
                    failed: true,
                    ..Response::default()
                };
                return (session, r);
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if INTERRUPTED.swap(false, Ordering::SeqCst) {
                    qdot::engine::cancel::cancel(ticket);
                    let r = Response {
                        err: "(interrupted; the session is as it was)\n".into(),
                        failed: true,
                        ..Response::default()
                    };
                    return (session, r);
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return (session, Response::default());
            }
        }
    }
}

/// Completion and highlighting from the session's names.
struct ReplHelper {
    colour: bool,
    coordinates: Vec<String>,
    parameters: Vec<String>,
    others: Vec<String>,
}

impl ReplHelper {
    fn new(s: &Session) -> ReplHelper {
        let mut h = ReplHelper {
            colour: true,
            coordinates: Vec::new(),
            parameters: Vec::new(),
            others: Vec::new(),
        };
        h.refresh(s);
        h
    }

    fn refresh(&mut self, s: &Session) {
        let sc = s.scene();
        self.coordinates = sc.coordinates.iter().map(|c| c.name.clone()).collect();
        self.parameters = sc.parameters.iter().map(|p| p.name.clone()).collect();
        self.others = s
            .names()
            .into_iter()
            .filter(|n| !self.coordinates.contains(n) && !self.parameters.contains(n))
            .collect();
    }
}

impl Helper for ReplHelper {}
impl Hinter for ReplHelper {
    type Hint = String;
}
impl Validator for ReplHelper {}

impl Completer for ReplHelper {
    type Candidate = Pair;

    fn complete(
        &self,
        line: &str,
        pos: usize,
        _ctx: &Context<'_>,
    ) -> rustyline::Result<(usize, Vec<Pair>)> {
        let (start, found) = completions(
            line,
            pos,
            &[&self.coordinates, &self.parameters, &self.others],
        );
        let pairs = found
            .into_iter()
            .map(|c| Pair {
                display: c.display,
                replacement: c.replacement,
            })
            .collect();
        Ok((start, pairs))
    }
}

impl Highlighter for ReplHelper {
    fn highlight<'l>(&self, line: &'l str, _pos: usize) -> Cow<'l, str> {
        if !self.colour {
            return Cow::Borrowed(line);
        }
        Cow::Owned(highlight(
            line,
            &self.coordinates,
            &self.parameters,
            &self.others,
        ))
    }

    fn highlight_char(&self, _line: &str, _pos: usize, _kind: CmdKind) -> bool {
        self.colour
    }
}
