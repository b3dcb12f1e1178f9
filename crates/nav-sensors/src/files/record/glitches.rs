//! Glitches of one sensor in a redundant unit's log: samples where a gyro
//! strays from what the other gyros say by far more than its own spread,
//! as a dropout resampled into the log or a transmission error does (the
//! real quadrotor flight `qdr_horizontal_path11.csv`: IMU 2's g2x ramps to
//! 42 deg/s off the others for two samples, twice).
//!
//! A gyro's parity-projected output (its output less the unit's
//! least-squares rate along its input axis: what the other gyros cannot
//! explain) is scored against its own median and robust spread (1.4826 ×
//! the median absolute deviation, σ for Gaussian noise). A sample beyond
//! [`GLITCH_Z`] robust σ starts a glitch, which takes in its neighbours
//! beyond [`GLITCH_NEIGHBOUR_Z`]. The motion does not enter (the projection
//! cancels any rate), so the screen holds on a moving record; a unit of
//! three gyros has no projection and no glitch.
//!
//! False alarms: on the two real flights' clean rows (10 510 rows × 9
//! gyros, with 3–5 m/s² of rotor vibration) no sample reaches 8 robust σ;
//! Gaussian noise reaches 10 σ with probability 2·10⁻²³.

use std::fmt;
use std::ops::Range;

use super::Record;
use crate::unit::Unit;

/// A glitch starts at a sample this many robust σ from the gyro's median.
pub const GLITCH_Z: f64 = 10.0;

/// A glitch takes in the adjacent samples beyond this many robust σ.
pub const GLITCH_NEIGHBOUR_Z: f64 = 5.0;

/// Samples of one gyro that stray from the others (see the module).
#[derive(Debug, Clone, PartialEq)]
pub struct Glitch {
    /// The gyro that best explains it.
    pub column: String,
    /// Every gyro that explains it as well as `column` does, `column`
    /// among them, in the unit's order: more than one where the unit can
    /// detect but not isolate (four gyros: every one of them), so the
    /// glitch is not pinned on one by rounding.
    pub candidates: Vec<String>,
    /// The samples, counted from the record's first (0).
    pub rows: Range<usize>,
    /// Their first and last time stamps, s.
    pub t_s: (f64, f64),
    /// The largest distance from the median, in robust σ.
    pub peak_z: f64,
}

impl fmt::Display for Glitch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let last = self.rows.end - 1;
        let rows = match self.rows.len() {
            1 => format!("row {}", self.rows.start),
            _ => format!("rows {}–{last}", self.rows.start),
        };
        let who = match self.candidates.as_slice() {
            [_] | [] => self.column.clone(),
            many => format!("one of {} (the unit cannot tell which)", many.join(", ")),
        };
        write!(
            f,
            "{who} {rows} (t {:.3}–{:.3} s, {:.1} σ)",
            self.t_s.0, self.t_s.1, self.peak_z
        )
    }
}

