//! Operating points: where in the space of test conditions each window of a
//! record sits, and how far a new record's windows are from those a model
//! was trained on.
//!
//! A window's operating point is the mean specific force along x, y and z
//! over its span (g: where gravity and steady acceleration put it) and its
//! vibration level (g rms: the root of the summed variances of the three
//! accelerations over the span). A network fitted on Z-axis shaker runs
//! knows nothing of a window whose gravity lies along x, or whose vibration
//! is three times stronger, however well it validated on its own record.
//!
//! The model keeps a strided sample of its training windows' points,
//! each coordinate divided by its spread over the training windows (at
//! least [`MIN_SCALE_G`]), and a reference distance: the 99th percentile of
//! its *validation* windows' distances to the nearest kept point — how far
//! data the model was validated on lie from what it was trained on. A new
//! window is **outside** when its distance to the nearest kept point
//! exceeds [`OUTSIDE_FACTOR`] times that reference (kiddo's k-d tree finds
//! it). The reference is measured, not assumed, so it holds whatever the
//! spacing of the training points.

use crate::error::DtgVibError;
use crate::pipeline::Prepared;
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use nav_sensors::geometry::Axis;
use serde::{Deserialize, Serialize};

/// The coordinates of an operating point, in order.
pub const FEATURES: [&str; 4] = ["mean_ax_g", "mean_ay_g", "mean_az_g", "vibration_g_rms"];

/// Smallest spread a coordinate is divided by, g: a coordinate the training
/// windows held constant (gravity along x in a Z-axis test) measures a
/// change of 0.05 g (a 3° tilt of gravity) as one unit, not as infinitely
/// many; an accelerometer bias that differs between two runs by a few mg
/// is not a new operating point.
pub const MIN_SCALE_G: f64 = 0.05;

/// Most training points a model keeps.
pub const MAX_POINTS: usize = 2000;

/// A window is outside the training range when its nearest training point
/// is farther than this many times the reference distance (the 99th
/// percentile of the validation windows' distances). Measured on records of
/// the training test's own profile (another seed) the share outside stays
/// under 5%; on a test that shakes along every axis it is close to 1
/// (tests/dtg_vib_records.rs, docs/dtg-vib.md).
pub const OUTSIDE_FACTOR: f64 = 1.5;

/// The operating point of the window of each row in `rows` (windows of
/// `length` samples).
///
/// ```
/// use dtg_vib::{operating::points, pipeline::{Prepared, Preprocess}};
/// use nav_sensors::sim::{simulate, Scenario};
/// let sim = simulate(&Scenario { duration_s: 4.0, ..Scenario::default() }).unwrap();
/// let prepared = Prepared::new(&sim.record, None, &Preprocess::default()).unwrap();
/// let p = points(&prepared, 50, &[0, 10]);
/// assert!((p[0][2] - 1.0).abs() < 0.1); // 1 g along z: the cluster sits level
/// assert!(p[0][3] > 0.0);
/// ```
pub fn points(prepared: &Prepared, length: usize, rows: &[usize]) -> Vec<[f64; 4]> {
    rows.iter()
        .map(|&r| {
            let (record, end) = prepared.locate(r);
            let span = end + 1 - length.min(end + 1)..=end;
            let n = span.clone().count() as f64;
            let mut p = [0.0; 4];
            let mut var = 0.0;
            for (k, axis) in Axis::ALL.into_iter().enumerate() {
                let a = &record.accel(axis)[span.clone()];
                let m = a.iter().sum::<f64>() / n;
                var += a.iter().map(|v| (v - m).powi(2)).sum::<f64>() / n;
                p[k] = m;
            }
            p[3] = var.sqrt();
            p
        })
        .collect()
}

/// The training operating points a model keeps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OperatingPoints {
    /// Names of the coordinates ([`FEATURES`]).
    pub features: Vec<String>,
    /// Each coordinate's divisor, g.
    pub scale: [f64; 4],
    /// Kept training points, scaled.
    pub points: Vec<[f64; 4]>,
    /// 99th percentile of the validation windows' distances to the kept
    /// points (scaled).
    pub reference_distance: f64,
}

impl OperatingPoints {
    /// Keeps the training windows' points (`train` rows), strided to at
    /// most [`MAX_POINTS`], and measures the reference distance on the
    /// validation rows `val`.
    pub fn from_training(
        prepared: &Prepared,
        length: usize,
        train: &[usize],
        val: &[usize],
    ) -> Result<Self, DtgVibError> {
        let all = points(prepared, length, train);
        let scale: [f64; 4] = std::array::from_fn(|k| {
            let n = all.len().max(1) as f64;
            let m = all.iter().map(|p| p[k]).sum::<f64>() / n;
            let sd = (all.iter().map(|p| (p[k] - m).powi(2)).sum::<f64>() / n).sqrt();
            sd.max(MIN_SCALE_G)
        });
        // Neighbouring windows share all but one sample: keep points half a
        // window apart at least, so the set is not thousands of near-copies.
        let stride = train.len().div_ceil(MAX_POINTS).max(length / 2).max(1);
        let kept: Vec<[f64; 4]> = all
            .iter()
            .step_by(stride)
            .map(|p| std::array::from_fn(|k| p[k] / scale[k]))
            .collect();
        if kept.is_empty() {
            return Err(DtgVibError::TooFewSamples {
                what: "training windows",
                have: 0,
                need: 1,
                hint: "use a longer record",
            });
        }
        let mut ops = Self {
            features: FEATURES.iter().map(|s| s.to_string()).collect(),
            scale,
            points: kept,
            reference_distance: 1.0,
        };
        let step = val.len().div_ceil(MAX_POINTS).max(1);
        let val: Vec<usize> = val.iter().step_by(step).copied().collect();
        let mut d = ops.relative_distances(&points(prepared, length, &val))?;
        d.sort_by(f64::total_cmp);
        let q99 = d.get(((d.len().max(1) - 1) as f64 * 0.99).round() as usize);
        // Validation windows on top of training ones (a constant test)
        // still leave a scale to compare with.
        ops.reference_distance = q99.copied().unwrap_or(1.0).max(1e-3);
        Ok(ops)
    }

    /// Each point's distance to the nearest kept training point (scaled),
    /// in units of [`OperatingPoints::reference_distance`] (outside above
    /// [`OUTSIDE_FACTOR`]).
    pub fn relative_distances(&self, points: &[[f64; 4]]) -> Result<Vec<f64>, DtgVibError> {
        let tree = tree(&self.points)?;
        Ok(points
            .iter()
            .map(|p| {
                let q: [f64; 4] = std::array::from_fn(|k| p[k] / self.scale[k]);
                tree.query(&q)
                    .nearest_one::<SquaredEuclidean<f64>>()
                    .execute()
                    .distance
                    .sqrt()
                    / self.reference_distance
            })
            .collect())
    }
}

fn tree(points: &[[f64; 4]]) -> Result<ImmutableKdTree<f64, 4>, DtgVibError> {
    ImmutableKdTree::new_from_slice(points)
        .map_err(|e| DtgVibError::OperatingPoints(format!("{} points: {e}", points.len())))
}
