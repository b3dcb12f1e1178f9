//! How to fix a failed fit, said as the flag to change.
//!
//! The library's errors carry the numbers (rank, condition, rows, centres); this
//! module maps them to the command-line remedy appended to the one-line error.

use rbf::{RbfError, SolveError, WidthError};

/// The largest ridge a hint proposes: the weights' penalty then matches the
/// kernel columns' own scale (Gaussian values ≤ 1), beyond which the fit
/// stops following the data.
const MAX_SUGGESTED_RIDGE: f64 = 1.0;

/// The remedy for `err`, if a flag fixes it. `ridge` is the ridge the fit used.
///
/// ```
/// use rbf::{RbfError, SolveError};
/// let e = RbfError::Solve(SolveError::NotPositiveDefinite { pivot: 3 });
/// assert_eq!(rbf_cli::hint::fix_for(&e, 0.0).as_deref(), Some("use --ridge 1e-8"));
/// assert_eq!(rbf_cli::hint::fix_for(&e, 1e-8).as_deref(), Some("use a larger --ridge (e.g. 1e-6)"));
/// let e = RbfError::FewerRowsThanCentres { rows: 20, centres: 50, most: 19 };
/// assert_eq!(rbf_cli::hint::fix_for(&e, 0.0).as_deref(), Some("use --max-centers ≤ 19"));
/// ```
pub fn fix_for(err: &RbfError, ridge: f64) -> Option<String> {
    match err {
        RbfError::Solve(
            SolveError::IllConditioned { .. }
            | SolveError::RankDeficient { .. }
            | SolveError::NotPositiveDefinite { .. },
        ) => {
            if ridge >= MAX_SUGGESTED_RIDGE {
                // A larger ridge would only swamp the data: the cause is elsewhere.
                Some("use fewer centres (--max-centers) or a smaller --width".to_string())
            } else if ridge > 0.0 {
                Some(format!(
                    "use a larger --ridge (e.g. {:e})",
                    (ridge * 100.0).clamp(1e-8, MAX_SUGGESTED_RIDGE)
                ))
            } else {
                Some("use --ridge 1e-8".to_string())
            }
        }
        RbfError::FewerRowsThanCentres { rows: 0, .. } => {
            Some("the training set is empty: check the split".to_string())
        }
        // `most` comes from the rule that refused: the value proposed works.
        RbfError::FewerRowsThanCentres { most: 0, .. } => {
            Some("use more training rows or a lower --degree".to_string())
        }
        RbfError::FewerRowsThanCentres { most, .. } => Some(format!("use --max-centers ≤ {most}")),
        RbfError::Memory(m) => Some(format!(
            "use --candidates {} (OLS picks centres from a random subsample of the training rows)",
            m.max_columns.max(1)
        )),
        // The library's message already says "use a fixed width": say how.
        RbfError::Width(WidthError::Degenerate) => Some("give it with --width BETA".to_string()),
        RbfError::Width(WidthError::TooFewCentres { .. }) => {
            Some("use a fixed --width BETA".to_string())
        }
        RbfError::TooFewSamples { needed, .. } => {
            Some(format!("provide at least {needed} training rows"))
        }
        RbfError::FoldFailed { reason } if reason.contains("ridge") => {
            Some("use --ridge 1e-8 or add ridges to --ridges".to_string())
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hints propose only values that work: no "--max-centers ≤ 0", no
    /// "--ridge 1e302".
    #[test]
    fn hints_never_propose_invalid_values() {
        let e = RbfError::FewerRowsThanCentres {
            rows: 0,
            centres: 5,
            most: 0,
        };
        assert!(!fix_for(&e, 0.0).unwrap().contains("≤ 0"));
        let e = RbfError::Solve(SolveError::NotPositiveDefinite { pivot: 1 });
        assert!(!fix_for(&e, 1e300).unwrap().contains("--ridge"));
        assert_eq!(
            fix_for(&e, 0.5).as_deref(),
            Some("use a larger --ridge (e.g. 1e0)")
        );
    }
}
