//! `rbf_dtg._native`: the Rust half of the Python package `rbf_dtg`.
//!
//! Thin on purpose: it converts arrays, calls the project's crates and maps their
//! errors; the Python half (`rbf_dtg/estimator.py`, `rbf_dtg/loop.py`) does the
//! scikit-learn conventions and the DataFrames. No identification logic lives here.
//!
//! | module | what |
//! |---|---|
//! | [`error`] | `rbf_dtg.Error` and the one mapping of a Rust error to it (the CLI's one-line message) |
//! | [`arrays`] | numpy ⇄ faer |
//! | [`interrupt`] | long calls without the GIL, stopped by Ctrl-C between their steps |
//! | [`rbf_model`] | `fit_rbf` (the `rbf fit` command's fit) and the fitted model |
//! | [`stage`] | records and calibrations from Python as the files the `dtg-vib` command reads |
//! | [`flags`] | keyword arguments parsed as the command's flags |
//! | [`table`] | the command's CSV output as Python's columns |
//! | [`unit`] | a unit as `--unit` resolves it |
//! | [`calls`] | `read_record`, `simulate`, `fit`, `explain`: the `dtg-vib` commands' library functions |
//! | [`analyses`] | `residues`, `allan`: a record's, with or without a model |
//! | [`model`] | a unit's model: `diagnose`, `check`, `compensate`, `report`, the model file |

mod analyses;
mod arrays;
mod calls;
mod error;
mod flags;
mod interrupt;
mod model;
mod rbf_model;
mod stage;
mod table;
mod unit;

use pyo3::prelude::*;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("Error", m.py().get_type::<error::Error>())?;
    m.add_function(wrap_pyfunction!(rbf_model::fit_rbf, m)?)?;
    m.add_class::<rbf_model::RbfModel>()?;
    m.add_function(wrap_pyfunction!(unit::unit_info, m)?)?;
    m.add_function(wrap_pyfunction!(unit::unit_toml, m)?)?;
    m.add_function(wrap_pyfunction!(calls::read_record, m)?)?;
    m.add_function(wrap_pyfunction!(calls::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(calls::fit, m)?)?;
    m.add_function(wrap_pyfunction!(calls::explain, m)?)?;
    m.add_function(wrap_pyfunction!(calls::write_text, m)?)?;
    m.add_function(wrap_pyfunction!(analyses::residues, m)?)?;
    m.add_function(wrap_pyfunction!(analyses::allan, m)?)?;
    m.add_class::<model::Model>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
