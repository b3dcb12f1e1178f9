//! The lot's summary, read from its folder alone: every unit's
//! coefficients with their intervals and its channels' rms after; per
//! channel and effect across the lot the median, the median absolute
//! deviation and who is out of family ([`super::family`]); who fails the
//! specification, naming the limit; who failed to run, and why; who has
//! not run yet. Its JSON (`DIR/summary.json`, `fleet summary --json`) is
//! documented in docs/formats.md.

use super::family::family;
use super::layout::{FAILED, Layout, LayoutError, MODEL, REPORT, TASK, read_json};
use super::task::Failure;
use crate::unit_sensor::UnitModel;
use serde::Serialize;
use std::collections::BTreeMap;

/// One coefficient of one unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectRow {
    /// The effect id.
    pub effect: String,
    /// The estimate.
    pub value: f64,
    /// Its standard error.
    pub se: f64,
    /// Its 95% interval.
    pub ci95: [f64; 2],
    /// Its unit (deg/h/g, …).
    pub unit: String,
}

/// One channel of one unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelRow {
    /// The gyro.
    pub channel: String,
    /// Validation rms after compensation, deg/h.
    pub rms_after_deg_h: f64,
    /// Its effects with their coefficients.
    pub effects: Vec<EffectRow>,
}

/// Where a unit stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Status {
    /// Its outputs are whole.
    #[serde(rename = "done")]
    Done,
    /// It failed (see `failed`).
    #[serde(rename = "failed")]
    Failed,
    /// No output yet.
    #[serde(rename = "not run")]
    NotRun,
}

/// One unit of the lot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UnitRow {
    /// Its id.
    pub id: String,
    /// `done`, `failed` or `not run`.
    pub status: Status,
    /// Its page, relative to the lot's folder (done units).
    pub report: Option<String>,
    /// Its model, relative to the lot's folder (done units).
    pub model: Option<String>,
    /// Its channels (done units).
    pub channels: Vec<ChannelRow>,
}

/// One unit's coefficient within its group.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Member {
    /// The unit's id.
    pub unit: String,
    /// The estimate.
    pub value: f64,
    /// Its 95% interval.
    pub ci95: [f64; 2],
    /// Its robust z (none when the group is not judged).
    pub z: Option<f64>,
}

/// One effect on one channel across the lot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Group {
    /// The gyro.
    pub channel: String,
    /// The effect id.
    pub effect: String,
    /// The coefficient's unit.
    pub unit: String,
    /// The lot's median.
    pub median: f64,
    /// The median absolute deviation about it (unscaled).
    pub mad: f64,
    /// The robust standard deviation, 1.4826 × mad.
    pub robust_sigma: f64,
    /// Whether out of family was judged (enough units, some spread).
    pub judged: bool,
    /// Every unit that has the effect.
    pub members: Vec<Member>,
}

/// A unit out of family.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutOfFamily {
    /// The unit's id.
    pub unit: String,
    /// The gyro.
    pub channel: String,
    /// The effect id.
    pub effect: String,
    /// Its coefficient.
    pub value: f64,
    /// Its 95% interval (which excludes the lot's median).
    pub ci95: [f64; 2],
    /// Its robust z.
    pub z: f64,
    /// The lot's median.
    pub median: f64,
    /// The coefficient's unit.
    pub coefficient_unit: String,
}

/// A unit beyond a limit of the specification.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FailingSpec {
    /// The unit's id.
    pub unit: String,
    /// The gyro.
    pub channel: String,
    /// The limit's key in `[spec]`: an effect id or `rms_after_deg_h`.
    pub limit_key: String,
    /// The unit's value (|coefficient| or rms after).
    pub value: f64,
    /// The limit.
    pub limit: f64,
    /// The value's unit.
    pub value_unit: String,
}

/// A unit that failed to run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FailedUnit {
    /// The unit's id.
    pub unit: String,
    /// Why, one line.
    pub reason: String,
}

/// The lot's summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// The lot's name.
    pub lot: String,
    /// The robust z beyond which a unit is out of family.
    pub threshold: f64,
    /// The fewest units an effect is judged over.
    pub min_units: usize,
    /// Every unit, in the manifest's order.
    pub units: Vec<UnitRow>,
    /// Per channel and effect across the lot.
    pub groups: Vec<Group>,
    /// Units out of family.
    pub out_of_family: Vec<OutOfFamily>,
    /// Units beyond a limit of the specification.
    pub failing_spec: Vec<FailingSpec>,
    /// Units that failed to run.
    pub failed: Vec<FailedUnit>,
    /// Units without output yet.
    pub not_run: Vec<String>,
}

