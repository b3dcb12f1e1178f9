//! A channel's frequency response per tap family: the FIR taps of one
//! stimulus (`sf@0..4`: the rate about the input axis; `acc:a2y@0..5`: one
//! accelerometer's specific force) read together as a filter, with the
//! gain and phase of its mean response over each of four bands from 0 Hz
//! to the Nyquist frequency, and, for the rate about the input axis, the
//! gyro's delay (the phase delay of its whole response, 1 + the error
//! taps, over the lowest band: its low-frequency delay). Every figure has its 95%
//! interval from the fit's joint covariance of the taps
//! ([`sysid::inference::derived`]).
//!
//! In parity a figure is the channel's as the parity residues see it: a
//! delay of one gyro among k along an axis shows as (1 − 1/k) of it on
//! that gyro (its output less the unit's least-squares rate).

use super::dynamic::{Dynamic, Stimulus};
use super::effect::UnitEffect;
use crate::numfmt::fmt;
use serde::Serialize;
use sysid::inference::Coefficient;
use sysid::inference::derived::{self, Derived, DerivedError};

/// Bands the Nyquist range is split into.
pub const BANDS: usize = 4;

/// The nominal response the rate taps are errors of: 1 in ppm.
const UNITY_PPM: f64 = 1e6;

/// One band's response of a tap family.
#[derive(Debug, Clone, Serialize)]
pub struct BandResponse {
    /// The band, Hz.
    pub band_hz: [f64; 2],
    /// The magnitude of the mean response over the band, in the family's
    /// unit; its interval is the range over the 2-D 95% region of the
    /// response's real and imaginary parts (0 at its low end when zero is
    /// inside).
    pub gain: Coefficient,
    /// Its phase, degrees (delta method); absent where the gain's interval
    /// reaches 0 and the phase is undetermined.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phase_deg: Option<Coefficient>,
}

/// The frequency response of one channel's tap family.
#[derive(Debug, Clone, Serialize)]
pub struct FamilyResponse {
    /// The family's id without a lag: `sf`, `ma_y`, `acc:a2y`.
    pub family: String,
    /// Its taps' lags, samples.
    pub lags: Vec<usize>,
    /// The gains' unit (the taps').
    pub unit: String,
    /// The gyro's delay from the rate taps about its input axis, ms.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub delay_ms: Option<Coefficient>,
    /// Gain and phase per band.
    pub bands: Vec<BandResponse>,
}

/// The responses of every family of two or more taps among a channel's
/// `effects`, with `coefs` their fitted coefficients (with the joint
/// covariance) at the sampling interval `dt_s`; none when there is no such
/// family.
///
/// # Errors
/// Why a channel with a family has no response: the fit kept no joint
/// covariance (a model written before it did), or no interval.
pub fn responses(
    effects: &[UnitEffect],
    coefs: Option<&[Coefficient]>,
    dt_s: f64,
) -> Result<Vec<FamilyResponse>, DerivedError> {
    let mut families: Vec<(Stimulus, Vec<(usize, usize)>)> = Vec::new();
    for (i, e) in effects.iter().enumerate() {
        let UnitEffect::Dynamic(Dynamic { stimulus, lag }) = e else {
            continue;
        };
        if *stimulus == Stimulus::InputRateDelay {
            continue;
        }
        match families.iter_mut().find(|(s, _)| s == stimulus) {
            Some((_, taps)) => taps.push((i, *lag)),
            None => families.push((stimulus.clone(), vec![(i, *lag)])),
        }
    }
    families.retain(|(_, taps)| taps.len() >= 2);
    if families.is_empty() {
        return Ok(Vec::new());
    }
    let d = Derived::new(coefs.unwrap_or_default())?;
    Ok(families
        .into_iter()
        .map(|(stimulus, taps)| family(&d, stimulus, &taps, dt_s))
        .collect())
}

