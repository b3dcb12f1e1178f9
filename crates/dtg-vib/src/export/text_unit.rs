//! A model of any unit as equations with units, for review (`dtg-vib
//! export --lang text` on a model of `fit --unit …`): the paper's text
//! ([`super::text`]) with the unit's gyros, models and calibration.

use super::text::{accel_text, channel_text, equations_with};
use crate::unit_sensor::UnitModel;
use nav_sensors::calibration::GyroCoefficients;
use nav_sensors::dtg::DtgTerm;
use nav_sensors::rate::RateTerm;
use std::fmt::Write;

/// The model written out (see [`super::equations`]), for any unit.
pub fn unit_equations(model: &UnitModel) -> String {
    let m = model.inner();
    equations_with(
        &format!(
            "# dtg-vib compensation model of the unit '{}'",
            model.unit().name()
        ),
        m.dt_s(),
        m.preprocess(),
        &|w| calibration_text(w, model),
        &|w| {
            for c in m.channels() {
                channel_text(w, c);
            }
        },
        m.operating_points(),
    )
}

/// The unit's columns and units, and its ground calibration as the inverse
/// models the preparation applies.
fn calibration_text(w: &mut String, model: &UnitModel) {
    let unit = model.unit();
    let _ = writeln!(
        w,
        "\n## Unit\nlog columns: time {} (s × {}); gyros {} ({}, times {} to deg/h); accelerometers {} ({}, times {} to g)",
        unit.columns().time,
        unit.columns().time_scale,
        unit.gyro_names().join(", "),
        unit.units().rate,
        unit.units().rate.to_deg_h(),
        unit.accel_names().join(", "),
        unit.units().specific_force,
        unit.units().specific_force.to_g(),
    );
    for g in unit.gyros() {
        let axes = match g.dtg_axes() {
            Some(a) => format!(
                "dtg, I = {:?}, O = {:?}, S = {:?}",
                a.input.as_slice(),
                a.output.as_slice(),
                a.spin.as_slice()
            ),
            None => format!("rate, input axis {:?}", g.input.as_slice()),
        };
        let _ = writeln!(w, "  {}: {axes}", g.name);
    }
    let _ = writeln!(w, "\n## Ground calibration");
    let Some(cal) = model.inner().sensor().calibration.as_ref() else {
        let _ = writeln!(w, "none: the raw outputs are used as they are");
        return;
    };
    let _ = writeln!(
        w,
        "accelerometers: the static triad inverse of the paper's unit when they are the unit's x, y, z axes (each coefficient ·1e-6), else as given; the specific force is their least-squares resolution in the unit frame"
    );
    for (name, c) in &cal.accels {
        accel_text(w, name, c);
    }
    let _ = writeln!(
        w,
        "gyros (a rate gyro: (output − Σ coefficient·term at zero rate)/(1 + scale factor·1e-6); a DTG: inverse of output = ω_I + Σ coefficient·term, Newton on the scale-factor nonlinearity, the rate from the least-squares rate of all gyros, two passes; g² terms with the within-interval covariance):"
    );
    for (name, c) in &cal.gyros {
        let terms: Vec<String> = match c {
            GyroCoefficients::Rate(r) => RateTerm::ALL
                .iter()
                .zip(r.to_array())
                .filter(|(_, v)| *v != 0.0)
                .map(|(t, v)| format!("{} = {v} {}", t.id(), t.unit()))
                .collect(),
            GyroCoefficients::Dtg(d) => DtgTerm::ALL
                .iter()
                .zip(d.to_array())
                .filter(|(_, v)| *v != 0.0)
                .map(|(t, v)| format!("{} = {v} {}", t.id(), t.unit()))
                .chain(std::iter::once(format!(
                    "nonlinearity = {} ppm/(deg/s)",
                    d.scale_factor_nonlinearity_ppm_per_deg_s
                )))
                .collect(),
        };
        let _ = writeln!(w, "  {name} ({}): {}", c.model(), terms.join(", "));
    }
}
