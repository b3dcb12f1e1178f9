//! The diagnosis of the paper's unit: the loop's diagnosis
//! ([`sysid::diagnose`]) by channel, and the unit's own part of it — which
//! vibration axis would tell two look-alike g-terms apart ([`separation`]).
//!
//! The loop layer that fits the mirror and the longer-window trial and
//! hands the diagnosis their predictions is [`crate::explain`].

pub(crate) mod separate;

pub use separate::{Separation, response, separation};
pub use sysid::diagnose::{
    Band, ChannelSeries, DiagnoseOptions, MIN_ENERGY_SHARE, NamedCheck, RankOptions,
    RecordCorrelation, RecordSeparation, Regime, RegimeBin, ResidualSpectrum, Response, Segment,
    Unexcited, p_text, rank, record_separations, regime, segments,
};

use crate::error::DtgVibError;
use crate::model::CompensationModel;
use crate::pipeline::Prepared;
use nav_sensors::geometry::{Axis, Channel};

/// Anisoinertia (rate-product) candidates are offered only when the angular
/// rate varies by more than this: see [`crate::effects::ANISOINERTIA_MIN_RATE_DEG_S`].
pub use crate::effects::ANISOINERTIA_MIN_RATE_DEG_S;

/// Everything found about one gyro channel.
pub type ChannelDiagnosis = sysid::diagnose::ChannelDiagnosis<Channel, Axis>;

/// The diagnosis of all six channels.
pub type Diagnosis = sysid::diagnose::Diagnosis<Channel, Axis>;

/// A candidate effect of a gyro channel, ranked.
pub type Candidate = sysid::diagnose::Candidate<Axis>;

/// A gyro channel's ranking.
pub type Ranking = sysid::diagnose::Ranking<Axis>;

/// Diagnoses `model` on the record(s) it was fitted on, `prepared` by
/// [`CompensationModel::prepare_many`], reading its predictions and those
/// of its `mirror` ([`crate::fit::mirror`]); see
/// [`sysid::diagnose::diagnose_prepared`].
pub fn diagnose_prepared(
    model: &CompensationModel,
    prepared: &Prepared,
    mirror: &CompensationModel,
    options: &DiagnoseOptions,
) -> Result<Diagnosis, DtgVibError> {
    Ok(sysid::diagnose::diagnose_prepared(
        model.inner(),
        prepared.inner(),
        mirror.inner(),
        options,
    )?)
}
