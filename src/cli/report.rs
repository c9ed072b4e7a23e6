//! Where the command line writes: results to standard output, errors and
//! warnings to standard error (as text or JSON lines).

use std::process::ExitCode;

/// Write a result to standard output. A reader that has gone (`qdot … |
/// head`) is not an error of the run: `print!` would panic on the closed
/// pipe; the rest is dropped instead.
pub fn emit(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            eprintln!("error: cannot write the result: {e}");
        }
    }
}

/// Where a command's errors and warnings go: standard error, as text about
/// the scene file, or (`--format json`, `--output json`) one JSON object
/// per line ([`qdot::Diagnostic::to_json`]).
#[derive(Clone, Copy)]
pub struct Reporter<'a> {
    /// The scene file, as named on the command line.
    pub file: &'a str,
    /// Whether diagnostics are printed as JSON.
    json: bool,
}

impl<'a> Reporter<'a> {
    pub fn new(file: &'a str, json: bool) -> Reporter<'a> {
        Reporter { file, json }
    }

    /// Print a diagnostic about `src` (an error or a warning).
    pub fn print(&self, d: &qdot::Diagnostic, src: &str) {
        if self.json {
            eprintln!("{}", d.to_json(src));
        } else {
            eprint!("{}", d.render(self.file, src));
        }
    }

    /// Print an error about `src`; the exit status of a failed command.
    pub fn fail(&self, d: &qdot::Diagnostic, src: &str) -> ExitCode {
        self.print(d, src);
        ExitCode::from(1)
    }

    /// The scene file's text, or the exit status after reporting why it
    /// cannot be read or is not UTF-8.
    pub fn read_scene(&self) -> Result<String, ExitCode> {
        qdot::diag::read_source(self.file).map_err(|e| {
            let (d, text) = e.diagnostic();
            self.fail(&d, text)
        })
    }
}
