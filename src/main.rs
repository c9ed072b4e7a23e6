//! The `qdot` command line.

use clap::{Parser, Subcommand, ValueEnum};
use qdot::output::{self, Format};
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
    /// Solve exactly: the accelerations of Lagrange's equations, and the
    /// scene's `solve` blocks (reactions, kinetostatic systems).
    Solve {
        file: String,
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
    },
    /// The generalized forces Q_k (virtual work δL = Σ Q_k·δq_k).
    Forces {
        file: String,
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
    },
    /// Equilibrium positions (Q_k = 0) and their stability.
    Equilibrium {
        file: String,
        #[arg(long, value_enum, default_value = "text")]
        format: Fmt,
        /// Parameter values for numeric roots and sign decisions: m=1,g=9.81
        #[arg(long)]
        set: Option<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let (cmd, file, fmt, set) = match &cli.command {
        Command::Derive { file, format } => (output::Command::Derive, file, *format, None),
        Command::Solve { file, format } => (output::Command::Solve, file, *format, None),
        Command::Forces { file, format } => (output::Command::Forces, file, *format, None),
        Command::Equilibrium { file, format, set } => {
            (output::Command::Equilibrium, file, *format, set.as_deref())
        }
    };
    let fmt = match fmt {
        Fmt::Text => Format::Text,
        Fmt::Json => Format::Json,
    };
    let set = match set.map(output::parse_set).transpose() {
        Ok(s) => s.unwrap_or_default(),
        Err(d) => {
            eprint!("{}", d.render(file, ""));
            return ExitCode::from(1);
        }
    };
    let src = match std::fs::read_to_string(file) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: cannot read `{file}`: {e}");
            return ExitCode::from(1);
        }
    };
    match output::run(cmd, &src, fmt, &set) {
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
