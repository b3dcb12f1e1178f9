//! Values the loop cannot square: a record's values are within ±1e150 (the
//! reader refuses more), but a calibration's polynomial terms (an
//! accelerometer's k3·a³, a gyro's g² sensitivities) or an effect's
//! products can carry them past what the filter and the fit can work with.
//! Each is refused naming the column (or effect), the value and its time.

use crate::error::DtgVibError;
use sysid::Signals;

/// What to check when a calibrated value is out of range.
pub(crate) const CALIBRATED_HINT: &str = "the calibration's coefficients or the record's values are out of range: check the units of both";

/// What to check when an effect's regressor is out of range.
pub(crate) const REGRESSOR_HINT: &str = "the record's accelerations (g) or rates are too large for this effect's products: check their units, or drop the effect";

/// The first value of `x` that is non-finite or beyond ±1e150, as an error
/// naming `what` and the record time.
pub(crate) fn check_range(
    what: impl FnOnce() -> String,
    x: &[f64],
    t: &[f64],
    hint: &'static str,
) -> Result<(), DtgVibError> {
    match x
        .iter()
        .position(|v| !(v.is_finite() && v.abs() <= tabular::MAX_MAGNITUDE))
    {
        None => Ok(()),
        Some(i) => Err(sysid::SysidError::OutOfRange {
            what: what(),
            value: x[i],
            t: t[i],
            row: i + 1,
            hint,
        }
        .into()),
    }
}

/// Each of the named columns of a calibrated record within range, in the
/// order given (the unit's gyros, then its accelerometers); a name the
/// record lacks is left to whoever reads it.
pub(crate) fn check_calibrated<'a>(
    calibrated: &Signals,
    names: impl IntoIterator<Item = &'a str>,
) -> Result<(), DtgVibError> {
    for name in names {
        if let Some(x) = calibrated.column(name) {
            check_range(
                || format!("column '{name}' after calibration"),
                x,
                calibrated.t(),
                CALIBRATED_HINT,
            )?;
        }
    }
    Ok(())
}
