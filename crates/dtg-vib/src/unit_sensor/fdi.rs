//! Parity fault detection and isolation over a record
//! ([`nav_sensors::fdi::ParityFdi`], one test per sample): how many
//! samples alarmed at the stated false-alarm probability, and to which
//! channel each alarm was isolated. The threshold needs the gyros' white
//! noise σ per sample; given none, it is read from the record itself, as
//! the spread of the parity vector's sample-to-sample differences (a
//! constant or slow fault does not enter them; vibration above the
//! sample rate's reach would, and raises σ).

use nav_sensors::fdi::{FdiError, FdiOutcome, ParityFdi};
use nav_sensors::unit::Unit;
use serde::Serialize;

/// The false-alarm probability per test that `residues` states by
/// default; the library's measured rate at it on clean simulated records
/// (nav-sensors test `fdi_false_alarm`): tetra 1.02e-3 and 9.8e-4,
/// dual-triad 1.02e-3, paper 8.4e-4.
pub const DEFAULT_FALSE_ALARM: f64 = 1e-3;

/// Where σ came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SigmaSource {
    /// Given (`--fdi-sigma`).
    Given,
    /// Read from the record (robust spread of the parity differences).
    Estimated,
}

/// What the tests over a record's samples found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FdiSummary {
    /// Samples tested (one test each).
    pub tests: usize,
    /// Samples whose parity vector exceeded the threshold.
    pub alarms: usize,
    /// `alarms / tests`.
    pub alarm_share: f64,
    /// Per channel, the alarms isolated to it (`{}` for four gyros,
    /// which detect but cannot isolate).
    pub isolated: std::collections::BTreeMap<String, usize>,
    /// Alarms no single channel explains best (four gyros: every one;
    /// channels sharing an input axis: theirs).
    pub detected_not_isolated: usize,
    /// The channel most alarms were isolated to, if any was.
    pub most_isolated: Option<String>,
}

/// The test as stated: its false-alarm probability, σ and threshold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FdiSetting {
    /// False-alarm probability per test under white noise of σ.
    pub false_alarm_probability: f64,
    /// The gyros' white noise per sample, deg/h.
    pub sigma_deg_h: f64,
    /// Where σ came from.
    pub sigma_source: SigmaSource,
    /// The threshold on ‖p‖, deg/h.
    pub threshold_deg_h: f64,
    /// Whether the unit can isolate (five gyros or more).
    pub isolation_possible: bool,
}

/// σ per sample from parity series (one per residue, equal lengths): the
/// median absolute sample-to-sample difference over all of them, as a
/// Gaussian's σ (÷ 0.6745), over √2 (a difference of two samples).
///
/// ```
/// let p = vec![(0..1000).map(|i| if i % 2 == 0 { 1.0 } else { -1.0 }).collect::<Vec<f64>>()];
/// let s = dtg_vib::unit_sensor::fdi::sigma_from_differences(&p);
/// assert!((s - 2.0 / 0.6745 / 2f64.sqrt()).abs() < 1e-9);
/// ```
pub fn sigma_from_differences(parity: &[Vec<f64>]) -> f64 {
    let mut d: Vec<f64> = parity
        .iter()
        .flat_map(|p| p.windows(2).map(|w| (w[1] - w[0]).abs()))
        .collect();
    if d.is_empty() {
        return 0.0;
    }
    d.sort_by(f64::total_cmp);
    let median = if d.len() % 2 == 1 {
        d[d.len() / 2]
    } else {
        0.5 * (d[d.len() / 2 - 1] + d[d.len() / 2])
    };
    median / 0.6745 / std::f64::consts::SQRT_2
}

/// The test for `unit` at false-alarm probability `p_fa`, with σ given or
/// read from the gyro series `gyros` (per channel, deg/h, equal lengths)
/// through their parity vectors V·m: the threshold is on ‖V·m‖, so σ is
/// read on the same scale whatever the unit names as its residues (a named
/// residue such as the paper's K0 = x0 − x1 has √2 times a gyro's noise).
pub fn setting(
    unit: &Unit,
    sigma: Option<f64>,
    p_fa: f64,
    gyros: &[Vec<f64>],
) -> Result<(ParityFdi, FdiSetting), FdiError> {
    let (sigma, source) = match sigma {
        Some(s) => (s, SigmaSource::Given),
        None => (
            sigma_from_differences(&parity_vectors(unit, gyros)),
            SigmaSource::Estimated,
        ),
    };
    let fdi = ParityFdi::for_false_alarm(unit, sigma, p_fa)?;
    let n = unit.gyros().len();
    Ok((
        fdi.clone(),
        FdiSetting {
            false_alarm_probability: p_fa,
            sigma_deg_h: sigma,
            sigma_source: source,
            threshold_deg_h: fdi.threshold(),
            isolation_possible: (0..n).any(|k| fdi.can_isolate(k)),
        },
    ))
}

/// V·m per sample of gyro series (per channel, equal lengths), per row of V.
pub fn parity_vectors(unit: &Unit, gyros: &[Vec<f64>]) -> Vec<Vec<f64>> {
    super::applied::per_sample(gyros, unit.parity_matrix().nrows(), |row| {
        unit.parity_vector(row)
    })
}

