//! Cross-fitted effect coefficients remembered within a process.
//!
//! One estimate of each coefficient is made three times in the explain loop
//! (the demo's): the diagnosis states a suggestion's coefficient with the
//! fit's estimator ([`crate::diagnose`]'s restatement), and the refit makes
//! the same estimate again for each input its choice tries (both read the
//! raw windows, whatever input the network then takes). Each estimate is six
//! cross-validated networks (three cuts, two blocks each): on the demo the
//! two repeats were 12 of its 44 network fits. The estimate is a pure
//! function of the rows it reads (every random choice is seeded), so one
//! asked again with the same inputs is taken from here, bit for bit the one
//! computed before.
//!
//! The key holds digests ([`super::digest`]) of the rows the estimate reads
//! (the windows, effect columns and target on `theta_rows`), the rows
//! themselves, the settings and the leakage gap. Failures are not
//! remembered: they are computed again, and say so again.

use super::digest::{Digest, Digester, Store};
use crate::inference::HacFit;
use crate::recipe::FitSettings;
use faer::{Mat, MatRef};

/// Estimates remembered; the oldest is dropped beyond this (each is a few
/// numbers per effect).
const CAPACITY: usize = 256;

static ESTIMATES: Store<Option<HacFit>> = Store::new(CAPACITY);

/// `estimate()`, the cross-fitted θ of `y` on the effect columns `z` over
/// rows `theta_rows` of the windows `x_theta`, taken from the estimates
/// remembered when one with the same inputs was made before.
///
/// Two threads asking for the same estimate at once may both compute it (a
/// wait there could deadlock a rayon worker that holds the first
/// computation's work); both get the same numbers.
pub(in crate::fit) fn remembered<E>(
    (x_theta, z, y): (MatRef<'_, f64>, &Mat<f64>, &[f64]),
    theta_rows: &[usize],
    settings: &FitSettings,
    gap: usize,
    estimate: impl FnOnce() -> Result<Option<HacFit>, E>,
) -> Result<Option<HacFit>, E> {
    let key = digest((x_theta, z, y), theta_rows, settings, gap);
    if let Some(f) = ESTIMATES.recall(key) {
        return Ok(f);
    }
    let f = estimate()?;
    ESTIMATES.keep(key, &f);
    Ok(f)
}

/// Everything [`crate::fit::partial::cross_fitted_theta`] reads: the rows `theta_rows` of
/// the windows, effect columns and target (the cuts' blocks are among
/// them), the rows' indices (the cuts and the gap read them), the settings
/// and the gap.
fn digest(
    (x, z, y): (MatRef<'_, f64>, &Mat<f64>, &[f64]),
    rows: &[usize],
    settings: &FitSettings,
    gap: usize,
) -> Digest {
    let mut d = Digester::new();
    d.usizes(rows);
    d.word(x.ncols() as u64);
    d.word(z.ncols() as u64);
    for &r in rows {
        d.f64s((0..x.ncols()).map(|j| x[(r, j)]));
        d.f64s((0..z.ncols()).map(|j| z[(r, j)]));
        d.word(y[r].to_bits());
    }
    // The choice only says which inputs and smoothers a fit tries; the
    // estimate reads the rest.
    let settings = FitSettings {
        choice: None,
        ..settings.clone()
    };
    d.text(&format!("{settings:?}"));
    d.word(gap as u64);
    d.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A remembered estimate is returned without computing; different rows,
    /// a different target or other settings are computed.
    #[test]
    fn an_estimate_is_remembered_by_what_it_reads() {
        let x = Mat::from_fn(40, 2, |i, j| (i * (j + 1)) as f64 * 0.37);
        let z = Mat::from_fn(40, 1, |i, _| (i % 5) as f64);
        let y: Vec<f64> = (0..40).map(|i| (i as f64 * 0.3).sin() + 1e-3).collect();
        let rows: Vec<usize> = (0..40).step_by(2).collect();
        let settings = FitSettings::default();
        let fit = |coef: f64| HacFit {
            coef: vec![coef],
            se: vec![0.1],
            cov: vec![vec![0.01]],
            bandwidth: 3,
            dof: 10.0,
            rss: 1.0,
            yy: 2.0,
            n: 20,
        };
        let ask = |y: &[f64], rows: &[usize], s: &FitSettings, v: f64| {
            remembered::<()>((x.as_ref(), &z, y), rows, s, 4, || Ok(Some(fit(v))))
                .unwrap()
                .unwrap()
                .coef[0]
        };
        assert_eq!(ask(&y, &rows, &settings, 1.0), 1.0);
        assert_eq!(ask(&y, &rows, &settings, 2.0), 1.0, "remembered");
        let mut other_y = y.clone();
        other_y[4] += 1.0;
        assert_eq!(ask(&other_y, &rows, &settings, 3.0), 3.0);
        // A row the estimate does not read does not matter.
        let mut unread = y.clone();
        unread[5] += 1.0;
        assert_eq!(ask(&unread, &rows, &settings, 4.0), 1.0);
        assert_eq!(ask(&y, &rows[1..], &settings, 5.0), 5.0);
        let seeded = FitSettings {
            seed: settings.seed + 1,
            ..settings.clone()
        };
        assert_eq!(ask(&y, &rows, &seeded, 6.0), 6.0);
        // A failure is not remembered.
        let y2: Vec<f64> = y.iter().map(|v| v * 2.0).collect();
        let failed = remembered::<&str>((x.as_ref(), &z, &y2), &rows, &settings, 4, || Err("no"));
        assert_eq!(failed, Err("no"));
        assert_eq!(ask(&y2, &rows, &settings, 7.0), 7.0);
    }
}
