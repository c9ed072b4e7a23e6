//! What can go wrong compiling exact expressions to f64 code, and running
//! the compiled dynamics.

use std::fmt;

/// Why expressions did not compile, or a compiled evaluation failed. Its
/// `Display` is the message qdot prints after "cannot compile the
/// equations: ".
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CompileError {
    /// A parameter (or a `solve` unknown) with no value that is not an
    /// input either: its name.
    UnsetParameter(String),
    /// A coordinate, one of its derivatives, or the time, used but not
    /// an input: described as `the coordinate x'` or `the time t`.
    NotAnInput(String),
    /// A given function of time (or one of its derivatives) with no
    /// definition: `f''`.
    UndefinedFunction(String),
    /// A √n whose n is not an integer (the atom table is inconsistent).
    BadRadical(String),
    /// An atom that exists only in printed output reached the compiler.
    PrintOnly,
    /// Slices or matrices of the wrong size: what was expected.
    Shape(String),
    /// A numerically singular matrix: a zero (or non-finite) pivot in
    /// `column`. `constant_mass` when it is the constant mass matrix,
    /// inverted once at construction.
    Singular {
        /// The column of the zero pivot.
        column: usize,
        /// Whether the matrix is the constant mass matrix.
        constant_mass: bool,
    },
    /// The exact accelerations could not be derived: the reason.
    NoAccelerations(String),
    /// M and f were asked of dynamics compiled without them: how it was
    /// compiled instead.
    NoMassMatrix(&'static str),
}

impl fmt::Display for CompileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompileError::UnsetParameter(name) => {
                write!(f, "the parameter {name} has no value and is not an input")
            }
            CompileError::NotAnInput(what) => write!(f, "{what} is not an input"),
            CompileError::UndefinedFunction(name) => {
                write!(f, "the given function {name} has no definition")
            }
            CompileError::BadRadical(n) => write!(f, "bad radical √{n}"),
            CompileError::PrintOnly => f.write_str("a print-only atom cannot be evaluated"),
            CompileError::Shape(expected) => f.write_str(expected),
            CompileError::Singular {
                column,
                constant_mass,
            } => {
                if *constant_mass {
                    f.write_str("the constant mass matrix: ")?;
                }
                write!(f, "the matrix is singular (column {column})")
            }
            CompileError::NoAccelerations(reason) => f.write_str(reason),
            CompileError::NoMassMatrix(how) => f.write_str(how),
        }
    }
}

impl std::error::Error for CompileError {}

impl CompileError {
    /// The kind of the diagnostic that reports this error: a value the
    /// user did not give, a definition missing, a singular matrix; the
    /// rest are the caller's mistakes ([`crate::diag::ErrorKind::Internal`]).
    pub fn kind(&self) -> crate::diag::ErrorKind {
        use crate::diag::ErrorKind;
        match self {
            CompileError::UnsetParameter(_) => ErrorKind::BadOption {
                option: "--set".into(),
            },
            CompileError::UndefinedFunction(_) => ErrorKind::Undefined,
            CompileError::Singular { .. } => ErrorKind::SingularSystem {
                unknowns: Vec::new(),
            },
            CompileError::NoAccelerations(_) => ErrorKind::NoClosedForm,
            CompileError::NotAnInput(_)
            | CompileError::BadRadical(_)
            | CompileError::PrintOnly
            | CompileError::Shape(_)
            | CompileError::NoMassMatrix(_) => ErrorKind::Internal,
        }
    }
}

impl From<crate::dense::DenseError> for CompileError {
    fn from(e: crate::dense::DenseError) -> CompileError {
        match e {
            crate::dense::DenseError::Shape { .. } => CompileError::Shape(e.to_string()),
            crate::dense::DenseError::Singular { column } => CompileError::Singular {
                column,
                constant_mass: false,
            },
        }
    }
}
