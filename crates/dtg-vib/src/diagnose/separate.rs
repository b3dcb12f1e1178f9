//! Candidates a record cannot tell apart, and the experiment that would.
//!
//! Under vibration a(t) along one cluster axis u, with the mean specific
//! force g₀ (gravity) held, a g-sensitive or g² regressor of a channel is
//! exactly r(g₀ + a·u) = r(g₀) + ℓ·a + q·a², with (ℓ, q) fixed by the
//! sensor geometry (the channel's I, O, S axes) and by g₀. Two candidates
//! whose (ℓ, q) are proportional on the record's vibration axis are
//! collinear there whatever the data; on another axis their responses may
//! differ, and a run along that axis separates them.

use crate::effects::Effect;
use nalgebra::Vector3;
use nav_sensors::dtg::{DtgInput, DtgTerm};
use nav_sensors::geometry::{Axis, Channel, ChannelFrame};
use sysid::Response;

/// What separates a group of candidates, along a vibration axis.
pub type Separation = sysid::Separation<Axis>;

/// The response of `term` on `channel` to vibration along `axis` about the
/// mean specific force `gravity_g` (cluster frame, g): the regressor's
/// change per g (linear) and per g² (rectifying) of vibration; `None` for
/// terms that do not depend on specific force.
///
/// ```
/// use dtg_vib::diagnose::response;
/// use nav_sensors::{dtg::DtgTerm, geometry::{Axis, Channel}};
/// let g = nalgebra::Vector3::new(0.0, 0.0, 1.0);
/// // Channel Z's input axis is cluster z: gg_II = f_I² responds 2·g₀·a + a².
/// let r = response(Channel::Z, DtgTerm::GgII, &g, Axis::Z).unwrap();
/// assert!((r.linear - 2.0).abs() < 1e-12 && (r.quadratic - 1.0).abs() < 1e-12);
/// assert!(response(Channel::Z, DtgTerm::AiIO, &g, Axis::Z).is_none());
/// ```
pub fn response(
    channel: Channel,
    term: DtgTerm,
    gravity_g: &Vector3<f64>,
    axis: Axis,
) -> Option<Response> {
    if !DtgTerm::SPECIFIC_FORCE.contains(&term) {
        return None;
    }
    let frame = ChannelFrame::of(channel);
    let mut u = Vector3::zeros();
    u[axis.index()] = 1.0;
    let at = |a: f64| {
        term.regressor(&DtgInput::resolved(
            &frame,
            &Vector3::zeros(),
            &(gravity_g + u * a),
        ))
    };
    let (m, z, p) = (at(-1.0), at(0.0), at(1.0));
    Some(Response {
        linear: (p - m) / 2.0,
        quadratic: (p + m) / 2.0 - z,
    })
}

/// How unlike two members' responses are, each stacked over several axes as
/// (ℓ·a, q·a²) at vibration amplitude `a_g` (g rms): 1 − |cos|, 0 for
/// proportional responses (a record with those axes cannot split them).
fn unlikeness(x: &[Response], y: &[Response], a_g: f64) -> f64 {
    let v: Vec<f64> = x
        .iter()
        .flat_map(|r| [r.linear * a_g, r.quadratic * a_g * a_g])
        .collect();
    let w: Vec<f64> = y
        .iter()
        .flat_map(|r| [r.linear * a_g, r.quadratic * a_g * a_g])
        .collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
    let n = (dot(&v, &v) * dot(&w, &w)).sqrt();
    if n <= 0.0 {
        // A member that does not respond at all differs from one that does.
        return if v == w { 0.0 } else { 1.0 };
    }
    1.0 - (dot(&v, &w) / n).abs()
}

/// The separation advice for `group` (representative first) on `channel`,
/// with `kappa[i]` the identified combination's weight of member i + 1,
/// the record's mean specific force, its vibration amplitude (g rms) and the
/// axis it vibrates along: which other axis, run as well, splits the group.
pub fn separation(
    channel: Channel,
    group: &[Effect],
    kappa: &[f64],
    gravity_g: &Vector3<f64>,
    vibration_g: f64,
    current: Axis,
) -> Separation {
    let terms: Vec<Option<DtgTerm>> = group
        .iter()
        .map(|e| match e {
            Effect::Term(t) if DtgTerm::SPECIFIC_FORCE.contains(t) => Some(*t),
            _ => None,
        })
        .collect();
    advise(
        Group {
            ids: group.iter().map(Effect::id).collect(),
            kappa,
            responsive: terms.iter().all(Option::is_some),
            has_column: group.iter().any(|e| matches!(e, Effect::Column(_))),
        },
        vibration_g,
        current,
        |axis| {
            terms
                .iter()
                .flatten()
                .map(|t| response(channel, *t, gravity_g, axis).expect("specific force"))
                .collect()
        },
    )
}

