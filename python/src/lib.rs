//! `rbf_dtg._native`: the Rust half of the Python package `rbf_dtg`.
//!
//! Thin on purpose: it converts arrays, calls the project's crates and maps their
//! errors; the estimator's Python half (`rbf_dtg/estimator.py`) does the
//! scikit-learn conventions. No identification logic lives here.
//!
//! | module | what |
//! |---|---|
//! | [`error`] | `rbf_dtg.Error` and the one mapping of a Rust error to it (the CLI's one-line message) |
//! | [`arrays`] | numpy ⇄ faer |
//! | [`interrupt`] | long calls without the GIL, stopped by Ctrl-C between their steps |
//! | [`rbf_model`] | `fit_rbf` (the `rbf fit` command's fit) and the fitted model |

mod arrays;
mod error;
mod interrupt;
mod rbf_model;

use pyo3::prelude::*;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("Error", m.py().get_type::<error::Error>())?;
    m.add_function(wrap_pyfunction!(rbf_model::fit_rbf, m)?)?;
    m.add_class::<rbf_model::RbfModel>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
