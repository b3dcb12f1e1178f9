//! Windowed inputs: each sample's input vector is the last `length` samples
//! of one or more signals, as the paper feeds the RBF network a window of 50
//! thrust-axis acceleration samples.
//!
//! Windows end at the sample they belong to (causal), so a fitted model can
//! run on-line: the compensation of sample t uses accelerations up to t only.
//!
//! Which signals a window reads is named, or chosen from the training
//! records among the sensor's operating signals ([`WindowSignals::Auto`],
//! the default: [`signal_choice`]). A model's window always names them.

pub mod signal_choice;

use faer::MatRef;
use serde::{Deserialize, Serialize};

/// Why windows could not be formed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WindowError {
    /// A window of zero samples was asked for.
    #[error("a window needs at least one sample")]
    ZeroLength,
    /// No signal to window.
    #[error("a window needs at least one input signal")]
    NoSignals,
    /// The window's signals are still to be chosen from the records
    /// ([`WindowSignals::Auto`]): only prepared records choose them.
    #[error(
        "the window's signals are still to be chosen (auto): prepare the records with the sensor (sysid::Prepared), which chooses them"
    )]
    Unchosen,
    /// The record is shorter than one window.
    #[error(
        "the record has {samples} samples, fewer than one window of {length}: use a shorter window (--window) or a longer record"
    )]
    TooShort { samples: usize, length: usize },
}

/// Every name of `lists`, once, in the order first read (list by list,
/// each in its order): the signals some channel reads.
///
/// ```
/// let lists = [vec!["bx".to_string(), "az".into()], vec!["az".into(), "ax".into()]];
/// assert_eq!(sysid::window::union(&lists), ["bx", "az", "ax"]);
/// ```
pub fn union(lists: &[Vec<String>]) -> Vec<String> {
    let mut union: Vec<String> = Vec::new();
    for s in lists.iter().flatten() {
        if !union.contains(s) {
            union.push(s.clone());
        }
    }
    union
}

/// `names` in `order` (a sensor's order of its signals,
/// [`crate::Sensor::signal_order`]): those it holds in its order, then the
/// others as they come.
///
/// ```
/// let names = ["bz", "x", "az"].map(String::from).to_vec();
/// let order = ["ax", "az", "bx", "bz"].map(String::from);
/// assert_eq!(sysid::window::ordered(names, &order), ["az", "bz", "x"]);
/// ```
pub fn ordered(names: Vec<String>, order: &[String]) -> Vec<String> {
    let (known, other): (Vec<String>, Vec<String>) =
        names.into_iter().partition(|n| order.contains(n));
    order
        .iter()
        .filter(|o| known.contains(o))
        .cloned()
        .chain(other)
        .collect()
}

/// The signals a window reads: named, or chosen from the training records
/// ([`signal_choice`]) when the records are prepared.
///
/// In a file, a list of names or the word `auto`.
///
/// ```
/// use sysid::window::WindowSignals;
/// let auto: WindowSignals = serde_json::from_str(r#""auto""#).unwrap();
/// assert_eq!(auto, WindowSignals::Auto);
/// let named: WindowSignals = serde_json::from_str(r#"["ax", "az"]"#).unwrap();
/// assert_eq!(serde_json::to_string(&named).unwrap(), r#"["ax","az"]"#);
/// assert_eq!(serde_json::to_string(&auto).unwrap(), r#""auto""#);
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "SignalsInFile", into = "SignalsInFile")]
pub enum WindowSignals {
    /// Every operating signal that vibrates in some training record
    /// ([`signal_choice::choose_among`]).
    Auto,
    /// These signals, in this order.
    Named(Vec<String>),
}

/// [`WindowSignals`] as a file holds it.
#[derive(Clone, Serialize, Deserialize)]
#[serde(untagged)]
enum SignalsInFile {
    Auto(AutoWord),
    Named(Vec<String>),
}

/// The word `auto`.
#[derive(Clone, Serialize, Deserialize)]
enum AutoWord {
    #[serde(rename = "auto")]
    Auto,
}