/// A group of candidates one record cannot tell apart, as the advice needs
/// it: their ids (the representative first), the identified combination's
/// weights, whether every member responds to specific force, and whether
/// one is an extra column.
pub(crate) struct Group<'a> {
    pub ids: Vec<String>,
    pub kappa: &'a [f64],
    pub responsive: bool,
    pub has_column: bool,
}

/// The advice for a group under vibration along `current` of `vibration_g`
/// (g rms), each member's response along an axis given by `on` (called only
/// when every member responds to specific force): the other axis along
/// which a run splits the group, if one does. One argument for every unit.
pub(crate) fn advise(
    group: Group<'_>,
    vibration_g: f64,
    current: Axis,
    on: impl Fn(Axis) -> Vec<Response>,
) -> Separation {
    let Group {
        ids,
        kappa,
        responsive,
        has_column,
    } = group;
    let combination: Vec<(String, f64)> = ids
        .iter()
        .skip(1)
        .cloned()
        .zip(kappa.iter().copied())
        .collect();
    let combo_text = combination
        .iter()
        .map(|(id, k)| format!("{k:+.3}·c({id})"))
        .collect::<Vec<_>>()
        .join(" ");
    let identified = format!("this record measures c({}) {combo_text}", ids[0]);
    if !responsive {
        let advice = if !has_column {
            format!(
                "{identified}; rate-product terms are separated on a rate table, not by vibration"
            )
        } else {
            format!(
                "{identified}; vary the column independently of the vibration (e.g. a separate thermal run) to tell them apart"
            )
        };
        return Separation {
            responses: vec![None; ids.len()],
            effects: ids,
            combination,
            axis: None,
            advice,
        };
    }
    let a = vibration_g.max(1e-3);
    let here = on(current);
    let (axis, there, worst) = Axis::ALL
        .iter()
        .filter(|&&k| k != current)
        .map(|&axis| {
            let there = on(axis);
            let worst = (0..there.len())
                .flat_map(|i| (i + 1..there.len()).map(move |j| (i, j)))
                .map(|(i, j)| unlikeness(&[here[i], there[i]], &[here[j], there[j]], a))
                .fold(f64::INFINITY, f64::min);
            (axis, there, worst)
        })
        .max_by(|x, y| x.2.total_cmp(&y.2))
        .expect("two other axes");
    let described: Vec<String> = ids
        .iter()
        .zip(&there)
        .map(|(id, r)| format!("{id} responds {:+.3}·a {:+.3}·a²", r.linear, r.quadratic))
        .collect();
    if worst < 1e-3 {
        return Separation {
            effects: ids,
            combination,
            axis: None,
            responses: there.into_iter().map(Some).collect(),
            advice: format!(
                "{identified}; a run along another single axis does not split them either (their responses stay proportional): change the mount so the vibration axis is tilted"
            ),
        };
    }
    Separation {
        effects: ids,
        combination,
        axis: Some(axis),
        advice: format!(
            "{identified}; run the same test with vibration along {} as well: there {} (a in g), unlike along {}",
            axis.name(),
            described.join(", "),
            current.name()
        ),
        responses: there.into_iter().map(Some).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Channel X under Z vibration with gravity along z: g_O and g_S are both
    /// ∝ a_z (the issue's example of a pair one record cannot split); a run
    /// along Y separates them (O = (y − z)/√2, S = −(y + z)/√2).
    #[test]
    fn z_vibration_pair_is_separated_by_another_axis() {
        let g = Vector3::new(0.0, 0.0, 1.0);
        let go = response(Channel::X, DtgTerm::GO, &g, Axis::Z).unwrap();
        let gs = response(Channel::X, DtgTerm::GS, &g, Axis::Z).unwrap();
        assert!(unlikeness(&[go], &[gs], 1.0) < 1e-12, "alike on Z");
        let s = separation(
            Channel::X,
            &["g_O".parse().unwrap(), "g_S".parse().unwrap()],
            &[1.0],
            &g,
            1.0,
            Axis::Z,
        );
        assert_eq!(s.axis, Some(Axis::Y), "{}", s.advice);
        let r = |i: usize| s.responses[i].unwrap().linear;
        assert!((r(0) - r(1)).abs() > 1.0, "{}", s.advice);
        assert!(
            s.advice.contains(&format!("along {}", Axis::Y.name())),
            "{}",
            s.advice
        );
    }

    #[test]
    fn a_column_is_separated_by_varying_it() {
        let s = separation(
            Channel::Y1,
            &["gg_IS".parse().unwrap(), "col:temp".parse().unwrap()],
            &[0.5],
            &Vector3::new(0.0, 0.0, 1.0),
            1.0,
            Axis::Z,
        );
        assert_eq!(s.axis, None);
        assert!(s.advice.contains("thermal"), "{}", s.advice);
    }
}