/// Runs `fdi` on every sample of the gyro series `gyros` (per channel,
/// deg/h, equal lengths).
pub fn run(unit: &Unit, fdi: &ParityFdi, gyros: &[Vec<f64>]) -> FdiSummary {
    let names = unit.gyro_names();
    let tests = gyros.first().map_or(0, Vec::len);
    let mut counts = vec![0usize; names.len()];
    let (mut alarms, mut undecided) = (0, 0);
    let mut row = vec![0.0; gyros.len()];
    for i in 0..tests {
        for (r, g) in row.iter_mut().zip(gyros) {
            *r = g[i];
        }
        match fdi.check(&row) {
            FdiOutcome::Healthy => {}
            FdiOutcome::Detected { .. } => {
                alarms += 1;
                undecided += 1;
            }
            FdiOutcome::Isolated { channel, .. } => {
                alarms += 1;
                counts[channel] += 1;
            }
        }
    }
    let most = counts
        .iter()
        .enumerate()
        .filter(|(_, c)| **c > 0)
        .max_by_key(|(_, c)| **c)
        .map(|(k, _)| names[k].to_string());
    FdiSummary {
        tests,
        alarms,
        alarm_share: if tests == 0 {
            0.0
        } else {
            alarms as f64 / tests as f64
        },
        isolated: names
            .iter()
            .zip(&counts)
            .filter(|(_, c)| **c > 0)
            .map(|(n, c)| (n.to_string(), *c))
            .collect(),
        detected_not_isolated: undecided,
        most_isolated: most,
    }
}

/// The summary in one line: alarms at the stated rate and where they were
/// isolated.
pub fn line(what: &str, s: &FdiSummary, setting: &FdiSetting) -> String {
    let expected = setting.false_alarm_probability * s.tests as f64;
    let isolation = if !setting.isolation_possible {
        "four gyros detect but cannot isolate".to_string()
    } else if s.alarms == 0 {
        "nothing to isolate".to_string()
    } else {
        let per: Vec<String> = s.isolated.iter().map(|(n, c)| format!("{n} {c}")).collect();
        format!(
            "isolated to {}{}",
            s.most_isolated.as_deref().unwrap_or("no channel"),
            match (per.len(), s.detected_not_isolated) {
                (0 | 1, 0) => String::new(),
                (_, u) => format!(" (per channel: {}; not isolated: {u})", per.join(", ")),
            }
        )
    };
    format!(
        "fault detection, {what}: {} of {} samples alarmed ({:.2e}; {:.1} expected from noise alone at the stated false-alarm rate {:.0e}); {isolation}",
        s.alarms, s.tests, s.alarm_share, expected, setting.false_alarm_probability
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_on_one_gyro_of_five_is_isolated_to_it() {
        // dual-triad: six gyros, gx2 isolable; white noise of 0.1 deg/h.
        let unit = Unit::builtin("dual-triad").unwrap();
        let n = 2000;
        let mut seed = 12345u64;
        let mut noise = || {
            // Two uniforms summed twelve times: close enough to Gaussian here.
            let mut s = 0.0;
            for _ in 0..12 {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                s += (seed >> 11) as f64 / (1u64 << 53) as f64;
            }
            0.1 * (s - 6.0)
        };
        let mut gyros: Vec<Vec<f64>> = (0..6).map(|_| (0..n).map(|_| noise()).collect()).collect();
        for v in &mut gyros[3][n / 2..] {
            *v += 3.0;
        }
        let (fdi, set) = setting(&unit, None, 1e-3, &gyros).unwrap();
        assert!((set.sigma_deg_h - 0.1).abs() < 0.02, "{set:?}");
        let s = run(&unit, &fdi, &gyros);
        assert!(s.alarms >= n / 2 - 10, "{s:?}");
        assert_eq!(s.most_isolated.as_deref(), Some("gx2"), "{s:?}");
        let text = line("as logged", &s, &set);
        assert!(text.contains("isolated to gx2"), "{text}");
    }

    #[test]
    fn a_triad_has_no_test() {
        let unit = Unit::builtin("triad").unwrap();
        let e = setting(&unit, Some(0.1), 1e-3, &[]).unwrap_err();
        assert!(
            e.to_string()
                .contains("fault detection needs at least 4 gyros")
        );
    }

    #[test]
    fn the_paper_units_parity_vectors_are_orthonormal_combinations() {
        // K0 = X − X1 has twice a gyro's noise variance; V·m has one per row.
        let u = nav_sensors::unit::Unit::paper();
        let e = |k: usize| -> Vec<Vec<f64>> {
            (0..6).map(|j| vec![f64::from(u8::from(j == k))]).collect()
        };
        let total: f64 = (0..6)
            .map(|k| {
                super::parity_vectors(&u, &e(k))
                    .iter()
                    .map(|p| p[0] * p[0])
                    .sum::<f64>()
            })
            .sum();
        // trace(VᵀV) = rows of V = 6 − 3.
        assert!((total - 3.0).abs() < 1e-12, "{total}");
    }
}
