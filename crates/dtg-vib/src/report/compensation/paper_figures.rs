//! Section "The paper's figures": Figs. 3, 5 and 6 of the paper (Fig. 7 is
//! under "Parity residues") drawn for this unit — the first residue of the
//! record as given against the thrust acceleration (for a unit with
//! residues), the processed acceleration and rate, the target and network
//! output on the training and validation rows, and for all channels.

use super::ctx::{Ctx, pick};
use crate::report::common::{Drawn, colours};
use plot::{Figure, Panel, Section, Series};

/// The section's figures, with their file stems: each the record lets
/// the page draw (Fig. 3 needs a residue and the thrust column as given,
/// Fig. 5 the thrust after the pre-filter).
pub(super) fn figures(ctx: &Ctx<'_>) -> Vec<(Figure, &'static str)> {
    let mut out = Vec::new();
    if let Some(f) = fig3(ctx) {
        out.push((f, "fig3_residue_accel"));
    }
    if let Some(f) = fig5(ctx) {
        out.push((f, "fig5_processed"));
    }
    out.push((fig6(ctx), "fig6_network"));
    out.push((fig6_all(ctx), "fig6_all_channels"));
    out
}

/// Fig. 3: a residue of the raw record and the thrust acceleration.
fn fig3(ctx: &Ctx<'_>) -> Option<Figure> {
    let (name, residue) = ctx.raw_residue.as_ref()?;
    let accel = ctx.thrust_raw.as_ref()?;
    let thrust = &ctx.thrust;
    let t_all = ctx.t_all;
    Some(
        Figure::new(format!(
            "Fig. 3 — residue {name} and thrust acceleration (record as given)"
        ))
        .share_x()
        .panel(
            Panel::new(
                format!("Residue {name}"),
                "time (s)",
                format!("{name} (deg/h)"),
            )
            .series(
                Series::line(name.as_str(), t_all.to_vec(), residue.clone())
                    .colour(colours::BEFORE),
            ),
        )
        .panel(
            Panel::new(
                format!("Thrust acceleration {thrust}"),
                "time (s)",
                format!("{thrust} (g)"),
            )
            .series(
                Series::line(thrust.clone(), t_all.to_vec(), accel.clone()).colour(colours::INPUT),
            ),
        ),
    )
}

/// Fig. 5: processed acceleration and rate.
fn fig5(ctx: &Ctx<'_>) -> Option<Figure> {
    let az_f = ctx.thrust_processed.as_ref()?;
    let t_all = ctx.t_all;
    let thrust = &ctx.thrust;
    let show = &ctx.channels[ctx.show];
    let ch = &show.name;
    Some(
        Figure::new(format!(
            "Fig. 5 — processed acceleration and rate (channel {ch})"
        ))
        .share_x()
        .panel(
            Panel::new(
                format!("Processed {thrust}"),
                "time (s)",
                format!("{thrust} (g)"),
            )
            .series(
                Series::line(thrust.clone(), t_all.to_vec(), az_f.clone()).colour(colours::INPUT),
            ),
        )
        .panel(
            Panel::new(
                format!("Processed rate output {ch}"),
                "time (s)",
                format!("{ch} (deg/h)"),
            )
            .series(
                Series::line(ch.as_str(), t_all.to_vec(), show.target_full.to_vec())
                    .colour(colours::BEFORE),
            ),
        ),
    )
}

/// Target and network output of channel `k` on `rows`.
fn target_and_output(ctx: &Ctx<'_>, k: usize, rows: &[usize], panel: Panel) -> Panel {
    let c = &ctx.channels[k];
    panel
        .series(
            Series::line("target", ctx.rows_t(rows), pick(c.target, rows)).colour(colours::BEFORE),
        )
        .series(
            Series::line("network output", ctx.rows_t(rows), pick(c.predicted, rows))
                .colour(colours::AFTER),
        )
}

/// Fig. 6: target and network output, training and validation.
fn fig6(ctx: &Ctx<'_>) -> Figure {
    let half = |rows: &[usize], title: &str| {
        let p = Panel::new(title.to_string(), "time (s)", "rate error (deg/h)");
        target_and_output(ctx, ctx.show, rows, p)
    };
    let mut fig = Figure::new(format!(
        "Fig. 6 — target and network output, channel {}",
        ctx.channels[ctx.show].name
    ));
    if !ctx.train.is_empty() {
        fig = fig.panel(half(ctx.train, "Training set"));
    }
    fig.panel(half(ctx.val, "Validation set"))
}

/// Fig. 6 for all channels, validation only.
fn fig6_all(ctx: &Ctx<'_>) -> Figure {
    let mut all6 = Figure::new("Network output on the validation set, all channels").share_x();
    for (k, c) in ctx.channels.iter().enumerate() {
        let ch = &c.name;
        let p = Panel::new(format!("Channel {ch}"), "time (s)", format!("{ch} (deg/h)"));
        all6 = all6.panel(target_and_output(ctx, k, ctx.val, p));
    }
    all6
}

/// The section, once its figures are drawn.
pub(super) fn section(ctx: &Ctx<'_>, drawn: &Drawn) -> Section {
    let mut sec = Section::new("The paper's figures").text(
        "Figs. 3, 5 and 6 of Malini, Mohanlal & Harikumar, drawn for this unit and record (Fig. 7 is under Parity residues).",
    );
    match (drawn.find("fig3_residue_accel"), &ctx.raw_residue) {
        (Some(f), Some((name, _))) => {
            sec = sec.figure(
                f,
                format!("Fig. 3: residue {name} and the thrust acceleration, record as given."),
            );
        }
        (_, None) => {
            sec = sec.text(format!(
                "Fig. 3 (a residue against the thrust acceleration) needs a parity residue: {}",
                super::residues::no_residue(ctx)
            ))
        }
        (None, Some(_)) => {
            sec = sec.text(format!(
                "Fig. 3 is not drawn: the thrust acceleration {} is not a column of every record.",
                ctx.thrust
            ))
        }
    }
    if let Some(f) = drawn.find("fig5_processed") {
        sec = sec.figure(f, "Fig. 5: processed acceleration and rate output.");
    }
    sec.figure(
        drawn.get("fig6_network"),
        "Fig. 6: target and network output on the training and validation sets.",
    )
    .figure(
        drawn.get("fig6_all_channels"),
        format!(
            "Network output on the validation set, all {} channels.",
            ctx.channels.len()
        ),
    )
}
