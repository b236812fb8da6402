//! Errors of the compiler and of compiled models.

/// Everything that can go wrong when compiling a design or loading a model.
#[derive(Debug, thiserror::Error, Clone, PartialEq, Eq)]
pub enum Error {
    /// A construct the compiler does not translate (with the module and the reason).
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// A signal name in a module's HDL that matches no signal.
    #[error("module `{module}`: unknown signal `{name}`")]
    UnknownSignal { module: String, name: String },
    /// Operand widths that Rust's type check would not have let through
    /// (a compiler bug or a construct it misreads).
    #[error("module `{module}`: {what}")]
    Width { module: String, what: String },
    /// A combinational loop, with the signals on it.
    #[error("combinational loop through: {}", .0.join(", "))]
    CombLoop(Vec<String>),
    /// A signal driven from two modules' code.
    #[error("signal `{0}` is assigned in two modules")]
    MultipleDrivers(String),
    /// A compiled model built from a rust-hdl instance of another shape.
    #[error(
        "no compiled model for this design shape: {model} has fingerprint {expected:#018x}, the instance has {found:#018x} \
         (compile a model for this configuration with canstar_rtlc::generate)"
    )]
    ShapeMismatch { model: String, expected: u64, found: u64 },
}

pub type Result<T> = std::result::Result<T, Error>;
