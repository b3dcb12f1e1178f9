//! When the diagnosis suggests an effect: the flags `diagnose` and `explain` share.

use crate::diagnose::DiagnoseOptions;
use clap::Args;

use super::parse::{parse_alpha, parse_gain};

/// When the diagnosis suggests an effect.
#[derive(Args, Clone, Copy)]
pub struct Thresholds {
    /// False-alarm level of a record: the chance, on a record with nothing
    /// missing, that any channel gets a suggestion (Bonferroni over channels and candidates).
    #[arg(long, default_value_t = 0.01, value_parser = parse_alpha)]
    alpha: f64,
    /// Worth threshold: suggest an effect only if adding it cuts the channel's residual rms by at least this fraction.
    #[arg(long = "min-gain", default_value_t = DiagnoseOptions::default().rank.min_rms_reduction, value_parser = parse_gain)]
    min_gain: f64,
}

impl Thresholds {
    pub fn options(self) -> DiagnoseOptions {
        let mut o = DiagnoseOptions::default();
        o.rank.alpha = self.alpha;
        o.rank.min_rms_reduction = self.min_gain;
        o
    }
}
