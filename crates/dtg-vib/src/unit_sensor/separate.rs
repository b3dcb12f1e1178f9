//! Which vibration axis of the unit would tell apart candidates a record
//! cannot, for any unit: the argument of [`crate::diagnose::separate`]
//! (a term's regressor under vibration a along a unit axis u about the
//! mean specific force g₀ is r(g₀) + ℓ·a + q·a²), with each channel's
//! regressors taken from its own model and axes in the unit file.

use super::effect::UnitEffect;
use crate::diagnose::separate::{Group, advise};
use nalgebra::Vector3;
use nav_sensors::geometry::Axis;
use nav_sensors::unit::{GyroTerm, Sensed, Unit};
use sysid::{OperatingStats, Response, Separation};

/// Whether a term depends on specific force (what vibration excites).
fn is_specific_force(t: &GyroTerm) -> bool {
    match t {
        GyroTerm::Dtg(d) => nav_sensors::dtg::DtgTerm::SPECIFIC_FORCE.contains(d),
        GyroTerm::Rate(r) => nav_sensors::rate::RateTerm::SPECIFIC_FORCE.contains(r),
    }
}

/// The response of `term` of gyro `channel` to vibration along `axis`
/// about `gravity_g` (unit frame, g); `None` for a term that does not
/// depend on specific force.
///
/// ```
/// use nav_sensors::geometry::Axis;
/// let triad = nav_sensors::unit::Unit::builtin("triad").unwrap();
/// let g = nalgebra::Vector3::new(0.0, 0.0, 1.0);
/// let gg = triad.parse_term(0, "gg_zz").unwrap();
/// let r = dtg_vib::unit_sensor::response(&triad, 0, gg, &g, Axis::Z).unwrap();
/// assert!((r.linear - 2.0).abs() < 1e-12 && (r.quadratic - 1.0).abs() < 1e-12);
/// ```
pub fn response(
    unit: &Unit,
    channel: usize,
    term: GyroTerm,
    gravity_g: &Vector3<f64>,
    axis: Axis,
) -> Option<Response> {
    if !is_specific_force(&term) {
        return None;
    }
    let gyro = &unit.gyros()[channel];
    let u = axis.unit_vector();
    let at = |a: f64| {
        gyro.regressor(
            term,
            &Sensed {
                specific_force_g: gravity_g + u * a,
                ..Sensed::default()
            },
        )
    };
    let (m, z, p) = (at(-1.0), at(0.0), at(1.0));
    Some(Response {
        linear: (p - m) / 2.0,
        quadratic: (p + m) / 2.0 - z,
    })
}

/// The operating signals' means and variances in the unit frame: the mean
/// specific force, and each axis's variance (the accelerometers' variances
/// carried through the unit's specific-force combination).
fn unit_frame(unit: &Unit, operating: &OperatingStats) -> (Vector3<f64>, [f64; 3]) {
    let n = unit.accels().len();
    if operating.means.len() != n || operating.variances.len() != n {
        return (Vector3::z(), [0.0, 0.0, 1.0]);
    }
    let gravity = unit.specific_force(&operating.means);
    let mut var = [0.0; 3];
    for (k, v) in operating.variances.iter().enumerate() {
        let mut e = vec![0.0; n];
        e[k] = 1.0;
        let column = unit.specific_force(&e);
        for (j, x) in var.iter_mut().enumerate() {
            *x += column[j] * column[j] * v;
        }
    }
    (gravity, var)
}

