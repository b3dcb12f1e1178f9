//! Each effect of a channel as the onboard tables carry it: its kind
//! (`dtg_onboard::kind`), index and parameters, in the unit frame of the
//! specific force and rates the evaluator computes.

use super::error::ExportError;
use crate::unit_sensor::effect::UnitEffect;
use crate::unit_sensor::sensor::rate_without;
use dtg_onboard::kind;
use nalgebra::Vector3;
use nav_sensors::dtg::DtgTerm;
use nav_sensors::rate::RateTerm;
use nav_sensors::unit::{GyroTerm, Unit};

/// The unit-frame axis a rate-gyro term's id letter names.
fn unit_axis(c: char) -> Vector3<f64> {
    match c {
        'x' => Vector3::x(),
        'y' => Vector3::y(),
        _ => Vector3::z(),
    }
}

/// One effect of channel `k` in the tables: kind, index, parameters.
pub(super) fn effect_entry(
    unit: &Unit,
    k: usize,
    effect: &UnitEffect,
    extra: &[String],
) -> Result<(u32, u32, Vec<f64>), ExportError> {
    let g = &unit.gyros()[k];
    let v3 = |v: Vector3<f64>| vec![v.x, v.y, v.z];
    let unsupported = |id: String| ExportError::Unsupported {
        channel: g.name.clone(),
        what: format!("effect {id}"),
        supported: "g_*, gg_*, ai_* and col:NAME effects",
    };
    let letters = |id: &str| -> Vec<char> { id.rsplit('_').next().unwrap_or("").chars().collect() };
    match effect {
        UnitEffect::Column(name) | UnitEffect::Temperature(name) => {
            let idx = extra
                .iter()
                .position(|e| e == name)
                .expect("extra columns are collected from the effects");
            Ok((kind::COLUMN, idx as u32, vec![]))
        }
        UnitEffect::Dynamic(d) => Err(unsupported(d.to_string())),
        UnitEffect::Term(GyroTerm::Rate(t)) => {
            let axes = letters(t.id());
            if RateTerm::SPECIFIC_FORCE[..3].contains(t) {
                Ok((kind::LINEAR_G, 0, v3(unit_axis(axes[0]))))
            } else if RateTerm::SPECIFIC_FORCE.contains(t) {
                let mut p = v3(unit_axis(axes[0]));
                p.extend(v3(unit_axis(axes[1])));
                Ok((kind::QUADRATIC_G, 0, p))
            } else {
                Err(unsupported(t.id().to_string()))
            }
        }
        UnitEffect::Term(GyroTerm::Dtg(t)) => {
            let Some(frame) = g.dtg_axes() else {
                return Err(unsupported(t.id().to_string()));
            };
            let ax = |c: char| match c {
                'I' => frame.input,
                'O' => frame.output,
                _ => frame.spin,
            };
            let axes = letters(t.id());
            if DtgTerm::SPECIFIC_FORCE[..3].contains(t) {
                Ok((kind::LINEAR_G, 0, v3(ax(axes[0]))))
            } else if DtgTerm::SPECIFIC_FORCE.contains(t) {
                let mut p = v3(ax(axes[0]));
                p.extend(v3(ax(axes[1])));
                Ok((kind::QUADRATIC_G, 0, p))
            } else if DtgTerm::ANISOINERTIA.contains(t) {
                // (a·op·m/3600)(b·op·m/3600): the rate of the other gyros,
                // resolved, in deg/s (the plug-in's regressor).
                let op = rate_without(unit, k).ok_or_else(|| unsupported(t.id().to_string()))?;
                let row = |c: char| {
                    let r = ax(c).transpose() * &op / 3600.0;
                    r.iter().copied().collect::<Vec<f64>>()
                };
                let mut p = row(axes[0]);
                p.extend(row(axes[1]));
                Ok((kind::RATE_PRODUCT, 0, p))
            } else {
                Err(unsupported(t.id().to_string()))
            }
        }
    }
}
