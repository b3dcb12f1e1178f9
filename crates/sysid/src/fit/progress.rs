//! A fit's progress, for display.

/// Which stage of a fit is running, for progress display.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitStage<C> {
    /// Reading and pre-processing the records.
    Preparing,
    /// One channel's cross-validation and fit finished.
    ChannelDone(C),
}

/// A fit's progress callback.
pub type Progress<'a, C> = &'a (dyn Fn(FitStage<C>) + Sync);