/// The separation advice for `group` (representative first) on gyro
/// `channel`: which other axis, run as well, splits the group.
pub fn separation(
    unit: &Unit,
    channel: usize,
    group: &[UnitEffect],
    kappa: &[f64],
    operating: &OperatingStats,
) -> Separation<Axis> {
    let (gravity_g, var) = unit_frame(unit, operating);
    let current = Axis::ALL
        .into_iter()
        .max_by(|a, b| var[a.index()].total_cmp(&var[b.index()]))
        .unwrap_or(Axis::Z);
    let terms: Vec<Option<GyroTerm>> = group
        .iter()
        .map(|e| match e {
            UnitEffect::Term(t) if is_specific_force(t) => Some(*t),
            _ => None,
        })
        .collect();
    advise(
        Group {
            ids: group.iter().map(UnitEffect::id).collect(),
            kappa,
            responsive: terms.iter().all(Option::is_some),
            has_column: group.iter().any(|e| e.column_name().is_some()),
        },
        var.iter().sum::<f64>().sqrt(),
        current,
        |axis| {
            terms
                .iter()
                .flatten()
                .map(|t| response(unit, channel, *t, &gravity_g, axis).expect("specific force"))
                .collect()
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rate gyro under z vibration with gravity on z: g_x and gg_xx both
    /// stay zero (one record cannot tell them apart); along x one responds
    /// linearly and the other rectifies, which is what the advice names.
    #[test]
    fn the_advice_names_an_axis_of_the_unit() {
        let triad = Unit::builtin("triad").unwrap();
        let ops = OperatingStats {
            names: vec!["ax".into(), "ay".into(), "az".into()],
            means: vec![0.0, 0.0, 1.0],
            variances: vec![0.0, 0.0, 0.25],
        };
        let group: Vec<UnitEffect> = ["g_x", "gg_xx"]
            .iter()
            .map(|s| s.parse().unwrap())
            .collect();
        let s = separation(&triad, 2, &group, &[1.0], &ops);
        assert_eq!(s.axis, Some(Axis::X), "{}", s.advice);
        assert!(s.advice.contains("along x as well"), "{}", s.advice);
    }

    /// Vibration along z of 1 g rms with gravity along z.
    fn z_vibration() -> OperatingStats {
        OperatingStats {
            names: vec!["ax".into(), "ay".into(), "az".into()],
            means: vec![0.0, 0.0, 1.0],
            variances: vec![0.0, 0.0, 1.0],
        }
    }

    /// The paper's channel X under Z vibration with gravity along z: g_O
    /// and g_S are both ∝ a_z (the issue's example of a pair one record
    /// cannot split); a run along Y separates them (O = (y − z)/√2,
    /// S = −(y + z)/√2).
    #[test]
    fn z_vibration_pair_is_separated_by_another_axis() {
        let paper = Unit::paper();
        let g = Vector3::new(0.0, 0.0, 1.0);
        let on_z = |id| {
            let t = paper.parse_term(0, id).unwrap();
            response(&paper, 0, t, &g, Axis::Z).unwrap()
        };
        let (go, gs) = (on_z("g_O"), on_z("g_S"));
        let alike = crate::diagnose::separate::unlikeness(&[go], &[gs], 1.0);
        assert!(alike < 1e-12, "alike on Z");
        let group: Vec<UnitEffect> = ["g_O", "g_S"].iter().map(|s| s.parse().unwrap()).collect();
        let s = separation(&paper, 0, &group, &[1.0], &z_vibration());
        assert_eq!(s.axis, Some(Axis::Y), "{}", s.advice);
        let r = |i: usize| s.responses[i].unwrap().linear;
        assert!((r(0) - r(1)).abs() > 1.0, "{}", s.advice);
        assert!(
            s.advice.contains(&format!("along {}", Axis::Y.name())),
            "{}",
            s.advice
        );
    }

    /// A group with an extra column is split by varying the column.
    #[test]
    fn a_column_is_separated_by_varying_it() {
        let paper = Unit::paper();
        let group: Vec<UnitEffect> = ["gg_IS", "col:temp"]
            .iter()
            .map(|s| s.parse().unwrap())
            .collect();
        let s = separation(&paper, 3, &group, &[0.5], &z_vibration());
        assert_eq!(s.axis, None);
        assert!(s.advice.contains("thermal"), "{}", s.advice);
    }
}
