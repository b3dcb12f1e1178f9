//! The paper's figures (Figs. 3, 5, 6, 7), residue spectra, before/after bars
//! and the report page that shows them with the numbers.

use super::{fmt, save_all};
use crate::apply::{Applied, raw_residues};
use crate::error::DtgVibError;
use crate::model::{ChannelScores, CompensationModel};
use crate::residue::ResidueStats;
use nav_sensors::geometry::{Channel, Residue};
use nav_sensors::record::Record;
use plot::{BarChart, Figure, HtmlReport, Panel, Section, Series, Table};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// What a report wrote and the numbers it shows.
#[derive(Debug, Clone, Serialize)]
pub struct ReportSummary {
    /// The report page.
    pub index: PathBuf,
    /// Residue rms before/after on the validation rows.
    pub residues: Vec<ResidueStats>,
    /// Each channel's scores on this record, in X, X1, Y, Y1, Z, Z1 order.
    pub channels: Vec<ChannelScores>,
}

/// A previous model of the same record, to show each channel's error before
/// and after (e.g. before and after adding an effect).
pub struct Baseline<'a> {
    /// Its name in the report (e.g. "baseline").
    pub label: &'a str,
    /// The model.
    pub model: &'a CompensationModel,
    /// It applied to the same record.
    pub applied: &'a Applied,
}

fn rows_t(a: &Applied, rows: &[usize]) -> Vec<f64> {
    rows.iter().map(|&r| a.residues.t[r]).collect()
}

fn pick(v: &[f64], rows: &[usize]) -> Vec<f64> {
    rows.iter().map(|&r| v[r]).collect()
}

/// The channel whose validation residual fell most against a bias-only model:
/// the one the paper's single-channel figures show.
fn showcase(scores: &[ChannelScores]) -> Channel {
    Channel::ALL
        .into_iter()
        .zip(scores)
        .max_by(|(_, a), (_, b)| {
            let g = |s: &ChannelScores| s.val_rms_bias_only / s.val_rms;
            g(a).total_cmp(&g(b))
        })
        .map_or(Channel::X, |(c, _)| c)
}

