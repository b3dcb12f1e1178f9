//! The lot's page, `DIR/index.html`: who is out of family, who fails the
//! specification, who failed to run; per channel and effect a strip plot
//! of every unit's coefficient with its 95% interval against the lot's
//! median and the out-of-family band; and a link to every unit's page.

use super::summary::{Group, Status, Summary, SummaryError};
use plot::{Figure, HtmlReport, Panel, Section, Series, Table};
use std::path::{Path, PathBuf};

fn num(x: f64) -> String {
    format!("{x:.4}")
}

/// The strip plot of one group: each unit at its place in the manifest,
/// its coefficient a dot with its interval (out of family in another
/// colour), the median and median ± threshold robust standard deviations
/// as lines.
fn strip(g: &Group, s: &Summary) -> Figure {
    let place = |id: &str| {
        s.units
            .iter()
            .position(|u| u.id == id)
            .map_or(f64::NAN, |k| k as f64 + 1.0)
    };
    let out = |id: &str| {
        s.out_of_family
            .iter()
            .any(|o| o.unit == id && o.channel == g.channel && o.effect == g.effect)
    };
    let (mut bx, mut by) = (Vec::new(), Vec::new());
    let (mut x, mut y, mut ox, mut oy) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for m in &g.members {
        let at = place(&m.unit);
        // One segment per unit: a NaN between them breaks the line.
        bx.extend([at, at, f64::NAN]);
        by.extend([m.ci95[0], m.ci95[1], f64::NAN]);
        match out(&m.unit) {
            true => (ox.push(at), oy.push(m.value)),
            false => (x.push(at), y.push(m.value)),
        };
    }
    let mut p = Panel::new(
        format!("{} on {}", g.effect, g.channel),
        "unit (its entry in the manifest, from 1)",
        format!("coefficient ({})", g.unit),
    )
    .series(Series::line("95% interval", bx, by).colour(0))
    .series(Series::points("coefficient", x, y).colour(0));
    if !ox.is_empty() {
        p = p.series(Series::points("out of family", ox, oy).colour(1));
    }
    p = p.ref_line(g.median, "lot median");
    if g.judged {
        let w = s.threshold * g.robust_sigma;
        p = p
            .ref_line(g.median + w, format!("median + {} robust σ", s.threshold))
            .ref_line(g.median - w, format!("median − {} robust σ", s.threshold));
    }
    Figure::new(format!("{} on {} across the lot", g.effect, g.channel)).panel(p)
}

fn verdicts(s: &Summary) -> Vec<Section> {
    let mut ooft = Table::new([
        "unit",
        "channel",
        "effect",
        "value",
        "95% interval",
        "robust z",
        "lot median",
    ]);
    for o in &s.out_of_family {
        ooft = ooft.row([
            o.unit.clone(),
            o.channel.clone(),
            o.effect.clone(),
            format!("{} {}", num(o.value), o.coefficient_unit),
            format!("{} to {}", num(o.ci95[0]), num(o.ci95[1])),
            format!("{:.1}", o.z),
            num(o.median),
        ]);
    }
    let mut spec = Table::new(["unit", "channel", "limit", "value", "limit value"]);
    for f in &s.failing_spec {
        spec = spec.row([
            f.unit.clone(),
            f.channel.clone(),
            f.limit_key.clone(),
            format!("{} {}", num(f.value), f.value_unit),
            format!("{} {}", num(f.limit), f.value_unit),
        ]);
    }
    let mut failed = Table::new(["unit", "reason"]);
    for f in &s.failed {
        failed = failed.row([f.unit.clone(), f.reason.clone()]);
    }
    vec![
        Section::new("Out of family").text(format!(
            "A unit is out of family when its robust z (distance to the lot's median over the lot's robust spread between units, 1.4826 × the median absolute deviation less the typical measurement variance, combined with the unit's own standard error) is beyond {} and its own 95% interval excludes the lot's median; judged over {} units or more. {} found.",
            s.threshold, s.min_units, s.out_of_family.len()
        )).table(ooft),
        Section::new("Failing the specification")
            .text(format!("{} found (|coefficient| per effect id, rms after per channel).", s.failing_spec.len()))
            .table(spec),
        Section::new("Failed to run").text(format!("{} units.", s.failed.len())).table(failed),
    ]
}

fn group_section(g: &Group, s: &Summary, figures: &Path) -> Result<Section, SummaryError> {
    let stem = format!("{}_{}", g.channel, g.effect.replace([':', '/'], "_"));
    let files = strip(g, s)
        .save(figures, &stem)
        .map_err(|e| SummaryError::Page(e.to_string()))?;
    let mut t = Table::new(["unit", "value", "95% interval", "robust z"]);
    for m in &g.members {
        t = t.row([
            m.unit.clone(),
            num(m.value),
            format!("{} to {}", num(m.ci95[0]), num(m.ci95[1])),
            m.z.map_or("—".into(), |z| format!("{z:.2}")),
        ]);
    }
    let judged = match g.judged {
        true => String::new(),
        false => format!(
            " Not judged for out of family: fewer than {} units or no spread.",
            s.min_units
        ),
    };
    Ok(Section::new(format!("{} on {} ({})", g.effect, g.channel, g.unit))
        .text(format!(
            "{} units: median {}, median absolute deviation {}, robust σ {}.{judged}",
            g.members.len(),
            num(g.median),
            num(g.mad),
            num(g.robust_sigma)
        ))
        .figure(&files, "Each unit's coefficient with its 95% interval; the lot's median and the out-of-family band.")
        .table(t))
}

/// Writes `dir/index.html` (figures in `dir/summary/`) and returns its path.
pub fn write(s: &Summary, dir: &Path) -> Result<PathBuf, SummaryError> {
    let count = |st: Status| s.units.iter().filter(|u| u.status == st).count();
    let mut page = HtmlReport::new(format!("The lot '{}'", s.lot)).summary(format!(
        "{} units: {} done, {} failed, {} not run. Out of family: {}. Failing the specification: {}.",
        s.units.len(),
        count(Status::Done),
        count(Status::Failed),
        count(Status::NotRun),
        names(s.out_of_family.iter().map(|o| &o.unit)),
        names(s.failing_spec.iter().map(|f| &f.unit)),
    ));
    for sec in verdicts(s) {
        page = page.section(sec);
    }
    let figures = dir.join("summary");
    for g in &s.groups {
        page = page.section(group_section(g, s, &figures)?);
    }
    let mut units = Section::new("Every unit");
    for u in &s.units {
        units = match &u.report {
            Some(r) => units.link(dir.join(r), format!("{}: its page", u.id)),
            None => units.text(format!("{}: {}", u.id, status_word(u.status))),
        };
    }
    page.section(units)
        .write(dir)
        .map_err(|e| SummaryError::Page(e.to_string()))
}

fn status_word(s: Status) -> &'static str {
    match s {
        Status::Done => "done",
        Status::Failed => "failed (see Failed to run)",
        Status::NotRun => "not run yet",
    }
}

/// Distinct ids, in order, or "none".
fn names<'a>(ids: impl Iterator<Item = &'a String>) -> String {
    let mut v: Vec<&str> = Vec::new();
    for id in ids {
        if !v.contains(&id.as_str()) {
            v.push(id);
        }
    }
    match v.is_empty() {
        true => "none".into(),
        false => v.join(", "),
    }
}
