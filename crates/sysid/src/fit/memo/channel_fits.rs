//! Channel fits remembered within a process, by what they are a function of.
//!
//! The explain loop fits the same channel on the same rows several times:
//! the refit with a suggested effect refits every channel although only the
//! one given the effect changed, and the refit's mirror fits again the
//! networks the baseline's mirror fitted. A channel's fit is a pure function
//! of its windows, target, effect columns, rows, settings and stored
//! coefficients (every random choice is seeded), so a fit asked again with
//! the same inputs is taken from here, bit for bit the one computed before.
//!
//! The key holds 128-bit digests of the arrays, not the arrays. Records of
//! more than [`MAX_ROWS`] rows are not remembered: hashing their windows
//! would cost time and nothing there is refitted.

use super::digest::{Digest, Digester};
use crate::error::SysidError;
use crate::fit::channel::ChannelFit;
use crate::inference::Coefficient;
use crate::prepared::Prepared;
use crate::recipe::FitSettings;
use crate::sensor::{Effect, Sensor};
use crate::split::leakage_gap;
use faer::{Mat, MatRef};
use std::collections::VecDeque;
use std::sync::Mutex;

/// Largest record (rows of windows) whose channel fits are remembered.
pub const MAX_ROWS: usize = 100_000;

/// Channel fits remembered; the oldest is dropped beyond this (the demo's
/// loop asks for about 50 distinct ones, each a few hundred kB at most).
const CAPACITY: usize = 96;

/// What every channel of one fit shares: the sensor type, the
/// pre-processing that made the windows (the smoother aside: it only
/// post-processes predictions), the windows themselves and the leakage gap;
/// with and without the windows the effects are partialled out with.
///
/// A channel whose fit does not partial effects out (none, or their
/// coefficients given) never reads those windows, and its key leaves them
/// out: the demo's refit gives one channel an effect, so the statistics
/// input's fit then prepares the raw windows for it, and the five channels
/// without effects, keyed with them, were fitted again (2.5 s of 22 s of
/// network fits).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::fit) struct Records {
    windows: Digest,
    with_theta: Digest,
}

impl Records {
    /// `None` above [`MAX_ROWS`] rows.
    /// `x_theta` is what the effects are partialled out with (the raw
    /// windows, or `x` itself when no channel cross-fits).
    pub(in crate::fit) fn of<S: Sensor>(
        prepared: &Prepared<S>,
        (x, x_theta): (MatRef<'_, f64>, MatRef<'_, f64>),
    ) -> Option<Self> {
        if x.nrows() > MAX_ROWS {
            return None;
        }
        let mut d = Digester::new();
        d.text(std::any::type_name::<S>());
        let mut pre = prepared.preprocess().clone();
        pre.smoother = None;
        d.text(&format!("{pre:?}"));
        d.word(leakage_gap(prepared) as u64);
        d.word(prepared.first_sample() as u64);
        d.matrix(x);
        let windows = d.finish();
        d.matrix(x_theta);
        Some(Self {
            windows,
            with_theta: d.finish(),
        })
    }

    /// The digest a channel's key holds: the windows it partials its
    /// effects out with only when it does (effects without coefficients
    /// given for each).
    fn of_channel(&self, n_effects: usize, known: Option<&[Coefficient]>) -> Digest {
        let partials = n_effects > 0 && known.is_none_or(|c| c.len() != n_effects);
        match partials {
            true => self.with_theta,
            false => self.windows,
        }
    }
}

/// One channel fit's key: [`Records`] and everything of the channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::fit) struct Key(Digest, Digest);

struct Entry {
    key: Key,
    z: Mat<f64>,
    width: f64,
    model: rbf::RbfModel,
    coefficients: Vec<Coefficient>,
}

static FITS: Mutex<VecDeque<Entry>> = Mutex::new(VecDeque::new());

/// A channel fit's key (none when `records` is none) and the fit
/// remembered under it, if any: a fit asked again ([`crate::fit::batched`]) is
/// taken from here instead of computed.
pub(in crate::fit) fn recall<S: Sensor>(
    records: Option<Records>,
    prepared: &Prepared<S>,
    rows: (&[usize], &[usize], Option<&[Coefficient]>),
    channel: usize,
    effects: &[S::Effect],
    settings: &FitSettings,
) -> Result<(Option<Key>, Option<ChannelFit<S>>), SysidError> {
    let Some(records) = records else {
        return Ok((None, None));
    };
    let key = Key(
        records.of_channel(effects.len(), rows.2),
        channel_digest(prepared, rows, channel, effects, settings)?,
    );
    let found = lock().iter().find(|e| e.key == key).map(|e| ChannelFit {
        channel,
        effects: effects.to_vec(),
        z: e.z.clone(),
        width: e.width,
        model: e.model.clone(),
        coefficients: e.coefficients.clone(),
    });
    Ok((Some(key), found))
}

/// Remembers a channel fit under `key` (none: not remembered).
pub(in crate::fit) fn remember<S: Sensor>(key: Option<Key>, f: &ChannelFit<S>) {
    let Some(key) = key else {
        return;
    };
    let mut fits = lock();
    if !fits.iter().any(|e| e.key == key) {
        if fits.len() >= CAPACITY {
            fits.pop_front();
        }
        fits.push_back(Entry {
            key,
            z: f.z.clone(),
            width: f.width,
            model: f.model.clone(),
            coefficients: f.coefficients.clone(),
        });
    }
}

/// The store; a panic elsewhere while it was held leaves it usable (an
/// entry is pushed whole or not at all).
fn lock() -> std::sync::MutexGuard<'static, VecDeque<Entry>> {
    FITS.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn channel_digest<S: Sensor>(
    prepared: &Prepared<S>,
    (train, theta_rows, known): (&[usize], &[usize], Option<&[Coefficient]>),
    channel: usize,
    effects: &[S::Effect],
    settings: &FitSettings,
) -> Result<Digest, SysidError> {
    let mut d = Digester::new();
    d.word(channel as u64);
    d.f64s(prepared.target(channel).iter().copied());
    for e in effects {
        d.text(&e.id());
    }
    d.word(effects.len() as u64);
    if !effects.is_empty() {
        d.matrix(prepared.effect_matrix(channel, effects)?.as_ref());
    }
    d.usizes(train);
    d.usizes(theta_rows);
    d.text(&format!("{known:?}"));
    // The choice only says which inputs and smoothers a fit tries; the
    // channel fit reads the rest.
    let settings = FitSettings {
        choice: None,
        ..settings.clone()
    };
    d.text(&format!("{settings:?}"));
    Ok(d.finish())
}
