//! Where a unit's columns come from in a PX4 ULog file: the unit file's
//! optional `[ulog]` table (`ulog::UlogTable`), checked against the unit
//! when the unit loads, and the default of a triad on x, y, z, PX4's
//! `sensor_combined`. A ULog's values are in PX4's units (rad/s, m/s², °C)
//! whatever `[units]` says: `[units]` describes the unit's CSV logs.

use nalgebra::Vector3;
use ulog::UlogTable;

use super::error::UnitError;

/// A sensor as the table sees it: its column name and input axis.
pub(crate) type Sensor<'a> = (&'a str, Vector3<f64>);

/// Checks a `[ulog]` table against the unit's columns: every gyro,
/// accelerometer and the temperature column mapped, no entry for the time
/// column (the base stream's time stamps are the time), `base` one of the
/// entries, and no empty topic, field or time field. Entries for other
/// names are the log's extra columns.
pub(crate) fn validate(
    file: &str,
    table: &UlogTable,
    (time, temperature): (&str, Option<&str>),
    gyros: &[Sensor],
    accels: &[Sensor],
) -> Result<(), UnitError> {
    let bad = |key: String, problem: String| UnitError::UlogTable {
        file: file.to_string(),
        key,
        problem,
    };
    let mut needed: Vec<(String, &str)> = Vec::new();
    for (k, (name, _)) in gyros.iter().enumerate() {
        needed.push((format!("gyro[{k}].name"), name));
    }
    for (k, (name, _)) in accels.iter().enumerate() {
        needed.push((format!("accel[{k}].name"), name));
    }
    if let Some(t) = temperature {
        needed.push(("columns.temperature".into(), t));
    }
    for (key, name) in &needed {
        if !table.columns.contains_key(*name) {
            return Err(bad(
                "ulog.columns".into(),
                format!(
                    "no entry for '{name}' ({key}); add `{name} = {{ topic = \"…\", field = \"…\" }}`"
                ),
            ));
        }
    }
    if table.columns.contains_key(time) {
        return Err(bad(
            format!("ulog.columns.{time}"),
            "the time column comes from the base stream's time stamps; remove the entry".into(),
        ));
    }
    if let Some(base) = &table.base
        && !table.columns.contains_key(base)
    {
        return Err(bad(
            "ulog.base".into(),
            format!("'{base}' is not an entry of ulog.columns; name one of them"),
        ));
    }
    for (name, s) in &table.columns {
        let parts = [
            ("topic", Some(&s.topic)),
            ("field", Some(&s.field)),
            ("time", Some(&s.time)),
            ("time_offset", s.time_offset.as_ref()),
            ("interval", s.interval.as_ref()),
        ];
        for (what, value) in parts {
            if value.is_some_and(|v| v.trim().is_empty()) {
                return Err(bad(
                    format!("ulog.columns.{name}.{what}"),
                    "is empty; give the ULog's name for it (docs/formats.md)".into(),
                ));
            }
        }
    }
    Ok(())
}

/// The default for a unit without a `[ulog]` table: a triad whose three
/// gyros and three accelerometers lie on +x, +y, +z (in any order) reads
/// PX4's `sensor_combined` (`gyro_rad[k]`, `accelerometer_m_s2[k]` on axis
/// k). `None` for any other unit, or one naming a temperature column
/// (`sensor_combined` has none).
pub(crate) fn default_table(
    temperature: Option<&str>,
    gyros: &[Sensor],
    accels: &[Sensor],
) -> Option<UlogTable> {
    if temperature.is_some() {
        return None;
    }
    let gyros = on_axes(gyros.iter().copied())?;
    let accels = on_axes(accels.iter().copied())?;
    Some(UlogTable::sensor_combined(gyros, accels))
}

/// Three sensors, one on each of +x, +y, +z: their names in axis order.
fn on_axes<'a>(sensors: impl Iterator<Item = (&'a str, Vector3<f64>)>) -> Option<[&'a str; 3]> {
    let mut by_axis: [Option<&str>; 3] = [None; 3];
    let mut count = 0;
    for (name, input) in sensors {
        count += 1;
        let k = (0..3).find(|&k| input == Vector3::ith(k, 1.0))?;
        if by_axis[k].replace(name).is_some() {
            return None;
        }
    }
    if count != 3 {
        return None;
    }
    Some([by_axis[0]?, by_axis[1]?, by_axis[2]?])
}
