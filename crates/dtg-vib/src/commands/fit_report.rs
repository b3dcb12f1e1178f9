//! `fit --json`: a unit's model as one JSON object (the unit, each
//! channel's centres, scores and effect coefficients with their standard
//! errors and 95% intervals, the split, the input and smoother chosen);
//! `explain --json` holds one as its final fit.

use crate::unit_sensor::UnitSensor;
use crate::unit_sensor::frequency_response::{FamilyResponse, responses};

/// `fit --json`.
#[derive(serde::Serialize)]
pub struct FitReport {
    /// The unit's name.
    unit: String,
    channels: Vec<ChannelReport>,
    split: String,
    fit_seconds: f64,
    /// `records` with `--cv records`.
    #[serde(skip_serializing_if = "Option::is_none")]
    cv: Option<String>,
    /// The networks' input (`raw`, `statistics`).
    input: sysid::ModelInput,
    /// The prediction smoother's cut-off, Hz (null: none).
    smoother_hz: Option<f64>,
    /// What `--input auto` / `--smoother auto` chose among, with every
    /// candidate's validation rms and worst Allan-deviation ratio.
    #[serde(skip_serializing_if = "Option::is_none")]
    choice: Option<sysid::fit::ChoiceReport>,
}

/// One channel of [`FitReport`].
#[derive(serde::Serialize)]
struct ChannelReport {
    channel: String,
    effects: Vec<String>,
    // The key is a contract (issue 24 §5: code says centre, JSON keys stay).
    #[serde(rename = "n_centers")]
    n_centres: usize,
    train_rms: f64,
    val_rms: f64,
    val_rms_bias_only: f64,
    val_fit_percent: f64,
    width: f64,
    bias: f64,
    effect_coefficients: std::collections::BTreeMap<String, CoefficientReport>,
    /// Validation rms per record, with several records.
    #[serde(skip_serializing_if = "Option::is_none")]
    records: Option<Vec<sysid::fit::RecordScore>>,
    /// The frequency response of each family of two or more FIR taps
    /// (delay, gain and phase per band, with 95% intervals).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    frequency_response: Vec<FamilyResponse>,
}

/// One effect coefficient of [`ChannelReport`].
#[derive(serde::Serialize)]
struct CoefficientReport {
    value: f64,
    unit: String,
    /// Absent for a model file that predates standard errors.
    #[serde(skip_serializing_if = "Option::is_none")]
    se: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ci95: Option<[f64; 2]>,
}

impl FitReport {
    /// The report of a unit's model, fitted in `fit_seconds`.
    pub fn of_model(model: &sysid::Model<UnitSensor>, fit_seconds: f64) -> Self {
        let split = match model.validated_on() {
            Some(name) => format!("by record (validated on {name})"),
            None => model.split().to_string(),
        };
        let mut r = Self::of_channels(model.channels(), split, fit_seconds).with_choice(model);
        r.unit = model.sensor().unit.name().to_string();
        for (report, c) in r.channels.iter_mut().zip(model.channels()) {
            // Without the covariance the text output says why; the JSON
            // holds no response.
            report.frequency_response =
                responses(c.effects(), c.coefficients(), model.dt_s()).unwrap_or_default();
        }
        r
    }

    /// The model's input, smoother and the fit's choice among candidates.
    pub fn with_choice<S: sysid::Sensor>(mut self, model: &sysid::Model<S>) -> Self {
        self.input = model.preprocess().input;
        self.smoother_hz = model.preprocess().smoother.map(|s| s.cutoff_hz);
        self.choice = model.choice().cloned();
        self
    }

    /// Each channel's validation rms per record (`per`, in channel order),
    /// and `records` for `--cv records`.
    pub fn set_records(&mut self, per: &[Vec<sysid::fit::RecordScore>], cv: Option<String>) {
        for (c, r) in self.channels.iter_mut().zip(per) {
            c.records = Some(r.clone());
        }
        self.cv = cv;
    }

    /// The report of any sensor's channel models.
    fn of_channels<C: Clone + std::fmt::Display, E: sysid::Effect>(
        channels: &[sysid::ChannelModel<C, E>],
        split: String,
        fit_seconds: f64,
    ) -> Self {
        let channels = channels
            .iter()
            .map(|c| {
                let s = c.scores();
                let effect_coefficients = c
                    .effects()
                    .iter()
                    .zip(c.effect_coefficients())
                    .enumerate()
                    .map(|(j, (e, v))| {
                        let k = c.coefficients().map(|k| &k[j]);
                        (
                            e.id(),
                            CoefficientReport {
                                value: v,
                                unit: e.unit(),
                                se: k.map(|k| k.se),
                                ci95: k.map(|k| k.ci95),
                            },
                        )
                    })
                    .collect();
                ChannelReport {
                    channel: c.channel().to_string(),
                    effects: c.effects().iter().map(|e| e.id()).collect(),
                    n_centres: c.n_centres(),
                    train_rms: s.train_rms,
                    val_rms: s.val_rms,
                    val_rms_bias_only: s.val_rms_bias_only,
                    val_fit_percent: s.val_fit_percent,
                    width: c.width(),
                    bias: c.bias(),
                    effect_coefficients,
                    records: None,
                    frequency_response: Vec::new(),
                }
            })
            .collect();
        Self {
            unit: String::new(),
            channels,
            split,
            fit_seconds,
            cv: None,
            input: sysid::ModelInput::default(),
            smoother_hz: None,
            choice: None,
        }
    }
}