impl From<SignalsInFile> for WindowSignals {
    fn from(f: SignalsInFile) -> Self {
        match f {
            SignalsInFile::Auto(_) => WindowSignals::Auto,
            SignalsInFile::Named(n) => WindowSignals::Named(n),
        }
    }
}

impl From<WindowSignals> for SignalsInFile {
    fn from(w: WindowSignals) -> Self {
        match w {
            WindowSignals::Auto => SignalsInFile::Auto(AutoWord::Auto),
            WindowSignals::Named(n) => SignalsInFile::Named(n),
        }
    }
}

/// How input windows are formed: `length` consecutive samples of each named
/// signal, concatenated signal by signal (oldest sample first).
///
/// ```
/// use sysid::window::WindowSpec;
/// let spec = WindowSpec::new(vec!["az".into()], 3).unwrap();
/// let az = [0.0, 1.0, 2.0, 3.0, 4.0];
/// let w = spec.build(&[&az]).unwrap();
/// assert_eq!(w.first_sample(), 2);           // the first full window ends at sample 2
/// assert_eq!(w.len(), 3);
/// assert_eq!(w.row(0), &[0.0, 1.0, 2.0]);
/// assert_eq!(w.row(2), &[2.0, 3.0, 4.0]);
/// ```
///
/// Channels may read windows of different signals (an inertial unit of
/// several IMUs: each gyro its own IMU's accelerometers): then
/// [`WindowSpec::signals`] is every signal some channel reads and
/// [`WindowSpec::signals_of`] one channel's. In a file the per-channel
/// lists are the key `channels`, written only when channels differ.
///
/// ```
/// use sysid::window::WindowSpec;
/// let order = ["ax", "bx", "by"].map(String::from);
/// let lists = vec![vec!["bx".into(), "by".into()], vec!["ax".into()], vec!["bx".into(), "by".into()]];
/// let w = WindowSpec::per_channel(lists, &order, 10).unwrap();
/// assert_eq!((w.signals(), w.signals_of(1)), (&order[..], &["ax".to_string()][..]));
/// assert_eq!(w.groups(3).iter().map(|(c, _)| c.clone()).collect::<Vec<_>>(), [vec![0, 2], vec![1]]);
/// // Every channel alike: the one shared list, as a window of named signals.
/// let same = WindowSpec::per_channel(vec![vec!["az".into()]; 3], &[], 10).unwrap();
/// assert_eq!(same, WindowSpec::new(vec!["az".into()], 10).unwrap());
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct WindowSpec {
    signals: WindowSignals,
    length: usize,
    /// Each channel's signals, in channel order, when they differ; empty
    /// when every channel reads [`WindowSpec::signals`] (absent in files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    channels: Vec<Vec<String>>,
}

impl WindowSpec {
    /// A window of `length` samples over the named signals (record columns,
    /// e.g. `az`).
    pub fn new(signals: Vec<String>, length: usize) -> Result<Self, WindowError> {
        if length == 0 {
            return Err(WindowError::ZeroLength);
        }
        if signals.is_empty() {
            return Err(WindowError::NoSignals);
        }
        Ok(Self {
            signals: WindowSignals::Named(signals),
            length,
            channels: Vec::new(),
        })
    }

    /// A window of `length` samples over each channel's own signals
    /// (`lists[k]`: channel k's). Every channel alike gives
    /// [`WindowSpec::new`] of their one list; otherwise
    /// [`WindowSpec::signals`] is every signal read, in `order` (the
    /// sensor's, [`crate::Sensor::signal_order`]; those it does not name
    /// after, in first-read order): each channel's list, itself in the
    /// sensor's order, is then in the order of the window's, as an onboard
    /// evaluator that feeds a channel its signals by a mask of the
    /// window's needs.
    pub fn per_channel(
        lists: Vec<Vec<String>>,
        order: &[String],
        length: usize,
    ) -> Result<Self, WindowError> {
        let Some(first) = lists.first() else {
            return Err(WindowError::NoSignals);
        };
        if lists.iter().all(|l| l == first) {
            return Self::new(first.clone(), length);
        }
        if lists.iter().any(Vec::is_empty) {
            return Err(WindowError::NoSignals);
        }
        let mut spec = Self::new(ordered(union(&lists), order), length)?;
        spec.channels = lists;
        Ok(spec)
    }

