//! The `qdot` command line: the arguments read into the application
//! layer's options (`cli::args`), each command run through it
//! (`cli::run`).

/// The command line's own modules (not the library's).
mod cli {
    pub mod args;
    pub mod report;
    pub mod run;
    pub mod study;
    pub mod terminal;
}

use clap::Parser;
use cli::args::{Cli, Command};
use qdot::output;
use std::process::ExitCode;

// Exact arithmetic allocates many small polynomials; mimalloc serves them
// faster than the system allocator (measured: ~25% of all instructions were
// glibc malloc/free on the seed problems).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let max_terms = cli.max_terms;
    let Some(command) = cli.command else {
        return cli::run::repl(None, false, max_terms);
    };
    match &command {
        Command::Repl { file, echo } => cli::run::repl(file.as_deref(), *echo, max_terms),
        Command::Simulate(args) => cli::run::simulate(args, max_terms),
        Command::Sweep(args) => cli::run::sweep(args, max_terms),
        Command::Codegen(args) => cli::run::codegen(args, max_terms),
        Command::Cycle(o) => cli::study::run(
            output::Command::Cycle,
            &o.file,
            o.output_name(),
            max_terms,
            |x| o.options(x),
            |r| o.pictures(r),
        ),
        Command::Response(o) => cli::study::run(
            output::Command::Response,
            &o.file,
            &o.output,
            max_terms,
            |x| o.options(x),
            |r| o.pictures(r),
        ),
        Command::Floquet(o) => cli::study::run(
            output::Command::Floquet,
            &o.file,
            &o.output,
            max_terms,
            |x| o.options(x),
            |r| o.pictures(r),
        ),
        // the exact commands (every other is matched above)
        exact => exact
            .exact()
            .map_or(ExitCode::FAILURE, |a| cli::run::exact(a, max_terms)),
    }
}
