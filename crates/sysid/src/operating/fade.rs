//! The causal fade of the network part outside the training range: its
//! weights and hold, sample by sample. A model's prediction faded is
//! [`crate::Model::predict_faded`].
//!
//! A network knows only the conditions it was trained on; beyond them its
//! output is extrapolation, while the physical effects (bias and named
//! terms, with units and intervals) hold wherever their physics does. So
//! outside the [`TrainingRange`](super::range::TrainingRange) the network
//! part stops following its input (its variation fades to zero) and the
//! effects stay:
//!
//! `ŷ[n] = bias + Σ θⱼ zⱼ[n] + h[n] + w[n]·(rbf(x[n]) − h[n])`,
//!
//! with `w` the fade weight and `h` the held network part: while the weight
//! is 1, `h` follows the network by the weight's own one-pole
//! (`h ← h + α·(rbf − h)`, a window's average of it), and below 1 it stays.
//! Inside (`w = 1`) the prediction is the fitted model's, to the bit;
//! outside (`w = 0`) the network part is the average it gave over the last
//! window inside, so leaving the range adds no step; between, a cross-fade.
//! A record starts its hold from the network at rest: its mean over the
//! quietest tenth of the training windows
//! ([`TrainingRange::network_mean`](super::range::TrainingRange::network_mean),
//! [`rest_rows`]).
//!
//! Why so (docs/campaign.md §6): the weight is a share of the network, not
//! a rate. A hold that moved toward the network by `w` every sample (as it
//! did) followed it within a few samples at any weight above a few per
//! cent, so a record just beyond the range held the network's
//! extrapolation there: on the campaign's x run the z run's model held the
//! network of the −6 dB level, which went the wrong way, and added 2.4% of
//! spread (3.2% on the y run). And a record that starts outside cannot
//! hold the network's mean over all training windows (an average over the
//! shaker's levels, several deg/h from what it says at rest: the flight's
//! pooled residue rms rose from 1.96 to 7.39 deg/h with the z run's model)
//! nor its first output (on a record far outside, extrapolation: −31.5
//! deg/h of offset on `triaxial_clean`, docs/dtg-vib.md).
//! The mean offset such a hold leaves is one the model cannot know: `check`
//! reports it beside the rms and calls the record outside.
//!
//! The weight is causal, as a flight computer needs it: from each window's
//! distance `d` outside the range (the window that ends at the row),
//! `w₀ = 1` up to the range's tolerance, falling as a smoothstep to 0 over
//! [`FadeSettings::width`] more scales, then smoothed by a one-pole
//! low-pass of time constant [`FadeSettings::time_constant_s`] that starts
//! at the first window's own weight: `w[n] = w[n−1] + α·(w₀[n] − w[n−1])`,
//! `α = 1 − exp(−Δt/τ)`, taking `w₀[n]` once within [`SNAP`] of it; toward
//! a lower weight the gain is [`FadeSettings::fall_alpha`] (1 for a model
//! fitted now: the weight falls at once and comes back by τ). The
//! onboard evaluator and the exported C compute the same, in the same order.

pub use super::fade_settings::{FADE_WIDTH, FadeSettings};
use super::range::{TrainingRange, statistics};
use crate::error::SysidError;
use crate::prepared::Prepared;
use crate::sensor::Sensor;

/// The weight of a window at distance `d` outside a range of tolerance
/// `tolerance`, before smoothing: 1 inside, a smoothstep down to 0 at
/// `tolerance + width`.
///
/// ```
/// use sysid::operating::fade::raw_weight;
/// assert_eq!(raw_weight(0.5, 1.0, 2.0), 1.0);
/// assert_eq!(raw_weight(2.0, 1.0, 2.0), 0.5);
/// assert_eq!(raw_weight(9.0, 1.0, 2.0), 0.0);
/// ```
pub fn raw_weight(d: f64, tolerance: f64, width: f64) -> f64 {
    if d <= tolerance {
        return 1.0;
    }
    let u = ((d - tolerance) / width.max(f64::MIN_POSITIVE)).min(1.0);
    1.0 - u * u * (3.0 - 2.0 * u)
}

/// The one-pole smoother of the weight, sample by sample: gain `alpha`
/// toward a higher weight, `fall` toward a lower one.
#[derive(Debug, Clone, Copy)]
pub struct Smoother {
    alpha: f64,
    fall: f64,
    state: Option<f64>,
}