/// One family's response.
fn family(
    d: &Derived<'_>,
    stimulus: Stimulus,
    taps: &[(usize, usize)],
    dt_s: f64,
) -> FamilyResponse {
    let id = Dynamic { stimulus, lag: 0 };
    let unit = id.stimulus.tap_unit();
    let edges = derived::bands(dt_s, BANDS);
    let bands = edges
        .iter()
        .copied()
        .map(|band| {
            let [re, im] = derived::band_weights(taps, dt_s, band);
            let (gain, phase_deg) = d.magnitude(&re, &im, unit);
            BandResponse {
                band_hz: band,
                gain,
                phase_deg,
            }
        })
        .collect();
    // No delay where the phase has passed ±90° (see `phase_delay`).
    let delay_ms = (id.stimulus == Stimulus::InputRate)
        .then(|| derived::phase_delay(d, taps, dt_s, UNITY_PPM, edges[0]))
        .flatten();
    FamilyResponse {
        family: id.to_string(),
        lags: taps.iter().map(|t| t.1).collect(),
        unit: unit.to_string(),
        delay_ms,
        bands,
    }
}

/// One line per family: `  g1x acc:a2y (deg/h/g): 0–15 Hz 0.8 (0.2 to
/// 1.4), …`, the delay first where there is one.
pub fn lines(channel: &str, families: &[FamilyResponse]) -> Vec<String> {
    let ci = |c: &Coefficient| {
        format!(
            "{} ({} to {})",
            fmt(c.value),
            fmt(c.ci95[0]),
            fmt(c.ci95[1])
        )
    };
    families
        .iter()
        .map(|f| {
            let delay = f
                .delay_ms
                .as_ref()
                .map(|t| format!("delay {} ms; ", ci(t)))
                .unwrap_or_default();
            let bands: Vec<String> = f
                .bands
                .iter()
                .map(|b| {
                    let [lo, hi] = b
                        .band_hz
                        .map(|f| crate::numfmt::short((f * 10.0).round() / 10.0));
                    format!("{lo}–{hi} Hz {}", ci(&b.gain))
                })
                .collect();
            format!(
                "{channel:>7}  {} taps @{}..{}: {delay}gain per band, {}: {}",
                f.family,
                f.lags.iter().min().unwrap_or(&0),
                f.lags.iter().max().unwrap_or(&0),
                f.unit,
                bands.join(", ")
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two taps of each of three stimuli, independent, se 0.1.
    fn families(with_covariance: bool) -> (Vec<UnitEffect>, Vec<Coefficient>) {
        let ids = ["ma_x", "ma_x@1", "sf", "sf@1", "acc:ax", "acc:ax@1"];
        let effects: Vec<UnitEffect> = ids.iter().map(|i| i.parse().unwrap()).collect();
        let n = ids.len();
        let coefs = (0..n)
            .map(|i| {
                let c = Coefficient::new(1.0, 0.1, [0.8, 1.2], "u");
                match with_covariance {
                    true => c.with_covariance((0..n).map(|j| f64::from(i == j) * 0.01).collect()),
                    false => c,
                }
            })
            .collect();
        (effects, coefs)
    }

    #[test]
    fn a_family_gain_is_in_the_unit_of_its_taps() {
        let (effects, coefs) = families(true);
        let r = responses(&effects, Some(&coefs), 0.01).unwrap();
        let units: Vec<(&str, &str)> = r
            .iter()
            .map(|f| (f.family.as_str(), f.unit.as_str()))
            .collect();
        assert_eq!(
            units,
            [("ma_x", "ppm"), ("sf", "ppm"), ("acc:ax", "deg/h/g")]
        );
        // The unit the model gives each tap after the first (ma_x's lag 0
        // is a misalignment, µrad: the same 10⁻⁶ scale).
        for (f, e) in r.iter().zip([&effects[1], &effects[3], &effects[5]]) {
            assert_eq!(f.unit, sysid::Effect::unit(e), "{}", f.family);
        }
        assert_eq!(sysid::Effect::unit(&effects[0]), "µrad");
    }

    #[test]
    fn a_model_without_the_covariance_says_why_it_has_no_response() {
        let (effects, coefs) = families(false);
        let e = responses(&effects, Some(&coefs), 0.01).unwrap_err();
        assert_eq!(e, DerivedError::NoCovariance);
        // No family of two taps: nothing to say, covariance or not.
        assert!(
            responses(&effects[..1], Some(&coefs[..1]), 0.01)
                .unwrap()
                .is_empty()
        );
    }
}