    /// The same signals (every channel's own) over `length` samples.
    pub fn with_length(&self, length: usize) -> Result<Self, WindowError> {
        if length == 0 {
            return Err(WindowError::ZeroLength);
        }
        Ok(Self {
            length,
            ..self.clone()
        })
    }

    /// Channel `channel`'s signals, in the order their samples appear in
    /// its windows.
    pub fn signals_of(&self, channel: usize) -> &[String] {
        self.channels
            .get(channel)
            .map_or_else(|| self.signals(), Vec::as_slice)
    }

    /// True when channels read different signals.
    pub fn is_per_channel(&self) -> bool {
        !self.channels.is_empty()
    }

    /// How many channels' lists the window names, when channels read
    /// different signals (`None` when every channel reads
    /// [`WindowSpec::signals`]).
    pub fn channel_lists(&self) -> Option<usize> {
        self.is_per_channel().then_some(self.channels.len())
    }

    /// The channels of `n` that read the same signals, each group with
    /// the window of its signals, in the order of their first channel:
    /// one group of every channel when they read alike.
    pub fn groups(&self, n: usize) -> Vec<(Vec<usize>, WindowSpec)> {
        let mut groups: Vec<(Vec<usize>, WindowSpec)> = Vec::new();
        for k in 0..n {
            let signals = self.signals_of(k);
            match groups.iter_mut().find(|(_, w)| w.signals() == signals) {
                Some((members, _)) => members.push(k),
                None => groups.push((vec![k], self.of_channel(k))),
            }
        }
        groups
    }

    /// Channel `channel`'s window: its signals alone, as every channel's.
    pub fn of_channel(&self, channel: usize) -> WindowSpec {
        Self {
            signals: match self.is_auto() {
                true => WindowSignals::Auto,
                false => WindowSignals::Named(self.signals_of(channel).to_vec()),
            },
            length: self.length,
            channels: Vec::new(),
        }
    }

    /// A window of `length` samples over the signals the training records
    /// choose ([`WindowSignals::Auto`]).
    ///
    /// ```
    /// let w = sysid::WindowSpec::auto(50).unwrap();
    /// assert!(w.is_auto() && w.signals().is_empty());
    /// ```
    pub fn auto(length: usize) -> Result<Self, WindowError> {
        if length == 0 {
            return Err(WindowError::ZeroLength);
        }
        Ok(Self {
            signals: WindowSignals::Auto,
            length,
            channels: Vec::new(),
        })
    }

    /// True until the records choose the signals ([`WindowSignals::Auto`]).
    pub fn is_auto(&self) -> bool {
        self.signals == WindowSignals::Auto
    }

    /// The signal names, in the order their samples appear in a window
    /// (none while [`WindowSpec::is_auto`]).
    pub fn signals(&self) -> &[String] {
        match &self.signals {
            WindowSignals::Auto => &[],
            WindowSignals::Named(n) => n,
        }
    }

    /// Samples per signal in one window.
    pub fn length(&self) -> usize {
        self.length
    }

    /// Input dimension: `length × number of signals`.
    pub fn dim(&self) -> usize {
        self.length * self.signals().len()
    }

    /// Channel `channel`'s input dimension: `length × its signals`.
    pub fn dim_of(&self, channel: usize) -> usize {
        self.length * self.signals_of(channel).len()
    }

