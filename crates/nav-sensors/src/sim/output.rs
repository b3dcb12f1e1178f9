//! What a simulation returns, and writing it to a directory.

use std::path::Path;

use super::error::SimError;
use super::paper_truth::Truth;
use crate::files::paper_calibration::PaperCalibration;
use crate::files::record::Record;

/// Named per-sample series that explain a record (same time base):
/// `level_squared`, then per channel `{ch}_noise`, `{ch}_motion`,
/// `{ch}_unmodelled`, `{ch}_expected` (its expectation given the level),
/// `{ch}_predictable` (given the level and the 50-Hz accelerations),
/// `{ch}_floor` (noise + motion + unmodelled − predictable), and per hidden
/// effect `hidden_{ch}_{term}` (the part of the effect a model can see), deg/h.
///
/// ```
/// let mut c = nav_sensors::sim::Components::new(vec![0.02, 0.04]);
/// c.push("X_noise", vec![0.1, -0.1]);
/// assert_eq!(c.get("X_noise").unwrap(), &[0.1, -0.1]);
/// assert!(c.get("Y_noise").is_none());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Components {
    t: Vec<f64>,
    names: Vec<String>,
    columns: Vec<Vec<f64>>,
}

impl Components {
    /// Empty components on a time base, s.
    ///
    /// ```
    /// let c = nav_sensors::sim::Components::new(vec![0.02, 0.04]);
    /// assert!(c.names().is_empty());
    /// ```
    pub fn new(t: Vec<f64>) -> Self {
        Self {
            t,
            names: Vec::new(),
            columns: Vec::new(),
        }
    }

    /// Adds a named series.
    ///
    /// ```
    /// let mut c = nav_sensors::sim::Components::new(vec![0.02]);
    /// c.push("Z_noise", vec![0.3]);
    /// assert_eq!(c.names(), ["Z_noise"]);
    /// ```
    #[track_caller]
    pub fn push(&mut self, name: &str, values: Vec<f64>) {
        assert_eq!(values.len(), self.t.len(), "one value per sample");
        self.names.push(name.to_string());
        self.columns.push(values);
    }

    /// A series by name.
    ///
    /// ```
    /// let sim = nav_sensors::sim::simulate_unit(&nav_sensors::unit::Unit::paper(), &nav_sensors::sim::Scenario { duration_s: 1.0, ..Default::default() }).unwrap();
    /// assert_eq!(sim.components.get("Z_floor").unwrap().len(), 50);
    /// ```
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| n == name)
            .map(|k| self.columns[k].as_slice())
    }

    /// The series' names.
    ///
    /// ```
    /// let sim = nav_sensors::sim::simulate_unit(&nav_sensors::unit::Unit::paper(), &nav_sensors::sim::Scenario { duration_s: 1.0, ..Default::default() }).unwrap();
    /// assert_eq!(sim.components.names()[0], "level_squared");
    /// ```
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Writes `t` and every series as CSV.
    ///
    /// ```
    /// let mut c = nav_sensors::sim::Components::new(vec![0.02, 0.04]);
    /// c.push("X_noise", vec![0.1, -0.2]);
    /// let path = std::env::temp_dir().join("nav-sensors-doc-components.csv");
    /// c.write_csv(&path).unwrap();
    /// let t = tabular::Table::read(&path).unwrap();
    /// assert_eq!(t.numeric("X_noise").unwrap(), vec![0.1, -0.2]);
    /// ```
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<(), SimError> {
        let mut names: Vec<&str> = vec!["t"];
        names.extend(self.names.iter().map(String::as_str));
        let mut cols: Vec<&[f64]> = vec![&self.t];
        cols.extend(self.columns.iter().map(Vec::as_slice));
        tabular::write_csv(path, &names, &cols).map_err(crate::files::record::RecordError::from)?;
        Ok(())
    }
}

/// A simulation in the paper's file formats ([`crate::unit::FileFormat::Paper`],
/// what the built-in `paper` unit writes): the record, the calibration and
/// truth in the paper's shapes, and the per-sample components.
pub(crate) struct PaperFiles {
    pub(crate) record: Record,
    pub(crate) calibration: PaperCalibration,
    pub(crate) truth: Truth,
    pub(crate) components: Components,
}

impl PaperFiles {
    /// File names written by [`PaperFiles::write_dir`].
    pub(crate) const FILES: [&'static str; 5] = [
        "record.csv",
        "calibration.json",
        "truth.json",
        "components.csv",
        "scenario.toml",
    ];

    /// Writes `record.csv`, `calibration.json`, `truth.json`,
    /// `components.csv` and `scenario.toml` into `dir` (created if needed).
    pub(crate) fn write_dir(&self, dir: impl AsRef<Path>) -> Result<(), SimError> {
        let dir = dir.as_ref();
        let io = |path: &Path| {
            let path = path.display().to_string();
            move |source| SimError::Io { path, source }
        };
        // Nothing is written if a table holds a number no reader takes (a
        // scenario temperature of 1e308 used to write records of inf).
        let (names, cols) = self.record.columns();
        let record = dir.join("record.csv").display().to_string();
        let components = dir.join("components.csv").display().to_string();
        let mut comp_names: Vec<&str> = vec!["t"];
        comp_names.extend(self.components.names.iter().map(String::as_str));
        let mut comp_cols: Vec<&[f64]> = vec![&self.components.t];
        comp_cols.extend(self.components.columns.iter().map(Vec::as_slice));
        if let Some(e) = tabular::first_unwritable(&record, &names, &cols)
            .or_else(|| tabular::first_unwritable(&components, &comp_names, &comp_cols))
        {
            return Err(crate::files::record::RecordError::from(e).into());
        }
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        self.record.write_csv(dir.join("record.csv"))?;
        self.calibration.save(dir.join("calibration.json"))?;
        let truth = dir.join("truth.json");
        outfile::write_bytes(&truth, self.truth.to_json()).map_err(io(&truth))?;
        self.components.write_csv(dir.join("components.csv"))?;
        self.truth.scenario.save(dir.join("scenario.toml"))?;
        Ok(())
    }
}
