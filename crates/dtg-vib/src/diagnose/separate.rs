//! Candidates a record cannot tell apart, and the experiment that would.
//!
//! Under vibration a(t) along one cluster axis u, with the mean specific
//! force g₀ (gravity) held, a g-sensitive or g² regressor of a channel is
//! exactly r(g₀ + a·u) = r(g₀) + ℓ·a + q·a², with (ℓ, q) fixed by the
//! sensor geometry (the channel's I, O, S axes) and by g₀. Two candidates
//! whose (ℓ, q) are proportional on the record's vibration axis are
//! collinear there whatever the data; on another axis their responses may
//! differ, and a run along that axis separates them.

use nav_sensors::geometry::Axis;
use sysid::Response;

/// What separates a group of candidates, along a vibration axis.
pub type Separation = sysid::Separation<Axis>;

/// How unlike two members' responses are, each stacked over several axes as
/// (ℓ·a, q·a²) at vibration amplitude `a_g` (g rms): 1 − |cos|, 0 for
/// proportional responses (a record with those axes cannot split them).
pub(crate) fn unlikeness(x: &[Response], y: &[Response], a_g: f64) -> f64 {
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