    /// Forms every full window of the given signals (one slice per name in
    /// [`WindowSpec::signals`], all of the record's length).
    #[track_caller]
    pub fn build(&self, signals: &[&[f64]]) -> Result<Windows, WindowError> {
        if self.is_auto() {
            return Err(WindowError::Unchosen);
        }
        assert_eq!(
            signals.len(),
            self.signals().len(),
            "one slice per windowed signal"
        );
        let n = signals[0].len();
        assert!(
            signals.iter().all(|s| s.len() == n),
            "windowed signals differ in length"
        );
        if n < self.length {
            return Err(WindowError::TooShort {
                samples: n,
                length: self.length,
            });
        }
        let first = self.length - 1;
        let rows = n - first;
        let dim = self.dim();
        if let [one] = signals {
            // One signal: window i is samples i ..= i + length − 1 of it, so
            // the windows are read from the samples themselves (a 1M-sample
            // record's 50-sample windows: 8 MB, not 400 MB).
            return Ok(Windows {
                data: one.to_vec(),
                dim,
                first,
                step: 1,
                rows,
            });
        }
        let mut data = Vec::with_capacity(rows * dim);
        for end in first..n {
            for s in signals {
                data.extend_from_slice(&s[end + 1 - self.length..=end]);
            }
        }
        Ok(Windows {
            data,
            dim,
            first,
            step: dim,
            rows,
        })
    }
}

/// Windows by rows: row `i` belongs to record sample `first_sample() + i`.
///
/// The windows of one signal overlap and are read from its samples (nothing
/// is copied); those of several signals are written out row by row.
///
/// ```
/// use sysid::window::WindowSpec;
/// let spec = WindowSpec::new(vec!["ax".into(), "az".into()], 2).unwrap();
/// let w = spec.build(&[&[1.0, 2.0, 3.0], &[10.0, 20.0, 30.0]]).unwrap();
/// assert_eq!(w.dim(), 4);
/// assert_eq!(w.row(1), &[2.0, 3.0, 20.0, 30.0]);
/// assert_eq!(w.sample_of_row(1), 2);
/// ```
#[derive(Debug, Clone)]
pub struct Windows {
    /// One signal's samples, or every window written out.
    data: Vec<f64>,
    dim: usize,
    first: usize,
    /// Offset in `data` from one row's start to the next: 1 (one signal,
    /// overlapping rows) or `dim`.
    step: usize,
    rows: usize,
}

impl PartialEq for Windows {
    /// The same windows, however they are stored.
    fn eq(&self, other: &Self) -> bool {
        (self.dim, self.first, self.rows) == (other.dim, other.first, other.rows)
            && (0..self.rows).all(|i| self.row(i) == other.row(i))
    }
}

impl Windows {
    /// Number of windows.
    pub fn len(&self) -> usize {
        self.rows
    }

    /// True when there are no windows.
    pub fn is_empty(&self) -> bool {
        self.rows == 0
    }

    /// Input dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Record index of the sample the first window belongs to.
    pub fn first_sample(&self) -> usize {
        self.first
    }

    /// Record index of the sample window `row` belongs to.
    pub fn sample_of_row(&self, row: usize) -> usize {
        self.first + row
    }

    /// One window.
    ///
    /// # Panics
    /// If `i` is not below [`Windows::len`].
    #[track_caller]
    pub fn row(&self, i: usize) -> &[f64] {
        assert!(i < self.rows, "window {i} of {}", self.rows);
        &self.data[i * self.step..i * self.step + self.dim]
    }

