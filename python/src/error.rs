//! `rbf_dtg.Error`: every refusal of the package, with the command line's one-line
//! message. It derives from `ValueError`, as scikit-learn expects of bad input.

use pyo3::PyErr;
use pyo3::exceptions::PyValueError;

pyo3::create_exception!(
    rbf_dtg,
    Error,
    PyValueError,
    "A refusal of rbf_dtg: bad input, settings that cannot be fitted, a numerical failure. The message is the command line's one-line error."
);

/// The one mapping of a Rust error to Python: the message the CLI prints after
/// `error: ` ([`cli_support::failure::message`]).
pub fn raise(e: impl Into<anyhow::Error>) -> PyErr {
    let e = e.into();
    Error::new_err(cli_support::failure::message(
        &e,
        cli_support::Style::TRIMMED,
    ))
}

/// A parameter refused as the CLI refuses a flag's value (clap's "invalid value …
/// for …"), named by its Python name.
pub fn invalid(name: &str, value: impl std::fmt::Display, why: impl std::fmt::Display) -> PyErr {
    Error::new_err(format!("invalid value '{value}' for {name}: {why}"))
}
