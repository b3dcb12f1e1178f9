//! The command's CSV output (a record in the unit's names and units) as
//! Python's columns: the names, and one float64 array each, read by the
//! library's own CSV reader, so the numbers are those the file would hold.

use numpy::PyArray1;
use pyo3::prelude::*;
use tabular::NumericTable;

/// Column names and values of a CSV text.
pub struct Columns {
    names: Vec<String>,
    values: Vec<Vec<f64>>,
}

impl Columns {
    /// Reads `text`; `name` labels errors.
    pub fn of_csv(text: &[u8], name: &str) -> anyhow::Result<Self> {
        let mut table = NumericTable::from_reader(text, name)?;
        let names = table.header().to_vec();
        let values = names
            .iter()
            .map(|n| table.take_column(n))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self { names, values })
    }

    /// `(names, arrays)`, which `rbf_dtg.loop` makes a DataFrame of.
    pub fn into_py(self, py: Python<'_>) -> (Vec<String>, Vec<Bound<'_, PyArray1<f64>>>) {
        let arrays = self
            .values
            .into_iter()
            .map(|v| PyArray1::from_vec(py, v))
            .collect();
        (self.names, arrays)
    }
}
