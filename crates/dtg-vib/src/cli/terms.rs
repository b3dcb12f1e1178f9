//! What the words the tables print mean, each said once in a short line
//! under the output that uses it: the terms a newcomer met in the terminal
//! and could read only with the docs (issue 26 item 5). A term is explained
//! only where it was printed, so a clean result stays short.

/// Under `check`'s channel table: which columns are about the mean, so
/// that "before" is compared with "spread after", not with "rms after".
pub const CHECK_COLUMNS: &str = "rms before and spread after are about the mean (rms after² = mean after² + spread after²); inside, outside: rms after on the windows inside and outside the training range";

/// What `check`'s reference distance is, in its line.
pub const REFERENCE_DISTANCE: &str =
    "99% of the model's own validation windows lie within it of a training point";

/// What a negative fit percentage says, naming the channels that have one;
/// nothing when none has.
pub fn negative_fit(channels: &[&str]) -> Option<String> {
    (!channels.is_empty()).then(|| {
        format!(
            "fit % = 100·(1 − residual rms / rms about the mean); below 0 on {}: the model leaves more than the mean alone would, worse than the mean",
            channels.join(", ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_negative_fit_is_said_only_where_there_is_one() {
        assert_eq!(negative_fit(&[]), None);
        let line = negative_fit(&["X", "Y"]).unwrap();
        assert!(line.contains("below 0 on X, Y") && line.contains("worse than the mean"));
    }
}
