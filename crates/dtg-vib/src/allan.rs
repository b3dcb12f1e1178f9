//! Allan deviation of a unit's gyro channels and parity residues on one
//! record (a log's segment between time gaps: an average never spans a
//! gap), before and after a model's compensation, with the IEEE Std 952
//! noise terms read from each curve ([`nav_sensors::noise`] does the
//! computing).
//!
//! The series are the ones `compensate` works on, unfiltered: **before** is
//! the calibrated output with the model's rate reference removed, **after**
//! the series `compensate` writes (calibrated output minus predicted error),
//! both from the first sample with a full window on, so both curves share
//! their τ. (`compensate` keeps the rate reference in its output; a constant
//! does not change an Allan deviation.) Without a model, before is the
//! record as given, every sample. The residues are the unit's (the paper's
//! K0 … K5, another unit's P0, …; none for three gyros) of the same series.

use crate::error::DtgVibError;
use crate::unit_sensor::{Applied, UnitModel, residues_of};
use nav_sensors::noise::{AllanCurve, NoiseTerm, NoiseTerms};
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use serde::Serialize;
use serde_json::Value;

/// One series' curves and terms, before and (with a model) after.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesAllan {
    /// A gyro's name (`X` … `Z1`, `g1`, …) or a residue's (`K0` … `K5`, `P0`, …).
    pub name: String,
    /// Curve before compensation (deg/h against s).
    pub before: AllanCurve,
    /// Noise terms read on `before`.
    pub terms_before: NoiseTerms,
    /// Curve after compensation, with a model.
    pub after: Option<AllanCurve>,
    /// Noise terms read on `after`.
    pub terms_after: Option<NoiseTerms>,
}

/// The Allan analysis of a record.
#[derive(Debug, Clone, PartialEq)]
pub struct AllanAnalysis {
    /// Sample interval τ₀, s.
    pub tau0_s: f64,
    /// First record sample used (0-based; the model's first full window).
    pub first_sample: usize,
    /// Samples used.
    pub samples: usize,
    /// Two-sided confidence level of every interval.
    pub confidence: f64,
    /// Whether a model compensated the record (then `after` is present).
    pub compensated: bool,
    /// Gyro channels, in the unit's order.
    pub channels: Vec<SeriesAllan>,
    /// Parity residues of the same series (the paper's K0 … K5 of eq. 6, a
    /// unit's P0, …; none for a unit of three gyros).
    pub residues: Vec<SeriesAllan>,
    /// What the residues are, in the residue figure's title: "eq. 6" for
    /// the paper's K0 … K5, "V·m" for a unit's.
    pub residue_source: &'static str,
}

/// A named series before and (with a model) after, deg/h, for
/// [`AllanAnalysis::of_series`].
pub type NamedSeries = (String, Vec<f64>, Option<Vec<f64>>);

fn analyse_one(
    name: String,
    before: &[f64],
    after: Option<&[f64]>,
    tau0_s: f64,
    confidence: f64,
) -> Result<SeriesAllan, DtgVibError> {
    let before = AllanCurve::octaves(before, tau0_s, confidence)?;
    let after = after
        .map(|a| AllanCurve::octaves(a, tau0_s, confidence))
        .transpose()?;
    Ok(SeriesAllan {
        name,
        terms_before: NoiseTerms::fit(&before),
        terms_after: after.as_ref().map(NoiseTerms::fit),
        before,
        after,
    })
}

impl AllanAnalysis {
    /// Analyses one record of `unit` (a segment between time gaps),
    /// compensated by `model` (of that unit) if given, with intervals at
    /// `confidence` (e.g. 0.683).
    ///
    /// ```
    /// use dtg_vib::allan::AllanAnalysis;
    /// use nav_sensors::sim::{simulate_unit, Scenario};
    /// let unit = nav_sensors::unit::Unit::paper();
    /// let sim = simulate_unit(&unit, &Scenario { duration_s: 10.0, ..Scenario::default() }).unwrap();
    /// let a = AllanAnalysis::new(&unit, None, &sim.record, 0.683).unwrap();
    /// assert_eq!(a.channels.len(), 6);
    /// assert_eq!(a.residues[0].name, "K0");
    /// // 500 samples: τ = 0.02 s to 0.64 s (m up to a tenth of the record).
    /// assert_eq!(a.channels[0].before.points.last().unwrap().tau_s, 0.64);
    /// ```
    pub fn new(
        unit: &Unit,
        model: Option<&UnitModel>,
        record: &Record,
        confidence: f64,
    ) -> Result<Self, DtgVibError> {
        let (before, after, first) = match model {
            None => (
                (0..unit.gyros().len())
                    .map(|k| record.gyro_at(k).to_vec())
                    .collect(),
                None,
                0,
            ),
            Some(m) => {
                let applied = Applied::unsplit(m, &[(String::new(), record)])?;
                let after = applied.compensated_gyros()?;
                let first = applied.prepared.first_sample();
                (applied.calibrated_gyros(), Some(after), first)
            }
        };
        let name = |k: usize| unit.gyro_names()[k].to_string();
        let res_before = residues_of(unit, &before);
        let res_after = after.as_ref().map(|a| residues_of(unit, a));
        let channels: Vec<NamedSeries> = before
            .into_iter()
            .enumerate()
            .map(|(k, b)| (name(k), b, after.as_ref().map(|a| a[k].clone())))
            .collect();
        let residues: Vec<NamedSeries> = res_before
            .into_iter()
            .enumerate()
            .map(|(k, b)| {
                let after = res_after.as_ref().map(|a| a[k].clone());
                (unit.residue_names()[k].clone(), b, after)
            })
            .collect();
        let mut a = Self::of_series(record.dt(), first, confidence, channels, residues)?;
        // The paper's residues are eq. 6's combinations; any other unit's the
        // rows of its parity matrix V.
        a.residue_source = if unit.has_paper_geometry() {
            "eq. 6"
        } else {
            "V·m"
        };
        Ok(a)
    }

