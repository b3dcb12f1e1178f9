//! The fit as `rbf fit` runs it, for every caller that must give the command's
//! model: the `rbf` binary and the Python binding (`python/`). One entry, so the
//! width search of `--width auto --stop press|gcv` and the remedy appended to a
//! failure are never written twice.

use anyhow::Result;
use rbf::faer::{Mat, MatRef};
use rbf::{RbfError, RbfModel, RbfValidParams};

use crate::hint;
use crate::report::WidthTrial;
use crate::settings::{FitSettings, WIDTH_GRID};

/// A fitted model and the widths `--width auto` tried to find it (empty unless it
/// searched).
#[derive(Clone, Debug)]
pub struct Fitted {
    /// The model.
    pub model: RbfModel,
    /// Every width of the search, with the size it kept and its PRESS.
    pub width_search: Vec<WidthTrial>,
}

/// Fits `params` (built from `settings` for these rows) on `x` → `y`, reporting to
/// `observe`: one fit, or with `--width auto --stop press|gcv` (OLS) one per width of
/// [`WIDTH_GRID`], the least PRESS kept.
///
/// # Errors
/// The library's error with the flag that fixes it, if any ([`hint::fix_for`]).
///
/// ```
/// use rbf::faer::Mat;
/// use rbf_cli::settings::{Centres, FitSettings, WidthArg};
/// let x = Mat::from_fn(40, 1, |i, _| i as f64 / 10.0);
/// let y = Mat::from_fn(40, 1, |i, _| (i as f64 / 10.0).sin());
/// let s = FitSettings { centres: Centres::Ols, max_centres: Some(5), width: WidthArg::Fixed(1.0), ..Default::default() };
/// let p = s.params(40, 1)?;
/// let fitted = rbf_cli::train::fit(&s, &p, x.as_ref(), y.as_ref(), &|_| {})?;
/// assert_eq!(fitted.model.n_centres(), 5);
/// assert!(fitted.width_search.is_empty());
/// # Ok::<(), anyhow::Error>(())
/// ```
pub fn fit(
    settings: &FitSettings,
    params: &RbfValidParams,
    x: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    observe: &(dyn Fn(rbf::Progress) + Sync),
) -> Result<Fitted> {
    let mut width_search = Vec::new();
    let fitted = if settings.searches_width() {
        search_width(settings, x, y, observe, &mut width_search)?
    } else {
        let no_linear = Mat::<f64>::zeros(x.nrows(), 0);
        params.fit_with_progress(x, no_linear.as_ref(), y, observe)
    };
    let model = fitted.map_err(|e| failed(e, settings))?;
    Ok(Fitted {
        model,
        width_search,
    })
}

/// `--width auto` with `--stop press|gcv`: one OLS run per width of
/// [`WIDTH_GRID`] × the median pairwise distance, each keeping the size `--stop`
/// chooses; the model with the least PRESS at that size wins, the first on ties. Widths whose fit fails
/// (e.g. too ill-conditioned) are skipped; if every one fails, the last error is
/// returned.
fn search_width(
    settings: &FitSettings,
    x: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    observe: &(dyn Fn(rbf::Progress) + Sync),
    trials: &mut Vec<WidthTrial>,
) -> Result<Result<RbfModel, RbfError>> {
    let no_linear = Mat::<f64>::zeros(x.nrows(), 0);
    let mut best: Option<(f64, RbfModel)> = None;
    let mut last_err = None;
    for scale in WIDTH_GRID {
        let p = settings.params_with_width(
            x.nrows(),
            x.ncols(),
            rbf::WidthRule::MedianPairwise { scale },
        )?;
        let m = match p.fit_with_progress(x, no_linear.as_ref(), y, observe) {
            Ok(m) => m,
            Err(e) => {
                last_err = Some(e);
                continue;
            }
        };
        let k = m.n_centres();
        let Some(c) = m
            .selection()
            .and_then(|s| s.criterion.iter().find(|c| c.k == k))
        else {
            continue;
        };
        // Widths are compared by PRESS even under --stop gcv: GCV counts parameters,
        // not leverage, and rewards near-interpolating narrow kernels (sunspots:
        // GCV 92 at k = 99 with β/4, validation rms 52 against 24).
        let value = c.press;
        trials.push(WidthTrial {
            scale,
            width: m.widths().get(0),
            k,
            criterion: value,
        });
        if best.as_ref().is_none_or(|(b, _)| value < *b) {
            best = Some((value, m));
        }
    }
    Ok(match (best, last_err) {
        (Some((_, m)), _) => Ok(m),
        (None, Some(e)) => Err(e),
        (None, None) => anyhow::bail!("--width auto: no width of the grid gave a model"),
    })
}

/// The library's error with the flag that fixes it, if any.
///
/// ```
/// let e = rbf::RbfError::FewerRowsThanCentres { rows: 20, centres: 50, most: 19 };
/// let s = rbf_cli::settings::FitSettings::default();
/// assert_eq!(rbf_cli::train::failed(e, &s).to_string(), "fit failed: 20 rows take at most 19 centres, not 50; use --max-centers ≤ 19");
/// ```
pub fn failed(e: RbfError, settings: &FitSettings) -> anyhow::Error {
    match hint::fix_for(&e, settings.ridge) {
        Some(fix) => anyhow::anyhow!("fit failed: {e}; {fix}"),
        None => anyhow::Error::from(e).context("fit failed"),
    }
}
