//! The diagnosis by channel: the loop's diagnosis ([`sysid::diagnose`])
//! and the part the units share — which vibration axis would tell two
//! look-alike g-terms apart (the advice the unit plug-in gives,
//! [`crate::unit_sensor::response`]).
//!
//! The loop layer that fits the mirror and the longer-window trial and
//! hands the diagnosis their predictions is [`sysid::explain`].

pub(crate) mod separate;

pub use separate::Separation;
pub use sysid::diagnose::{
    Band, ChannelSeries, DiagnoseOptions, MIN_ENERGY_SHARE, NamedCheck, RankOptions,
    RecordCorrelation, RecordSeparation, Regime, RegimeBin, ResidualSpectrum, Response, Segment,
    Unexcited, p_text, rank, record_separations, regime, segments,
};

use nav_sensors::geometry::{Axis, Channel};

/// Anisoinertia (rate-product) candidates are offered only when the angular
/// rate varies by more than this: see [`crate::unit_sensor::ANISOINERTIA_MIN_RATE_DEG_S`].
pub use crate::unit_sensor::ANISOINERTIA_MIN_RATE_DEG_S;

/// Everything found about one gyro channel.
pub type ChannelDiagnosis = sysid::diagnose::ChannelDiagnosis<Channel, Axis>;

/// The diagnosis of all six channels.
pub type Diagnosis = sysid::diagnose::Diagnosis<Channel, Axis>;

/// A candidate effect of a gyro channel, ranked.
pub type Candidate = sysid::diagnose::Candidate<Axis>;

/// A gyro channel's ranking.
pub type Ranking = sysid::diagnose::Ranking<Axis>;