    /// The analysis of any unit's series: `channels` and `residues`, each
    /// named with its curve before and (with a model) after, deg/h, sampled
    /// every `tau0_s` from record sample `first_sample` on.
    ///
    /// ```
    /// use dtg_vib::allan::AllanAnalysis;
    /// let y: Vec<f64> = (0..400).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
    /// let a = AllanAnalysis::of_series(0.02, 0, 0.683, vec![("g1".into(), y, None)], vec![]).unwrap();
    /// assert_eq!((a.channels[0].name.as_str(), a.residues.len()), ("g1", 0));
    /// assert!(!a.compensated);
    /// ```
    pub fn of_series(
        tau0_s: f64,
        first_sample: usize,
        confidence: f64,
        channels: Vec<NamedSeries>,
        residues: Vec<NamedSeries>,
    ) -> Result<Self, DtgVibError> {
        let samples = channels.first().map_or(0, |(_, b, _)| b.len());
        let compensated = channels.iter().any(|(_, _, a)| a.is_some());
        let analyse = |v: Vec<NamedSeries>| {
            v.into_iter()
                .map(|(name, before, after)| {
                    analyse_one(name, &before, after.as_deref(), tau0_s, confidence)
                })
                .collect::<Result<Vec<_>, _>>()
        };
        Ok(Self {
            tau0_s,
            first_sample,
            samples,
            confidence,
            compensated,
            channels: analyse(channels)?,
            residues: analyse(residues)?,
            residue_source: "V·m",
        })
    }

    /// The JSON of `dtg-vib allan --json` (docs/formats.md).
    pub fn to_json(&self) -> Value {
        serde_json::to_value(self.report()).expect("plain data serialises")
    }

    /// The typed form of [`AllanAnalysis::to_json`].
    pub fn report(&self) -> AllanReport<'_> {
        AllanReport {
            channels: self.channels.iter().map(|s| s.report(true)).collect(),
            residues: self.residues.iter().map(|s| s.report(false)).collect(),
            tau0_s: self.tau0_s,
            first_sample: self.first_sample,
            samples: self.samples,
            confidence: self.confidence,
            units: Units {
                tau_s: "s",
                adev: "deg/h",
                arw: "deg/√h",
                bias_instability: "deg/h",
                rrw: "deg/h/√h",
            },
        }
    }
}

impl SeriesAllan {
    fn report(&self, is_channel: bool) -> SeriesReport<'_> {
        let pick = |f: fn(&NoiseTerms) -> &NoiseTerm| BeforeAfter {
            before: f(&self.terms_before).estimate().map(|e| e.value),
            after: self
                .terms_after
                .as_ref()
                .map(|t| f(t).estimate().map(|e| e.value)),
        };
        SeriesReport {
            channel: is_channel.then_some(self.name.as_str()),
            residue: (!is_channel).then_some(self.name.as_str()),
            tau_s: self.before.tau_s(),
            adev_before: self.before.adev(),
            adev_after: self.after.as_ref().map(AllanCurve::adev),
            arw_deg_per_sqrt_h: pick(|t| &t.arw),
            bias_instability_deg_per_h: pick(|t| &t.bias_instability),
            rrw_deg_per_h_per_sqrt_h: pick(|t| &t.rrw),
            adev_before_detail: CurveDetail::of(&self.before),
            adev_after_detail: self.after.as_ref().map(CurveDetail::of),
            noise_terms: Terms {
                before: &self.terms_before,
                after: self.terms_after.as_ref(),
            },
        }
    }
}

