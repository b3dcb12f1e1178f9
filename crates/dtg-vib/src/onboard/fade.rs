//! The fade block of the onboard tables: the model's per-axis training
//! range and how its network part fades beyond it
//! (`sysid::operating::fade`), as the evaluator reads it
//! (`dtg_onboard::FADE_FLOATS` numbers after the channels).

use super::error::ExportError;
use crate::model::CompensationModel;
use nav_sensors::geometry::{Axis, Channel};

/// The fade block of a model with a training range (`None` without one:
/// the tables then do not fade, as the model does not).
pub(super) fn fade_block(model: &CompensationModel) -> Result<Option<Vec<f64>>, ExportError> {
    let Some(range) = model.operating_points().and_then(|o| o.range.as_ref()) else {
        return Ok(None);
    };
    let unsupported = |what: String| ExportError::Unsupported {
        channel: Channel::X,
        what,
        supported: "a training range over ax, ay, az windows of the model's length",
    };
    if range.window != model.preprocess().window.length() {
        return Err(unsupported(format!(
            "a training range over {}-sample windows",
            range.window
        )));
    }
    let axes: Vec<String> = Axis::ALL.iter().map(|a| a.column().to_string()).collect();
    if range.signals != axes || range.check(&axes, 6).is_err() {
        return Err(unsupported(format!(
            "a training range over {}",
            range.signals.join(", ")
        )));
    }
    let mut f = Vec::with_capacity(dtg_onboard::FADE_FLOATS);
    for k in 0..3 {
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
        range.fade.alpha(model.dt_s()),
    ]);
    f.extend(&range.network_mean);
    debug_assert_eq!(f.len(), dtg_onboard::FADE_FLOATS);
    Ok(Some(f))
}