/// Why a summary could not be made.
#[derive(Debug, thiserror::Error)]
pub enum SummaryError {
    /// The folder.
    #[error(transparent)]
    Layout(#[from] LayoutError),
    /// Its page.
    #[error("{0}")]
    Page(String),
}

/// The channels of a done unit's model.
fn channels(m: &UnitModel) -> Vec<ChannelRow> {
    m.inner()
        .channels()
        .iter()
        .map(|c| ChannelRow {
            channel: c.channel(),
            rms_after_deg_h: c.scores().val_rms,
            effects: c
                .effects()
                .iter()
                .zip(c.coefficients().unwrap_or(&[]))
                .map(|(e, k)| EffectRow {
                    effect: e.id(),
                    value: k.value,
                    se: k.se,
                    ci95: k.ci95,
                    unit: k.unit.clone(),
                })
                .collect(),
        })
        .collect()
}

/// A unit's row, and its failure if it has one.
fn unit_row(out: &Layout, id: &str) -> (UnitRow, Option<FailedUnit>) {
    let dir = out.unit(id);
    let rel = |f: &str| format!("units/{id}/{f}");
    let mut row = UnitRow {
        id: id.to_string(),
        status: Status::NotRun,
        report: None,
        model: None,
        channels: Vec::new(),
    };
    let failed = |reason: String| {
        Some(FailedUnit {
            unit: id.to_string(),
            reason,
        })
    };
    if dir.join(TASK).exists() {
        return match UnitModel::load(dir.join(MODEL)) {
            Ok(m) => {
                row.status = Status::Done;
                row.report = Some(rel(&format!("{REPORT}/index.html")));
                row.model = Some(rel(MODEL));
                row.channels = channels(&m);
                (row, None)
            }
            Err(e) => {
                row.status = Status::Failed;
                (row, failed(format!("its model: {e}")))
            }
        };
    }
    if dir.join(FAILED).exists() {
        row.status = Status::Failed;
        let reason = match read_json::<Failure>(&dir.join(FAILED)) {
            Ok(f) => f.reason,
            Err(e) => format!("unreadable failure record: {e}"),
        };
        return (row, failed(reason));
    }
    (row, None)
}

/// Groups of every (channel, effect) the done units have, and who is out of family.
fn groups(units: &[UnitRow], threshold: f64, min_units: usize) -> (Vec<Group>, Vec<OutOfFamily>) {
    let mut by: BTreeMap<(String, String), (String, Vec<Member>)> = BTreeMap::new();
    for u in units {
        for c in &u.channels {
            for e in &c.effects {
                let g = by
                    .entry((c.channel.clone(), e.effect.clone()))
                    .or_insert_with(|| (e.unit.clone(), Vec::new()));
                g.1.push(Member {
                    unit: u.id.clone(),
                    value: e.value,
                    ci95: e.ci95,
                    z: None,
                });
            }
        }
    }
    let mut out = Vec::new();
    let groups = by
        .into_iter()
        .map(|((channel, effect), (unit, mut members))| {
            let values: Vec<f64> = members.iter().map(|m| m.value).collect();
            let ci: Vec<[f64; 2]> = members.iter().map(|m| m.ci95).collect();
            let f = family(&values, &ci, threshold, min_units);
            if let Some(f) = &f {
                for (k, m) in members.iter_mut().enumerate() {
                    m.z = Some(f.z[k]);
                    if f.out[k] {
                        out.push(OutOfFamily {
                            unit: m.unit.clone(),
                            channel: channel.clone(),
                            effect: effect.clone(),
                            value: m.value,
                            ci95: m.ci95,
                            z: f.z[k],
                            median: f.median,
                            coefficient_unit: unit.clone(),
                        });
                    }
                }
            }
            Group {
                median: stats::median(&values),
                mad: stats::mad(&values),
                robust_sigma: stats::MAD_TO_SIGMA * stats::mad(&values),
                judged: f.is_some(),
                channel,
                effect,
                unit,
                members,
            }
        })
        .collect();
    (groups, out)
}

/// Units beyond a limit of `spec`.
fn failing_spec(units: &[UnitRow], spec: &super::manifest::Spec) -> Vec<FailingSpec> {
    let mut out = Vec::new();
    for u in units {
        for c in &u.channels {
            for e in &c.effects {
                if let Some(&limit) = spec.effects.get(&e.effect)
                    && e.value.abs() > limit
                {
                    out.push(FailingSpec {
                        unit: u.id.clone(),
                        channel: c.channel.clone(),
                        limit_key: e.effect.clone(),
                        value: e.value.abs(),
                        limit,
                        value_unit: e.unit.clone(),
                    });
                }
            }
            if let Some(limit) = spec.rms_after_deg_h
                && c.rms_after_deg_h > limit
            {
                out.push(FailingSpec {
                    unit: u.id.clone(),
                    channel: c.channel.clone(),
                    limit_key: "rms_after_deg_h".into(),
                    value: c.rms_after_deg_h,
                    limit,
                    value_unit: "deg/h".into(),
                });
            }
        }
    }
    out
}

/// The summary of the lot in `out`, judging out of family beyond robust
/// z `threshold` over at least `min_units` units.
pub fn summarise(out: &Layout, threshold: f64, min_units: usize) -> Result<Summary, SummaryError> {
    let lot = out.lot()?;
    let mut units = Vec::new();
    let mut failed = Vec::new();
    for id in &lot.ids {
        let (row, f) = unit_row(out, id);
        units.push(row);
        failed.extend(f);
    }
    let (groups, out_of_family) = groups(&units, threshold, min_units);
    let failing_spec = failing_spec(&units, &lot.spec);
    let not_run = units
        .iter()
        .filter(|u| u.status == Status::NotRun)
        .map(|u| u.id.clone())
        .collect();
    Ok(Summary {
        lot: lot.name,
        threshold,
        min_units,
        units,
        groups,
        out_of_family,
        failing_spec,
        failed,
        not_run,
    })
}
