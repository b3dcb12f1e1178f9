//! A PX4 ULog file read with a unit: the unit's `[ulog]` table (or a
//! triad's `sensor_combined` default, [`Unit::ulog_table`]) says which
//! topic instance and field fills each column; `ulog` joins them on the
//! base stream's time stamps, and the table so made goes through the one
//! path of every log ([`super::csv::from_table`]): the same checks,
//! gap split and conversions as a CSV. A ULog's values are in PX4's units
//! (rad/s, m/s², °C, time in µs made s from the first row), whatever the
//! unit's `[units]` say of its CSV logs.

use std::io::Read;
use std::path::Path;

use tabular::NumericTable;
use ulog::Ulog;

use super::error::RecordError;
use super::time::GAP_FACTOR;
use crate::unit::Unit;

/// Whether the file at `path` starts as a ULog file does (a file that
/// cannot be opened is not: the CSV reader then says why).
pub fn is_ulog(path: &Path) -> bool {
    let mut head = [0u8; 7];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok_and(|()| Ulog::is_ulog(&head))
}

/// The table of the ULog file at `path` that `unit` reads (see the module
/// documentation), in PX4's units.
pub(super) fn table(path: &Path, unit: &Unit) -> Result<NumericTable, RecordError> {
    let file = path.display().to_string();
    let table = unit.ulog_table().ok_or_else(|| RecordError::NoUlogTable {
        file: file.clone(),
        unit_file: unit.file().to_string(),
    })?;
    let log = Ulog::read(path)?;
    let mut names: Vec<&str> = unit.gyro_names();
    names.extend(unit.accel_names());
    // The temperature and any other entry of the table: extra columns.
    names.extend(
        table
            .columns
            .keys()
            .map(String::as_str)
            .filter(|n| !unit.gyro_names().contains(n) && !unit.accel_names().contains(n)),
    );
    let joined = table.join(&log, &names, GAP_FACTOR)?;
    let mut header = vec![unit.columns().time.clone()];
    let mut columns = vec![joined.t_s];
    for (name, values) in joined.columns {
        header.push(name);
        columns.push(values);
    }
    Ok(NumericTable::from_columns(&file, header, columns)?)
}