impl Smoother {
    /// A smoother of gains `alpha` ([`FadeSettings::alpha`]) and `fall`
    /// ([`FadeSettings::fall_alpha`]) at rest.
    pub fn new(alpha: f64, fall: f64) -> Self {
        Self {
            alpha,
            fall,
            state: None,
        }
    }

    /// The smoothed weight after `w0`; the first starts at `w0` itself, and
    /// a weight within [`SNAP`] of `w0` becomes `w0` (a one-pole only
    /// approaches its input: back inside, the model is again the fitted one,
    /// to the bit).
    pub fn step(&mut self, w0: f64) -> f64 {
        let w = match self.state {
            None => w0,
            Some(w) => {
                let gain = if w0 < w { self.fall } else { self.alpha };
                snap(w + gain * (w0 - w), w0)
            }
        };
        self.state = Some(w);
        w
    }
}

/// How close the smoothed weight must come to its input to take it.
pub const SNAP: f64 = 1e-9;

/// `w`, or `w0` when within [`SNAP`] of it.
#[inline]
pub fn snap(w: f64, w0: f64) -> f64 {
    if (w0 - w).abs() <= SNAP { w0 } else { w }
}

/// Per row: the window's distance outside the range and the fade weight.
#[derive(Debug, Clone, PartialEq)]
pub struct Weights {
    /// Distance outside the training range, in its scales.
    pub distance: Vec<f64>,
    /// Smoothed weight of the network part, 0 to 1.
    pub weight: Vec<f64>,
}

/// The fade weights of `range` (a model's, fitted at `dt_s`) on prepared
/// data: each record of several restarts the smoother. The range must fit
/// the sensor ([`TrainingRange::check`]).
pub fn weights<S: Sensor>(
    range: &TrainingRange,
    prepared: &Prepared<S>,
    dt_s: f64,
) -> Result<Weights, SysidError> {
    let rows: Vec<usize> = (0..prepared.rows()).collect();
    let distance = range.distances(&statistics(prepared, range.window, &rows)?);
    let (alpha, fall) = (range.fade.alpha(dt_s), range.fade.fall_alpha(dt_s));
    let mut weight = Vec::with_capacity(distance.len());
    for (_, part) in prepared.record_rows() {
        let mut s = Smoother::new(alpha, fall);
        weight.extend(
            distance[part]
                .iter()
                .map(|&d| s.step(raw_weight(d, range.tolerance, range.fade.width))),
        );
    }
    Ok(Weights { distance, weight })
}

/// One record's prediction `p` with its network part `r` faded by the
/// weights `w` (the hold starting at `c` and following the network by
/// `alpha` while the weight is 1): `p − r + ` [`held_series`]; exactly `p`
/// where `w = 1`.
///
/// ```
/// let p = [10.0, 11.0, 12.0];
/// let r = [1.0, 2.0, 3.0]; // the network's share of p
/// let out = sysid::operating::fade::fade_series(&p, &r, 0.5, &[1.0, 0.0, 0.0], 1.0);
/// assert_eq!(out, [10.0, 10.0, 10.0]); // outside, the network holds its last value
/// ```
pub fn fade_series(p: &[f64], r: &[f64], c: f64, w: &[f64], alpha: f64) -> Vec<f64> {
    p.iter()
        .zip(r)
        .zip(held_series(r, c, w, alpha))
        .map(|((p, r), h)| p - (r - h))
        .collect()
}

/// One record's faded network part: the network `r` itself where the
/// weight `w` is 1, else the cross-fade `h + w·(r − h)` of the held part
/// `h` (starting at `c`, following `r` by the one-pole gain `alpha` while
/// the weight is 1, frozen below) toward the network.
///
/// ```
/// let f = sysid::operating::fade::held_series(&[1.0, 3.0, 5.0, 2.0], 1.0, &[1.0, 1.0, 0.0, 0.5], 0.5);
/// // Inside the network itself, the hold half way from 1 to 3; then held.
/// assert_eq!(f, [1.0, 3.0, 2.0, 2.0]);
/// ```
pub fn held_series(r: &[f64], c: f64, w: &[f64], alpha: f64) -> Vec<f64> {
    let mut h = c;
    r.iter()
        .zip(w)
        .map(|(&r, &w)| {
            let out;
            (h, out) = hold(h, r, w, alpha);
            out
        })
        .collect()
}

