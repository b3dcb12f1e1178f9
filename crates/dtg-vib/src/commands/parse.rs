//! The validators of numeric flags: each refuses a value with the valid
//! range, so clap's one-line error says how to fix it.

/// A false-alarm level, strictly between 0 and 1.
pub fn parse_alpha(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err(format!(
            "'{s}': a false-alarm level must lie strictly between 0 and 1 (e.g. 0.01)"
        )),
    }
}

/// A noise level in deg/h: positive and finite.
pub fn parse_sigma(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "'{s}': a noise level must be a positive number of deg/h (the gyros' white noise per sample, e.g. 0.1)"
        )),
    }
}

/// A share of the rms, from 0 to below 1.
pub fn parse_gain(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..1.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "'{s}': a gain is a fraction of the rms from 0 to below 1 (e.g. 0.1 for 10%)"
        )),
    }
}

/// `WX,WY,WZ`: three numbers, comma-separated (clap's `num_args = 3` with a
/// delimiter would count `0,0,10` as one value and refuse it).
pub fn parse_rate(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|c| c.trim().parse::<f64>().map_err(|e| format!("'{c}': {e}")))
        .collect::<Result<_, _>>()?;
    if v.iter()
        .any(|w| !(w.is_finite() && w.abs() <= MAX_TABLE_RATE_DEG_S))
    {
        return Err(format!(
            "each rate must be finite and within ±{MAX_TABLE_RATE_DEG_S} deg/s"
        ));
    }
    v.try_into()
        .map_err(|v: Vec<f64>| format!("expected WX,WY,WZ (three numbers, deg/s), got {}", v.len()))
}

/// The fastest table rate `--table-rate` takes, deg/s: rate tables turn at
/// up to a few thousand deg/s; beyond, the rate reference only overflows.
const MAX_TABLE_RATE_DEG_S: f64 = 10_000.0;

/// A count (window samples, centres, candidates): a whole number ≥ 1.
pub fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("must be a whole number ≥ 1".into()),
    }
}

/// A fraction strictly between 0 and 1.
pub fn parse_fraction(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err("must be a number strictly between 0 and 1".into()),
    }
}

/// A cut-off frequency: positive and finite here; its upper bound (the
/// record's Nyquist frequency) is checked once the record is read.
pub fn parse_hz(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err("must be a positive frequency in Hz, below the record's Nyquist frequency".into()),
    }
}

/// A low-pass order the filter takes.
pub fn parse_order(s: &str) -> Result<usize, String> {
    let max = crate::signal::MAX_ORDER;
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!("must be a whole number from 1 to {max}")),
    }
}

/// The largest `--ridge`: beyond it the penalty swamps the unpenalised bias
/// and effect columns and the solve reports them rank deficient (measured:
/// 1e18 still fits, 1e30 does not); at 1e12 the kernel weights are zero.
const MAX_RIDGE: f64 = 1e12;

/// A ridge from 0 to [`MAX_RIDGE`].
pub fn parse_ridge(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=MAX_RIDGE).contains(&v) => Ok(v.abs()),
        _ => Err(format!("must be a number from 0 to {MAX_RIDGE:e}")),
    }
}

/// A latitude, deg.
pub fn parse_latitude(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() <= 90.0 => Ok(v),
        _ => Err(format!(
            "'{s}': a latitude must be a number from -90 to 90 (deg)"
        )),
    }
}

/// A share from 0 to 1.
pub fn parse_share(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("{s:?} is not a share between 0 and 1 (e.g. 0.05)")),
    }
}
