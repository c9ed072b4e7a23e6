//! The `qdot` command line.

use clap::{Parser, Subcommand, ValueEnum};
use qdot::output::{self, Format};
use qdot::{Diagnostic, Scene};
use std::process::ExitCode;

// Exact arithmetic allocates many small polynomials; mimalloc serves them
// faster than the system allocator (measured: ~25% of all instructions were
// glibc malloc/free on the seed problems).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[derive(Parser)]
#[command(
    name = "qdot",
    version,
    about = "Exact analytical mechanics: Lagrange's equations, derived and solved exactly"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum Fmt {
    Text,
    Json,
}

#[derive(Subcommand)]
enum Command {
    /// Derive Lagrange's equations, the mass matrix and the forcing.
    Derive {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
    },
    /// Derive, then solve exactly for the accelerations.
    Solve {
        file: String,
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let (file, fmt, solve) = match &cli.command {
        Command::Derive { file, format } => (file, *format, false),
        Command::Solve { file, format } => (file, *format, true),
    };
    let fmt = match fmt {
        Fmt::Text => Format::Text,
        Fmt::Json => Format::Json,
    };
    let src = match std::fs::read_to_string(file) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: cannot read `{file}`: {e}");
            return ExitCode::from(1);
        }
    };
    match run(&src, fmt, solve) {
        Ok((out, warnings)) => {
            for w in warnings {
                eprint!("{}", w.render(file, &src));
            }
            print!("{out}");
            ExitCode::SUCCESS
        }
        Err(d) => {
            eprint!("{}", d.render(file, &src));
            ExitCode::from(1)
        }
    }
}

fn run(src: &str, fmt: Format, solve: bool) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let scene = Scene::parse(src)?;
    let lag = scene.lagrange()?;
    let out = if solve {
        let acc = lag.accelerations()?;
        match fmt {
            Format::Text => output::solve_text(&lag, &acc),
            Format::Json => json(output::solve_json(&lag, &acc)),
        }
    } else {
        match fmt {
            Format::Text => output::derive_text(&lag),
            Format::Json => json(output::derive_json(&lag)),
        }
    };
    Ok((out, scene.warnings.clone()))
}

fn json(m: serde_json::Map<String, serde_json::Value>) -> String {
    let mut s = serde_json::to_string_pretty(&serde_json::Value::Object(m)).unwrap_or_default();
    s.push('\n');
    s
}