/// One sample of the fade of the network part `r` at weight `w`, from the
/// held part `h`: the next held part and the faded network part. At full
/// weight the output is `r` exactly and the hold follows it by `alpha`;
/// below, the hold stays and the output cross-fades.
///
/// ```
/// use sysid::operating::fade::hold;
/// assert_eq!(hold(0.0, 2.0, 1.0, 0.25), (0.5, 2.0));
/// assert_eq!(hold(0.5, 2.0, 0.5, 0.25), (0.5, 1.25));
/// ```
#[inline]
pub fn hold(h: f64, r: f64, w: f64, alpha: f64) -> (f64, f64) {
    if w >= 1.0 {
        (h + alpha * (r - h), r)
    } else {
        (h, h + w * (r - h))
    }
}

/// Share of the training windows, the quietest, over which the network's
/// value at rest is averaged.
pub const REST_SHARE: f64 = 0.1;

/// The quietest [`REST_SHARE`] of rows `rows` (windows of `length`
/// samples): those with the smallest summed variance of the operating
/// signals, in row order; at least one.
pub fn rest_rows<S: Sensor>(
    prepared: &Prepared<S>,
    length: usize,
    rows: &[usize],
) -> Result<Vec<usize>, SysidError> {
    let k = prepared.sensor().operating_signals().len();
    let stats = statistics(prepared, length, rows)?;
    let level = |s: &Vec<f64>| s[k..2 * k].iter().map(|l| l * l).sum::<f64>();
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by(|&a, &b| level(&stats[a]).total_cmp(&level(&stats[b])));
    let n = ((rows.len() as f64 * REST_SHARE).ceil() as usize).clamp(1, rows.len().max(1));
    let mut rest: Vec<usize> = order.into_iter().take(n).map(|i| rows[i]).collect();
    rest.sort_unstable();
    Ok(rest)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smoothed_weight_starts_at_its_input_and_snaps_back_to_one() {
        let f = FadeSettings {
            fall_time_constant_s: None,
            ..FadeSettings::for_window(50, 0.02)
        };
        let mut s = Smoother::new(f.alpha(0.02), f.fall_alpha(0.02));
        assert_eq!(s.step(0.0), 0.0);
        let w: Vec<f64> = (0..2000).map(|_| s.step(1.0)).collect();
        assert!(w[0] > 0.0 && w[0] < 0.05, "{}", w[0]);
        assert!(w.windows(2).all(|p| p[1] >= p[0]), "monotone");
        assert_eq!(*w.last().unwrap(), 1.0, "exactly the fitted model again");
    }

    #[test]
    fn the_weight_falls_at_once_and_comes_back_by_its_time_constant() {
        let f = FadeSettings::for_window(50, 0.02);
        let mut s = Smoother::new(f.alpha(0.02), f.fall_alpha(0.02));
        assert_eq!(s.step(1.0), 1.0);
        assert_eq!(s.step(0.2), 0.2, "down at once");
        let up = s.step(1.0);
        assert!(up > 0.2 && up < 0.25, "{up}");
    }

    #[test]
    fn outside_the_network_part_holds_and_inside_it_is_untouched() {
        let p = [5.0, 6.0, 7.0, 8.0];
        let r = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(fade_series(&p, &r, 0.0, &[1.0; 4], 1.0), p);
        // Half weight: half the network's move since the hold, which stays.
        let out = fade_series(&p, &r, 0.0, &[1.0, 0.5, 0.5, 0.0], 1.0);
        assert_eq!(out, [5.0, 5.5, 6.0, 5.0]);
        // A record that starts outside holds the network at rest, c.
        assert_eq!(
            fade_series(&p, &r, 0.25, &[0.0; 4], 1.0),
            [4.25, 4.25, 4.25, 4.25]
        );
    }

    /// A weight is a share of the network, not a rate: a record that stays
    /// just beyond the range (weight 0.1) keeps 10% of the network's move,
    /// however long it stays (the hold used to follow it all the way).
    #[test]
    fn a_small_weight_keeps_a_small_share_of_the_network() {
        let r: Vec<f64> = (0..1000).map(|i| if i < 10 { 0.0 } else { 10.0 }).collect();
        let w: Vec<f64> = (0..1000).map(|i| if i < 10 { 1.0 } else { 0.1 }).collect();
        let h = held_series(&r, 0.0, &w, 0.02);
        assert_eq!(h[..10], [0.0; 10]);
        assert!(
            h[10..].iter().all(|&v| (v - 1.0).abs() < 1e-12),
            "{:?}",
            &h[995..]
        );
    }
}
