//! The fade block of the onboard tables: the model's per-axis training
//! range and how its network part fades beyond it
//! (`sysid::operating::fade`), as the evaluator reads it
//! (`dtg_onboard::fade_floats` numbers after the channels; the vibration
//! shape's range at its end, flag `FLAG_FADE_SHAPE`, when the model has one).

use super::error::ExportError;
use crate::unit_sensor::model::UnitModel;
use sysid::operating::OperatingPoints;

/// The fade block of a model with a training range (`None` without one:
/// the tables then do not fade, as the model does not): its range over the
/// unit's accelerometers' windows, and whether it ends with the shape's.
pub(super) fn fade_block(model: &UnitModel) -> Result<Option<(Vec<f64>, bool)>, ExportError> {
    let m = model.inner();
    let unit = model.unit();
    fade_block_of(
        m.operating_points(),
        m.preprocess().window.length(),
        m.dt_s(),
        (
            &sysid::Sensor::operating_signals(m.sensor()),
            unit.gyros().len(),
        ),
        (
            unit.gyros()[0].name.clone(),
            "a training range over the unit's accelerometers' windows of the model's length",
        ),
    )
}

/// The fade block of a training range over the operating `signals` (the
/// accelerometers the evaluator rings) of a model of `n_channels`
/// channels, `window`-sample windows and output period `dt_s`; a range
/// the layout cannot carry is refused naming `channel` and what is
/// `supported`.
fn fade_block_of(
    points: Option<&OperatingPoints>,
    window: usize,
    dt_s: f64,
    (signals, n_channels): (&[String], usize),
    (channel, supported): (String, &'static str),
) -> Result<Option<(Vec<f64>, bool)>, ExportError> {
    let Some(range) = points.and_then(|o| o.range.as_ref()) else {
        return Ok(None);
    };
    let unsupported = |what: String| ExportError::Unsupported {
        channel: channel.clone(),
        what,
        supported,
    };
    if range.window != window {
        return Err(unsupported(format!(
            "a training range over {}-sample windows",
            range.window
        )));
    }
    if range.signals != signals || range.check(signals, n_channels).is_err() {
        return Err(unsupported(format!(
            "a training range over {}",
            range.signals.join(", ")
        )));
    }
    let n_a = signals.len();
    let shape = range.shape.is_some();
    let mut f = Vec::with_capacity(dtg_onboard::fade_floats(n_a, n_channels, shape));
    for k in 0..n_a {
        f.extend([
            range.mean_min[k],
            range.mean_max[k],
            range.level_min[k],
            range.level_max[k],
        ]);
    }
    f.extend([
        range.scale,
        range.tolerance,
        range.fade.width,
        range.fade.alpha(dt_s),
    ]);
    f.extend(&range.network_mean);
    if let Some(s) = &range.shape {
        for k in 0..n_a {
            f.extend([s.min[k], s.max[k]]);
        }
        f.extend([s.scale, range.fade.fall_alpha(dt_s)]);
    } else if range.fade.fall_time_constant_s.is_some() {
        return Err(unsupported(
            "a fade whose weight falls by its own time constant without a vibration shape range"
                .into(),
        ));
    }
    debug_assert_eq!(f.len(), dtg_onboard::fade_floats(n_a, n_channels, shape));
    Ok(Some((f, shape)))
}