/// `dtg-vib allan --json`.
#[derive(Debug, Serialize)]
pub struct AllanReport<'a> {
    /// Gyro channels.
    pub channels: Vec<SeriesReport<'a>>,
    /// Parity residues.
    pub residues: Vec<SeriesReport<'a>>,
    /// Sample interval τ₀, s.
    pub tau0_s: f64,
    /// First record sample used.
    pub first_sample: usize,
    /// Samples used.
    pub samples: usize,
    /// Two-sided confidence level of every interval.
    pub confidence: f64,
    /// Units of the numbers.
    pub units: Units,
}

/// The units `allan --json` states.
#[derive(Debug, Serialize)]
pub struct Units {
    tau_s: &'static str,
    adev: &'static str,
    arw: &'static str,
    bias_instability: &'static str,
    rrw: &'static str,
}

/// One series of `allan --json`: `channel` or `residue` names it.
#[derive(Debug, Serialize)]
pub struct SeriesReport<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    channel: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    residue: Option<&'a str>,
    tau_s: Vec<f64>,
    adev_before: Vec<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    adev_after: Option<Vec<f64>>,
    arw_deg_per_sqrt_h: BeforeAfter<Option<f64>>,
    bias_instability_deg_per_h: BeforeAfter<Option<f64>>,
    rrw_deg_per_h_per_sqrt_h: BeforeAfter<Option<f64>>,
    adev_before_detail: CurveDetail,
    #[serde(skip_serializing_if = "Option::is_none")]
    adev_after_detail: Option<CurveDetail>,
    noise_terms: Terms<'a>,
}

/// A term before and (with a model) after; null where unresolved.
#[derive(Debug, Serialize)]
struct BeforeAfter<T> {
    before: T,
    #[serde(skip_serializing_if = "Option::is_none")]
    after: Option<T>,
}

/// The noise terms read on the curves before and after.
#[derive(Debug, Serialize)]
struct Terms<'a> {
    before: &'a NoiseTerms,
    #[serde(skip_serializing_if = "Option::is_none")]
    after: Option<&'a NoiseTerms>,
}

/// Per-τ confidence intervals, degrees of freedom and noise types.
#[derive(Debug, Serialize)]
struct CurveDetail {
    low: Vec<f64>,
    high: Vec<f64>,
    edf: Vec<f64>,
    noise: Vec<nav_sensors::noise::PowerLaw>,
    noise_identified: Vec<bool>,
}

impl CurveDetail {
    fn of(c: &AllanCurve) -> Self {
        Self {
            low: c.points.iter().map(|p| p.low).collect(),
            high: c.points.iter().map(|p| p.high).collect(),
            edf: c.points.iter().map(|p| p.edf).collect(),
            noise: c.points.iter().map(|p| p.noise).collect(),
            noise_identified: c.points.iter().map(|p| p.noise_identified).collect(),
        }
    }
}

/// A term for people: `value [low, high]`, or `< bound (not resolved)`.
///
/// ```
/// use nav_sensors::noise::NoiseTerm;
/// let t = NoiseTerm::Unresolved { reason: "short".into(), upper_bound: Some(0.0123456) };
/// assert_eq!(dtg_vib::allan::term_text(&t), "< 0.01235 (not resolved)");
/// ```
pub fn term_text(t: &NoiseTerm) -> String {
    use crate::numfmt::fmt;
    match t {
        NoiseTerm::Resolved(e) => format!("{} [{}, {}]", fmt(e.value), fmt(e.low), fmt(e.high)),
        NoiseTerm::Unresolved {
            upper_bound: Some(b),
            ..
        } => format!("< {} (not resolved)", fmt(*b)),
        NoiseTerm::Unresolved { .. } => "not resolved".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nav_sensors::sim::{Scenario, simulate_unit};

    #[test]
    fn json_has_the_contract_keys_and_no_after_without_a_model() {
        let unit = Unit::paper();
        let scenario = Scenario {
            duration_s: 4.0,
            ..Scenario::default()
        };
        let sim = simulate_unit(&unit, &scenario).unwrap();
        let j = AllanAnalysis::new(&unit, None, &sim.record, 0.683)
            .unwrap()
            .to_json();
        let ch = &j["channels"];
        assert_eq!(ch.as_array().unwrap().len(), 6);
        let x = &ch[0];
        assert_eq!(x["channel"], "X");
        let n = x["tau_s"].as_array().unwrap().len();
        assert_eq!(n, 5); // 200 samples: m = 1 … 16
        assert_eq!(x["adev_before"].as_array().unwrap().len(), n);
        assert!(x.get("adev_after").is_none());
        assert!(x["arw_deg_per_sqrt_h"].get("before").is_some());
        assert!(x["arw_deg_per_sqrt_h"].get("after").is_none());
        assert!(x["bias_instability_deg_per_h"].get("before").is_some());
        assert_eq!(j["residues"][5]["residue"], "K5");
    }
}
