//! What the words the tables print mean, each said once in a short line
//! under the output that uses it: the terms a newcomer met in the terminal
//! and could read only with the docs (issue 26 item 5). A term is explained
//! only where it was printed, so a clean result stays short.

use dtg_vib::unit_sensor::ANISOINERTIA_MIN_RATE_DEG_S;
use nav_sensors::dtg::DtgTerm;

/// Under `check`'s channel table: which columns are about the mean, so
/// that "before" is compared with "spread after", not with "rms after".
pub const CHECK_COLUMNS: &str = "rms before and spread after are about the mean (rms after² = mean after² + spread after²); inside, outside: rms after on the windows inside and outside the training range";

/// What `check`'s columns without the fade are.
pub const CHECK_FADE: &str = "rms after, mean after, spread after: the compensation as applied, its network part fading out beyond the per-axis range (it holds its last value there; the effects stay); no fade: the model as fitted, everywhere";

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

/// The lines under `diagnose`'s findings that say what their terms mean:
/// the candidates not ranked, the failing correlation tests, a negative fit,
/// and the words of the findings (cross-fitted, |r|, σ, white floor) where
/// they were printed.
pub fn diagnosis_terms<C: std::fmt::Display>(
    d: &sysid::diagnose::Diagnosis<C, nav_sensors::geometry::Axis>,
) -> Vec<String> {
    let mut out = Vec::new();
    let mut unexcited: Vec<(&str, &str)> = Vec::new();
    let mut failing: Vec<&str> = Vec::new();
    for c in &d.channels {
        for u in &c.unexcited {
            if !unexcited.iter().any(|(id, _)| *id == u.effect) {
                unexcited.push((&u.effect, &u.reason));
            }
        }
        for f in &c.failing {
            if !failing.contains(&f.as_str()) {
                failing.push(f);
            }
        }
    }
    let is_ai = |id: &str| DtgTerm::ANISOINERTIA.iter().any(|t| t.id() == id);
    let ai: Vec<&str> = unexcited
        .iter()
        .map(|(id, _)| *id)
        .filter(|id| is_ai(id))
        .collect();
    if !ai.is_empty() {
        out.push(format!(
            "{}: anisoinertia drifts (IEEE Std 813), proportional to products of the angular rates about the gyro's axes; a record whose rate varies by more than {ANISOINERTIA_MIN_RATE_DEG_S} deg/s rms (a rate table, a flight) excites them, a vibration table does not",
            ai.join(", ")
        ));
    }
    // Any other candidate not ranked, grouped by why.
    let mut others: Vec<(&str, Vec<&str>)> = Vec::new();
    for (id, reason) in unexcited.iter().filter(|(id, _)| !is_ai(id)) {
        match others.iter_mut().find(|(r, _)| r == reason) {
            Some((_, ids)) => ids.push(id),
            None => others.push((reason, vec![id])),
        }
    }
    for (reason, ids) in others {
        out.push(format!("{}: not ranked: {reason}", ids.join(", ")));
    }
    out.extend(failing.iter().map(|name| test_meaning(name)));
    let negative: Vec<String> = d
        .channels
        .iter()
        .filter(|c| c.compare.val_fit_percent < 0.0)
        .map(|c| c.channel.to_string())
        .collect();
    let negative: Vec<&str> = negative.iter().map(String::as_str).collect();
    out.extend(negative_fit(&negative));
    let printed = |word: &str| {
        d.channels
            .iter()
            .any(|c| c.findings.iter().any(|f| f.contains(word)))
    };
    for (word, meaning) in [
        (
            "cross-fitted",
            "cross-fitted residual: every row's residual from a model that did not see it (on the validation rows the model's; on the training rows its mirror's, fitted on the validation rows)",
        ),
        (
            "|r|",
            "|r|: the size of the correlation of two candidates' columns on that record (1.00: one is the other times a constant, the record cannot tell them apart)",
        ),
        (
            "σ)",
            "(Nσ): how far apart the residual's means over the axis's range lie, in standard errors",
        ),
        (
            "white floor",
            "white floor: the power a white residual of the same rms would have in the band, after the pre-filter",
        ),
    ] {
        if printed(word) {
            out.push(meaning.to_string());
        }
    }
    out
}

/// A correlation test's name (`billings_voon_u2_e:ax`) in words.
fn test_meaning(name: &str) -> String {
    let (test, input) = name.split_once(':').unwrap_or((name, ""));
    let what = match test {
        "whiteness" => {
            "the residual is correlated with itself beyond the model's window: something slow is left".to_string()
        }
        "independence" => format!(
            "the residual is correlated with {input} at some lag: something linear in {input} is left"
        ),
        "billings_voon_e_eu" => format!(
            "Billings–Voon test, the residual against the residual × {input}: a product of the error and {input} is left"
        ),
        "billings_voon_u2_e" => format!(
            "Billings–Voon test, the residual against {input}²: an even function of {input} (a g² term) is left"
        ),
        "billings_voon_u2_e2" => format!(
            "Billings–Voon test, the residual's square against {input}²: the error's size follows {input}'s level"
        ),
        _ => return format!("{name}: a correlation test of the residual"),
    };
    format!("{name}: {what}")
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

    #[test]
    fn every_test_the_diagnosis_names_is_said_in_words() {
        for kind in [
            dtg_vib::residuals::CorrelationKind::Whiteness,
            dtg_vib::residuals::CorrelationKind::Independence,
            dtg_vib::residuals::CorrelationKind::ResidualTimesInput,
            dtg_vib::residuals::CorrelationKind::SquaredInput,
            dtg_vib::residuals::CorrelationKind::SquaredInputSquaredResidual,
        ] {
            let name = format!("{}:az", kind.name());
            let line = test_meaning(&name);
            assert!(
                !line.contains("a correlation test of the residual"),
                "{line}"
            );
        }
        assert_eq!(
            test_meaning("billings_voon_u2_e:ax"),
            "billings_voon_u2_e:ax: Billings–Voon test, the residual against ax²: an even function of ax (a g² term) is left"
        );
    }
}