/// The glitches of `record` read with `unit`, by gyro then row. A sample
/// that strays on several gyros (a glitch on one enters every gyro's
/// projection, less on the others) is the glitch of the gyro that best
/// explains it: the largest deviation over the square root of the gyro's
/// diagonal of the projection (the fault-isolation rule of [`crate::fdi`]).
///
/// ```
/// use nav_sensors::record::{Record, glitches};
/// use nav_sensors::unit::Unit;
/// // Three aligned triads: a ±1 ripple on every gyro (out of step between
/// // triads), and g2x jumps by 100 at row 50.
/// let mut toml = String::from("name = \"three triads\"\n[units]\nrate = \"deg/s\"\nspecific_force = \"g\"\n");
/// for k in 1..=3 {
///     for (a, axis) in [("x", "[1.0, 0.0, 0.0]"), ("y", "[0.0, 1.0, 0.0]"), ("z", "[0.0, 0.0, 1.0]")] {
///         toml += &format!("[[gyro]]\nname = \"g{k}{a}\"\nmodel = \"rate\"\ninput = {axis}\n");
///     }
/// }
/// for (a, axis) in [("x", "[1.0, 0.0, 0.0]"), ("y", "[0.0, 1.0, 0.0]"), ("z", "[0.0, 0.0, 1.0]")] {
///     toml += &format!("[[accel]]\nname = \"a{a}\"\ninput = {axis}\n");
/// }
/// let unit = Unit::from_toml(&toml, "u.toml").unwrap();
/// let mut csv = format!("t,{},ax,ay,az\n", unit.gyro_names().join(","));
/// for i in 0..100 {
///     let g: Vec<String> = (0..9)
///         .map(|k| (if (i + k) % 2 == 0 { 1.0 } else { -1.0 }) + if i == 50 && k == 3 { 100.0 } else { 0.0 })
///         .map(|v: f64| v.to_string())
///         .collect();
///     csv += &format!("{},{},0,0,1\n", i as f64 * 0.01, g.join(","));
/// }
/// let rec = &Record::from_reader_with_unit(csv.as_bytes(), "l.csv", &unit).unwrap().records[0];
/// let g = glitches(&unit, rec);
/// assert_eq!(g.len(), 1, "{g:?}");
/// assert_eq!((g[0].column.as_str(), g[0].rows.clone()), ("g2x", 50..51));
/// ```
pub fn glitches(unit: &Unit, record: &Record) -> Vec<Glitch> {
    let (scores, deviations) = robust_scores(unit, record);
    let n = record.len();
    let t = record.t();
    let most = |i: usize| {
        (0..deviations.len())
            .max_by(|&a, &b| deviations[a][i].total_cmp(&deviations[b][i]))
            .unwrap_or(0)
    };
    let mut out = Vec::new();
    for (k, z) in scores.iter().enumerate() {
        let mut i = 0;
        while i < n {
            if z[i] <= GLITCH_Z || most(i) != k {
                i += 1;
                continue;
            }
            let mut start = i;
            while start > 0 && z[start - 1] > GLITCH_NEIGHBOUR_Z {
                start -= 1;
            }
            let mut end = i + 1;
            while end < n && z[end] > GLITCH_NEIGHBOUR_Z {
                end += 1;
            }
            // Ties within rounding: gyros the projection cannot tell apart.
            let best = deviations[k][i];
            let candidates = (0..deviations.len())
                .filter(|&j| deviations[j][i] >= best * (1.0 - 1e-9))
                .map(|j| unit.gyros()[j].name.clone())
                .collect();
            out.push(Glitch {
                column: unit.gyros()[k].name.clone(),
                candidates,
                rows: start..end,
                t_s: (t[start], t[end - 1]),
                peak_z: z[start..end].iter().copied().fold(0.0, f64::max),
            });
            i = end;
        }
    }
    out
}

/// Each gyro's score per sample, in robust σ from its median, of its
/// parity-projected output (see the module); zeros for a gyro the others
/// fully explain (a triad's). [`glitches`] starts a glitch beyond
/// [`GLITCH_Z`].
pub fn glitch_scores(unit: &Unit, record: &Record) -> Vec<Vec<f64>> {
    robust_scores(unit, record).0
}

/// Each gyro's distance from its median per sample, of its
/// parity-projected output: in robust σ (zeros for a gyro the others fully
/// explain, a triad's), and in deg/h over the square root of its diagonal
/// of the projection I − H·H⁺ (what isolates a glitch).
fn robust_scores(unit: &Unit, record: &Record) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let n = record.len();
    let gyros = unit.gyros();
    let rates: Vec<_> = (0..n)
        .map(|i| unit.least_squares_rate(&record.gyro_row(i)))
        .collect();
    let mut scores = Vec::with_capacity(gyros.len());
    let mut deviations = Vec::with_capacity(gyros.len());
    for (k, gyro) in gyros.iter().enumerate() {
        let m = record.gyro_at(k);
        let r: Vec<f64> = (0..n).map(|i| m[i] - gyro.input.dot(&rates[i])).collect();
        let median = super::time::median(&r);
        let dev: Vec<f64> = r.iter().map(|x| (x - median).abs()).collect();
        let sigma = 1.4826 * super::time::median(&dev);
        let scale = m.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let mut unit_k = vec![0.0; gyros.len()];
        unit_k[k] = 1.0;
        let diagonal = 1.0 - gyro.input.dot(&unit.least_squares_rate(&unit_k));
        if sigma <= 1e-12 * scale.max(1.0) || diagonal <= 1e-12 {
            scores.push(vec![0.0; n]);
            deviations.push(vec![0.0; n]);
            continue;
        }
        scores.push(dev.iter().map(|d| d / sigma).collect());
        deviations.push(dev.iter().map(|d| d / diagonal.sqrt()).collect());
    }
    (scores, deviations)
}
