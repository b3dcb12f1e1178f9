//! `rbf_dtg.Unit`'s facts: a unit as the command's `--unit ARG` resolves it.

use dtg_vib::commands::records::unit_of;
use nav_sensors::unit::Unit;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::raise;

/// The unit `--unit ARG` names (a built-in name or a unit file).
pub fn resolve(arg: &str) -> PyResult<Unit> {
    unit_of(Some(arg)).map_err(raise)
}

/// What Python shows of a unit.
pub fn info<'py>(py: Python<'py>, unit: &Unit) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", unit.name())?;
    d.set_item("file", unit.file())?;
    d.set_item("gyros", unit.gyro_names())?;
    d.set_item("accels", unit.accel_names())?;
    d.set_item("residues", unit.residue_names())?;
    let c = unit.columns();
    let columns = PyDict::new(py);
    columns.set_item("time", &c.time)?;
    columns.set_item("time_scale", c.time_scale)?;
    columns.set_item("temperature", &c.temperature)?;
    d.set_item("columns", columns)?;
    Ok(d)
}

/// `Unit(arg)`'s facts.
#[pyfunction]
pub fn unit_info<'py>(py: Python<'py>, arg: &str) -> PyResult<Bound<'py, PyDict>> {
    info(py, &resolve(arg)?)
}

/// The unit written as a unit file.
#[pyfunction]
pub fn unit_toml(arg: &str) -> PyResult<String> {
    Ok(resolve(arg)?.to_toml())
}
