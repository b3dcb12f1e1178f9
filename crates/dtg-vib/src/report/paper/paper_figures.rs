//! Section "The paper's figures": Fig. 3 (a residue and the thrust
//! acceleration), Fig. 5 (processed acceleration and rate), Fig. 6 (target
//! and network output) for the showcase channel and for all channels.

use super::ctx::{Ctx, pick};
use crate::apply::raw_residues;
use crate::error::DtgVibError;
use crate::report::common::colours;
use nav_sensors::geometry::Channel;
use plot::{Figure, Panel, Section, Series};

/// The section's figures, with their file stems.
pub(super) fn figures(ctx: &Ctx<'_>) -> Result<Vec<(Figure, &'static str)>, DtgVibError> {
    Ok(vec![
        (fig3(ctx)?, "fig3_residue_accel"),
        (fig5(ctx)?, "fig5_processed"),
        (fig6(ctx), "fig6_network"),
        (fig6_all(ctx), "fig6_all_channels"),
    ])
}

/// Fig. 3: a residue of the raw record and the thrust acceleration.
fn fig3(ctx: &Ctx<'_>) -> Result<Figure, DtgVibError> {
    let t_all = ctx.record.t();
    let thrust = &ctx.thrust;
    let raw = raw_residues(ctx.record);
    Ok(
        Figure::new("Fig. 3 — residue K0 and thrust acceleration (record as given)")
            .share_x()
            .panel(
                Panel::new("Residue K0", "time (s)", "K0 (deg/h)").series(
                    Series::line("K0", t_all.to_vec(), raw[0].clone()).colour(colours::BEFORE),
                ),
            )
            .panel(
                Panel::new(
                    format!("Thrust acceleration {thrust}"),
                    "time (s)",
                    format!("{thrust} (g)"),
                )
                .series(
                    Series::line(
                        thrust.clone(),
                        t_all.to_vec(),
                        crate::pipeline::signal(ctx.record, thrust)?.to_vec(),
                    )
                    .colour(colours::INPUT),
                ),
            ),
    )
}

/// Fig. 5: processed acceleration and rate.
fn fig5(ctx: &Ctx<'_>) -> Result<Figure, DtgVibError> {
    let t_all = ctx.record.t();
    let (thrust, show) = (&ctx.thrust, ctx.show);
    let az_f = ctx.applied.prepared.signal_full(thrust)?;
    Ok(Figure::new(format!(
        "Fig. 5 — processed acceleration and rate (channel {show})"
    ))
    .share_x()
    .panel(
        Panel::new(
            format!("Processed {thrust}"),
            "time (s)",
            format!("{thrust} (g)"),
        )
        .series(Series::line(thrust.clone(), t_all.to_vec(), az_f).colour(colours::INPUT)),
    )
    .panel(
        Panel::new(
            format!("Processed rate output {show}"),
            "time (s)",
            format!("{show} (deg/h)"),
        )
        .series(
            Series::line(
                show.name(),
                t_all.to_vec(),
                ctx.applied.prepared.target_full(show).to_vec(),
            )
            .colour(colours::BEFORE),
        ),
    ))
}

/// Target and network output of `ch` on `rows`.
fn target_and_output(ctx: &Ctx<'_>, ch: Channel, rows: &[usize], panel: Panel) -> Panel {
    let y = ctx.applied.prepared.target(ch);
    let p = &ctx.applied.predicted[ch.index()];
    panel
        .series(Series::line("target", ctx.rows_t(rows), pick(y, rows)).colour(colours::BEFORE))
        .series(
            Series::line("network output", ctx.rows_t(rows), pick(p, rows)).colour(colours::AFTER),
        )
}

/// Fig. 6: target and network output, training and validation.
fn fig6(ctx: &Ctx<'_>) -> Figure {
    let show = ctx.show;
    let half = |rows: &[usize], title: &str| {
        let p = Panel::new(title.to_string(), "time (s)", "rate error (deg/h)");
        target_and_output(ctx, show, rows, p)
    };
    Figure::new(format!(
        "Fig. 6 — target and network output, channel {show}"
    ))
    .panel(half(&ctx.applied.train, "Training set"))
    .panel(half(&ctx.applied.val, "Validation set"))
}

/// Fig. 6 for all channels, validation only.
fn fig6_all(ctx: &Ctx<'_>) -> Figure {
    let mut all6 = Figure::new("Network output on the validation set, all channels").share_x();
    for ch in Channel::ALL {
        let p = Panel::new(format!("Channel {ch}"), "time (s)", format!("{ch} (deg/h)"));
        all6 = all6.panel(target_and_output(ctx, ch, &ctx.applied.val, p));
    }
    all6
}

/// The section, once its figures are drawn.
pub(super) fn section(drawn: &crate::report::common::Drawn) -> Section {
    Section::new("The paper's figures")
        .figure(
            drawn.get("fig3_residue_accel"),
            "Fig. 3: residue K0 and the thrust acceleration, record as given.",
        )
        .figure(
            drawn.get("fig5_processed"),
            "Fig. 5: processed acceleration and rate output.",
        )
        .figure(
            drawn.get("fig6_network"),
            "Fig. 6: target and network output on the training and validation sets.",
        )
        .figure(
            drawn.get("fig6_all_channels"),
            "Network output on the validation set, all six channels.",
        )
}