/// Writes the figures and `index.html` into `dir`.
///
/// `source` names the record on the page (its file name, or "simulated").
pub fn write_report(
    model: &CompensationModel,
    applied: &Applied,
    record: &Record,
    source: &str,
    baseline: Option<Baseline<'_>>,
    dir: &Path,
) -> Result<ReportSummary, DtgVibError> {
    let t_all = record.t();
    let raw = raw_residues(record);
    // Scores on this record (not the fit-time ones: the record may be another).
    let scores: Vec<ChannelScores> = Channel::ALL.map(|c| applied.scores(c)).to_vec();
    let base_scores: Option<Vec<ChannelScores>> = baseline
        .as_ref()
        .map(|b| Channel::ALL.map(|c| b.applied.scores(c)).to_vec());
    let show = showcase(&scores);
    let thrust = model
        .preprocess()
        .window
        .signals()
        .first()
        .cloned()
        .unwrap_or_else(|| "az".into());
    let (train, val) = (&applied.train, &applied.val);

    let mut figs: Vec<(Figure, &str)> = Vec::new();
    // Fig. 3: a residue of the raw record and the thrust acceleration.
    figs.push((
        Figure::new("Fig. 3 — residue K0 and thrust acceleration (record as given)")
            .share_x()
            .panel(
                Panel::new("Residue K0", "time (s)", "K0 (deg/h)").series(Series::line(
                    "K0",
                    t_all.to_vec(),
                    raw[0].clone(),
                )),
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
                        crate::pipeline::signal(record, &thrust)?.to_vec(),
                    )
                    .colour(2),
                ),
            ),
        "fig3_residue_accel",
    ));
    // Fig. 5: processed acceleration and rate.
    let az_f = applied.prepared.signal_full(&thrust)?;
    figs.push((
        Figure::new(format!(
            "Fig. 5 — processed acceleration and rate (channel {show})"
        ))
        .share_x()
        .panel(
            Panel::new(
                format!("Processed {thrust}"),
                "time (s)",
                format!("{thrust} (g)"),
            )
            .series(Series::line(thrust.clone(), t_all.to_vec(), az_f).colour(2)),
        )
        .panel(
            Panel::new(
                format!("Processed rate output {show}"),
                "time (s)",
                format!("{show} (deg/h)"),
            )
            .series(Series::line(
                show.name(),
                t_all.to_vec(),
                applied.prepared.target_full(show).to_vec(),
            )),
        ),
        "fig5_processed",
    ));
    // Fig. 6: target and network output, training and validation.
    let y = applied.prepared.target(show);
    let p = &applied.predicted[show.index()];
    let fig6 = |rows: &[usize], title: &str| {
        Panel::new(title.to_string(), "time (s)", "rate error (deg/h)")
            .series(Series::line("target", rows_t(applied, rows), pick(y, rows)).colour(1))
            .series(Series::line("network output", rows_t(applied, rows), pick(p, rows)).colour(0))
    };
    figs.push((
        Figure::new(format!(
            "Fig. 6 — target and network output, channel {show}"
        ))
        .panel(fig6(train, "Training set"))
        .panel(fig6(val, "Validation set")),
        "fig6_network",
    ));
    // Fig. 6 for all channels, validation only.
    let mut all6 = Figure::new("Network output on the validation set, all channels").share_x();
    for ch in Channel::ALL {
        let y = applied.prepared.target(ch);
        let p = &applied.predicted[ch.index()];
        all6 = all6.panel(
            Panel::new(format!("Channel {ch}"), "time (s)", format!("{ch} (deg/h)"))
                .series(Series::line("target", rows_t(applied, val), pick(y, val)).colour(1))
                .series(
                    Series::line("network output", rows_t(applied, val), pick(p, val)).colour(0),
                ),
        );
    }
    figs.push((all6, "fig6_all_channels"));
    // Fig. 7: residues with and without compensation.
    let mut fig7 = Figure::new("Fig. 7 — residues with and without compensation").share_x();
    for r in Residue::ALL {
        let k = r.index();
        fig7 = fig7.panel(
            Panel::new(r.name(), "time (s)", format!("{} (deg/h)", r.name()))
                .series(
                    Series::line(
                        "without compensation",
                        applied.residues.t.clone(),
                        applied.residues.before[k].clone(),
                    )
                    .colour(1),
                )
                .series(
                    Series::line(
                        "with compensation",
                        applied.residues.t.clone(),
                        applied.residues.after[k].clone(),
                    )
                    .colour(0),
                ),
        );
    }
    figs.push((fig7, "fig7_residues"));
    // Residue spectra before and after, validation rows (at their own rate:
    // alternate rows of an interleaved split are two samples apart).
    let fs = 1.0 / record.dt();
    let fs_val = fs / crate::split::row_spacing(val) as f64;
    let mut spectra = Figure::new("Residue spectra on the validation rows");
    for r in Residue::ALL {
        let k = r.index();
        let b = pick(&applied.residues.before[k], val);
        let a = pick(&applied.residues.after[k], val);
        let seg = 512.min(b.len().next_power_of_two() / 2).max(8);
        if b.len() >= seg {
            let sb = nav_sensors::vibration::welch(&b, fs_val, seg);
            let sa = nav_sensors::vibration::welch(&a, fs_val, seg);
            spectra = spectra.panel(
                Panel::psd(r.name(), "PSD ((deg/h)²/Hz)")
                    .series(
                        Series::line("without compensation", sb.frequency_hz.clone(), sb.density)
                            .colour(1),
                    )
                    .series(
                        Series::line("with compensation", sa.frequency_hz, sa.density).colour(0),
                    ),
            );
        }
    }
    figs.push((spectra, "residue_spectra"));
    // Before/after bars.
    let stats = applied.validation_residues();
    let names: Vec<&str> = Residue::ALL.iter().map(|r| r.name()).collect();
    let mut bars = Figure::new("RMS on the validation rows").panel(
        BarChart::new("Residues", "rms (deg/h)", names.clone())
            .group_coloured(
                "without compensation",
                stats.iter().map(|s| s.rms_before).collect::<Vec<_>>(),
                1,
            )
            .group_coloured(
                "with compensation",
                stats.iter().map(|s| s.rms_after).collect::<Vec<_>>(),
                0,
            ),
    );
    let ch_names: Vec<&str> = Channel::ALL.iter().map(|c| c.name()).collect();
    let mut ch_bars = BarChart::new(
        "Channels: validation residual",
        "rms (deg/h)",
        ch_names.clone(),
    )
    // Colours as in Fig. 7: orange without compensation, blue with.
    .group_coloured(
        "bias only",
        scores
            .iter()
            .map(|s| s.val_rms_bias_only)
            .collect::<Vec<_>>(),
        1,
    );
    if let (Some(b), Some(bs)) = (&baseline, &base_scores) {
        ch_bars =
            ch_bars.group_coloured(b.label, bs.iter().map(|s| s.val_rms).collect::<Vec<_>>(), 2);
    }
    ch_bars = ch_bars.group_coloured(
        "this model",
        scores.iter().map(|s| s.val_rms).collect::<Vec<_>>(),
        0,
    );
    bars = bars.panel(ch_bars);
    figs.push((bars, "before_after"));

    let files = save_all(figs, dir)?;
    let f = |stem: &str| files.iter().find(|(s, _)| *s == stem).map(|(_, f)| f);

    // The page.
    let mut residue_table = Table::new([
        "residue",
        "rms before (deg/h)",
        "rms after (deg/h)",
        "reduction",
    ])
    .caption("Validation rows of the model's split.");
    for s in &stats {
        residue_table = residue_table.row([
            s.residue.name().to_string(),
            fmt(s.rms_before),
            fmt(s.rms_after),
            format!("{:.2}×", s.reduction),
        ]);
    }
    let mut ch_table = Table::new([
        "channel",
        "effects",
        "centres",
        "β (g)",
        "train rms",
        "val rms",
        "bias-only val rms",
        "val fit %",
    ]);
    for (c, s) in model.channels().iter().zip(&scores) {
        let eff: Vec<String> = c.effects().iter().map(|e| e.id()).collect();
        ch_table = ch_table.row([
            c.channel().name().to_string(),
            if eff.is_empty() {
                "—".into()
            } else {
                eff.join(", ")
            },
            c.n_centres().to_string(),
            fmt(c.width()),
            fmt(s.train_rms),
            fmt(s.val_rms),
            fmt(s.val_rms_bias_only),
            format!("{:.1}", s.val_fit_percent),
        ]);
    }
    let min_red = stats
        .iter()
        .map(|s| s.reduction)
        .fold(f64::INFINITY, f64::min);
    let max_red = stats.iter().map(|s| s.reduction).fold(0.0, f64::max);
    let mut page = HtmlReport::new("DTG vibration-error compensation")
        .summary(format!(
            "Record {} ({} samples at {} Hz); split {} ({} training, {} validation rows). Residue rms fell {:.2}× to {:.2}× on the validation rows.",
            source,
            record.len(),
            fmt(fs),
            model.split(),
            applied.train.len(),
            applied.val.len(),
            min_red,
            max_red
        ))
        .section(Section::new("Residues (eq. 6)").table(residue_table).figure(f("fig7_residues").expect("drawn"), "Fig. 7: residues with and without compensation.").figure(f("residue_spectra").expect("drawn"), "Residue spectra before and after, validation rows."))
        .section(Section::new("Channel models").text("Each channel: bias, the listed physical effects (linear) and a Gaussian RBF on the acceleration window; centres and width chosen by blocked cross-validation inside the training rows. RMS in deg/h.").table(ch_table));
    let mut before_after = Section::new("Before and after").figure(
        f("before_after").expect("drawn"),
        "Residue and channel rms on the validation rows.",
    );
    if let (Some(b), Some(bs)) = (&baseline, &base_scores) {
        let mut t = Table::new([
            "channel",
            format!("{} effects", b.label).as_str(),
            format!("{} val rms", b.label).as_str(),
            "this model's effects",
            "this model's val rms",
            "change",
        ]);
        for ((old, new), (old_s, new_s)) in b
            .model
            .channels()
            .iter()
            .zip(model.channels())
            .zip(bs.iter().zip(&scores))
        {
            let ids = |c: &crate::model::ChannelModel| {
                let e: Vec<String> = c.effects().iter().map(|e| e.id()).collect();
                if e.is_empty() {
                    "—".to_string()
                } else {
                    e.join(", ")
                }
            };
            t = t.row([
                new.channel().name().to_string(),
                ids(old),
                fmt(old_s.val_rms),
                ids(new),
                fmt(new_s.val_rms),
                format!("{:+.1}%", 100.0 * (new_s.val_rms / old_s.val_rms - 1.0)),
            ]);
        }
        before_after = before_after.table(t);
    }
    page = page.section(before_after).section(
        Section::new("The paper's figures")
            .figure(
                f("fig3_residue_accel").expect("drawn"),
                "Fig. 3: residue K0 and the thrust acceleration, record as given.",
            )
            .figure(
                f("fig5_processed").expect("drawn"),
                "Fig. 5: processed acceleration and rate output.",
            )
            .figure(
                f("fig6_network").expect("drawn"),
                "Fig. 6: target and network output on the training and validation sets.",
            )
            .figure(
                f("fig6_all_channels").expect("drawn"),
                "Network output on the validation set, all six channels.",
            ),
    );
    let index = page.write(dir)?;
    Ok(ReportSummary {
        index,
        residues: stats,
        channels: scores,
    })
}