    /// The windows as a `len() × dim()` matrix view of what they are read
    /// from: nothing is copied.
    ///
    /// ```
    /// use sysid::window::WindowSpec;
    /// let one = WindowSpec::new(vec!["az".into()], 3).unwrap().build(&[&[0.0, 1.0, 2.0, 3.0, 4.0]]).unwrap();
    /// let m = one.matrix();
    /// assert_eq!((m.nrows(), m.ncols(), m[(2, 0)], m[(2, 2)]), (3, 3, 2.0, 4.0));
    /// let two = WindowSpec::new(vec!["ax".into(), "az".into()], 2).unwrap()
    ///     .build(&[&[1.0, 2.0, 3.0], &[10.0, 20.0, 30.0]]).unwrap();
    /// assert_eq!(two.matrix()[(1, 3)], 30.0);
    /// ```
    pub fn matrix(&self) -> MatRef<'_, f64> {
        if self.rows == 0 {
            return MatRef::from_row_major_slice(&[], 0, self.dim);
        }
        // Element (i, j) is data[i·step + j]; the largest index read is
        // (rows − 1)·step + dim − 1 = data.len() − 1 for both layouts.
        assert!((self.rows - 1) * self.step + self.dim <= self.data.len());
        // SAFETY: every element the view reaches lies inside `data` (the
        // assertion above), `data` outlives the view, and the view is
        // read-only: overlapping rows (step 1) alias no mutable access.
        unsafe {
            MatRef::from_raw_parts(
                self.data.as_ptr(),
                self.rows,
                self.dim,
                self.step as isize,
                1,
            )
        }
    }

    /// Rows written out one after another (`rows × dim` values), row `i`
    /// belonging to sample `first + i`: the inputs of [`crate::ModelInput`]
    /// that are not the window itself.
    pub(crate) fn written(data: Vec<f64>, dim: usize, first: usize, rows: usize) -> Windows {
        assert_eq!(data.len(), rows * dim, "rows × dim values");
        Windows {
            data,
            dim,
            first,
            step: dim,
            rows,
        }
    }

    /// The windows of several records of the same spec, one after another:
    /// row `i` of the result is sample `first_sample() + i` of the records
    /// laid end to end with each later record's first `first_sample()`
    /// samples (its warm-up, which has no window) left out.
    ///
    /// ```
    /// use sysid::window::{WindowSpec, Windows};
    /// let spec = WindowSpec::new(vec!["az".into()], 2).unwrap();
    /// let a = spec.build(&[&[1.0, 2.0, 3.0]]).unwrap();
    /// let b = spec.build(&[&[7.0, 8.0]]).unwrap();
    /// let ab = Windows::concat(&[a, b]);
    /// assert_eq!((ab.len(), ab.row(2)), (3, &[7.0, 8.0][..]));
    /// ```
    #[track_caller]
    pub fn concat(parts: &[Windows]) -> Windows {
        let (dim, first) = (parts[0].dim, parts[0].first);
        assert!(
            parts.iter().all(|w| w.dim == dim && w.first == first),
            "windows of one spec"
        );
        // Written out: overlapping rows of different records cannot share
        // one run of samples (the rows across a boundary are not windows).
        let rows = parts.iter().map(Windows::len).sum();
        Windows {
            data: parts
                .iter()
                .flat_map(|w| (0..w.len()).flat_map(move |i| w.row(i).iter().copied()))
                .collect(),
            dim,
            first,
            step: dim,
            rows,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn too_short_record_is_an_error() {
        let spec = WindowSpec::new(vec!["az".into()], 50).unwrap();
        let az = vec![0.0; 49];
        assert_eq!(
            spec.build(&[&az]),
            Err(WindowError::TooShort {
                samples: 49,
                length: 50
            })
        );
        assert_eq!(spec.build(&[&vec![0.0; 50]]).unwrap().len(), 1);
    }

    #[test]
    fn validation_rules() {
        assert_eq!(
            WindowSpec::new(vec!["az".into()], 0),
            Err(WindowError::ZeroLength)
        );
        assert_eq!(WindowSpec::new(vec![], 5), Err(WindowError::NoSignals));
    }

    #[test]
    fn every_row_is_the_causal_history_of_its_sample() {
        let x: Vec<f64> = (0..200).map(|i| i as f64).collect();
        let spec = WindowSpec::new(vec!["x".into()], 7).unwrap();
        let w = spec.build(&[&x]).unwrap();
        for r in 0..w.len() {
            let t = w.sample_of_row(r);
            let expect: Vec<f64> = (t - 6..=t).map(|i| i as f64).collect();
            assert_eq!(w.row(r), expect.as_slice());
        }
    }
}
