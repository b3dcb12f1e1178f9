//! The command line of `dtg-vib`: one module per subcommand, each with its
//! flags, its output (printed tables and `--json` structs) and the glue that
//! calls the library; the flags several subcommands share and the validators
//! of numeric flags in their own modules.
//!
//! | module | what |
//! |---|---|
//! | [`simulate`], [`fit`], [`compensate`], [`residues`], [`report`], [`check`], [`diagnose`], [`explain`], [`allan`], [`export`], [`demo`] | the subcommands |
//! | [`terms`] | what the words the tables print mean, in a line under them |
//!
//! The flags a fit and a diagnosis share, the records as every command
//! reads them and each command's work are the library's
//! ([`dtg_vib::commands`]): the Python package calls the same functions.

pub mod allan;
pub mod check;
pub mod compensate;
pub mod demo;
pub mod diagnose;
pub mod explain;
pub mod export;
pub mod findings;
pub mod fit;
pub mod fleet;
pub mod report;
pub mod residues;
pub mod simulate;
pub mod terms;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "dtg-vib",
    version,
    about = "Identify and compensate vibration-induced DTG errors with RBF networks, and find what the model is missing"
)]
pub struct Cli {
    /// No progress display on stderr.
    #[arg(long, global = true)]
    pub quiet: bool,
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands; each one's doc comment is its line in `--help`.
#[derive(Subcommand)]
pub enum Command {
    /// Simulate a sensor-unit vibration test (default: the paper's Z-axis random test).
    Simulate(simulate::SimulateArgs),
    /// Fit every gyro channel's model on test records.
    // Negative numbers are values here: a southern latitude (--earth-rate -33.9),
    // a table turning backwards (--table-rate -1,0,0).
    #[command(allow_negative_numbers = true)]
    Fit(Box<dtg_vib::commands::fit_args::FitArgs>),
    /// Write the record compensated by a model.
    Compensate(compensate::CompensateArgs),
    /// Write the parity residues (the paper's K0..K5 of eq. 6; P0.. of another unit), with a model the compensated ones, and test them for a fault.
    Residues(residues::ResiduesArgs),
    /// Write the figures and index.html of a model on a record.
    Report(report::ReportArgs),
    /// Does a model hold on a record it was not fitted on? Rms before and
    /// after, residues, and the share of windows outside the training range.
    ///
    /// Per channel, deg/h: rms before, the output's rms about its mean (what
    /// the best constant correction leaves); rms after, of output − model
    /// about zero; mean after and spread after, its mean and its rms about
    /// the mean (rms after² = mean after² + spread after²: compare spread
    /// after with rms before); fit %, 100·(1 − rms after / rms before), below
    /// 0 when the model does worse than the mean; inside and outside, rms
    /// after on the windows inside and outside the training range. A window
    /// is outside when its nearest training point lies farther than 1.5
    /// reference distances, the distance within which 99% of the model's own
    /// validation windows lie. The parity residues (K0..K5 for the paper's
    /// unit) follow, before and after about zero, how many times better or
    /// worse, and pooled: the rms of them all together.
    Check(check::CheckArgs),
    /// Find what a model is missing: compare, locate failures, rank candidate effects.
    Diagnose(diagnose::DiagnoseArgs),
    /// The whole loop: fit, diagnose, add every suggested effect, refit, until nothing new is suggested.
    #[command(allow_negative_numbers = true)]
    Explain(Box<explain::ExplainArgs>),
    /// Overlapping Allan deviation and IEEE 952 noise terms of every channel and residue, before and after a model.
    Allan(allan::AllanArgs),
    /// Export a causal model for onboard use: C99 sources and tables (--lang c), or equations (--lang text).
    Export(export::ExportArgs),
    /// The main job on a built-in default: simulate, fit, compensate, report, diagnose, refit.
    Demo(demo::DemoArgs),
    /// A lot of units: one unit's task, every task here, a Slurm or Kubernetes plan, the lot's summary.
    Fleet(fleet::FleetArgs),
}
