//! The smallest sensor the loop can run: one channel `y` that reads a
//! slope times its input `u`, plus a nonlinear function of the recent
//! inputs (the network's part), plus noise. What the documentation's
//! examples and the crate's own tests fit; `examples/pressure_transducer.rs`
//! is a sensor with physics.

use crate::preprocess::Preprocess;
use crate::sensor::{Candidacy, Effect, OperatingStats, Sensor, SensorError, Separation, Wording};
use crate::signals::Signals;
use crate::window::WindowSpec;
use serde::{Deserialize, Serialize};

/// The one effect of [`Line`]: the slope on the input, id `u`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Slope;

impl std::fmt::Display for Slope {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("u")
    }
}

impl Effect for Slope {
    fn id(&self) -> String {
        "u".into()
    }
    fn unit(&self) -> String {
        "y/u".into()
    }
    fn description(&self) -> String {
        "sensitivity to the input".into()
    }
}

/// A one-channel sensor: output column `y`, input column `u`.
///
/// ```
/// use sysid::Sensor;
/// let s = sysid::example::Line;
/// assert_eq!(s.channels(), ["y"]);
/// assert_eq!(s.operating_signals(), ["u"]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line;

impl Line {
    /// Unfiltered windows of 5 samples of `u`.
    pub fn preprocess() -> Preprocess {
        Preprocess {
            filter: None,
            window: WindowSpec::new(vec!["u".into()], 5).expect("one signal, five samples"),
            ..Preprocess::default()
        }
    }
}

impl Sensor for Line {
    type Channel = String;
    type Effect = Slope;
    type Axis = String;

    fn channels(&self) -> Vec<String> {
        vec!["y".into()]
    }

    fn wording(&self) -> Wording {
        Wording {
            target_unit: "y".into(),
            operating_unit: "u".into(),
            spread: "swing".into(),
            operating_noun: "input".into(),
            regime_hint: "a term in the input may be missing".into(),
            slow_hint: "a drift".into(),
        }
    }

    fn calibrate(&self, raw: &Signals) -> Result<Signals, SensorError> {
        Ok(raw.clone())
    }

    fn targets(&self, calibrated: &Signals) -> Result<Vec<Vec<f64>>, SensorError> {
        let y = calibrated.column("y").ok_or("the record has no column y")?;
        Ok(vec![y.to_vec()])
    }

    fn operating_signals(&self) -> Vec<String> {
        vec!["u".into()]
    }

    fn operating_scale(&self) -> f64 {
        0.01
    }

    fn extra_columns(&self, record: &Signals) -> Vec<String> {
        let own = ["y", "u"];
        record
            .names()
            .into_iter()
            .filter(|n| !own.contains(n))
            .map(String::from)
            .collect()
    }

    fn candidates(&self, _: &Signals, _: &[usize], _: usize) -> Vec<Candidacy<Slope>> {
        vec![Candidacy::Excited(Slope)]
    }

    fn parse_effect(&self, _: usize, id: &str) -> Result<Slope, SensorError> {
        match id {
            "u" => Ok(Slope),
            other => Err(format!("unknown effect '{other}' (valid: u)").into()),
        }
    }

    fn regressors(
        &self,
        calibrated: &Signals,
        _: usize,
        effects: &[Slope],
    ) -> Result<Vec<Vec<f64>>, SensorError> {
        let u = calibrated.column("u").ok_or("the record has no column u")?;
        Ok(effects.iter().map(|_| u.to_vec()).collect())
    }

    fn separation(&self, _: usize, group: &[Slope], _: &[f64], _: &OperatingStats) -> Separation {
        Separation {
            effects: group.iter().map(Effect::id).collect(),
            combination: Vec::new(),
            axis: None,
            responses: vec![None; group.len()],
            advice: "one input: nothing separates them".into(),
        }
    }
}

/// A record of [`Line`]: `n` samples 0.02 s apart of an input that steps
/// and wiggles, an output of `slope·u + 0.5·sin(u₋₂)` and seeded noise of
/// 0.01.
///
/// ```
/// let r = sysid::example::line_record(100, 2.0, 7);
/// assert_eq!(r.len(), 100);
/// assert_eq!(r.names(), ["y", "u"]);
/// ```
pub fn line_record(n: usize, slope: f64, seed: u64) -> Signals {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut noise = move || {
        // xorshift64*: enough for an example's noise, and no dependency.
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.02).collect();
    let u: Vec<f64> = (0..n)
        .map(|i| ((i / 50) % 5) as f64 * 0.4 + 0.3 * (i as f64 * 0.37).sin() + 0.2 * noise())
        .collect();
    let y: Vec<f64> = (0..n)
        .map(|i| slope * u[i] + 0.5 * u[i.saturating_sub(2)].sin() + 0.02 * noise())
        .collect();
    Signals::new(t, vec![("y".into(), y), ("u".into(), u)]).expect("equal lengths")
}
