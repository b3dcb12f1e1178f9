//! The built-in scenarios. Their one source is the TOML files in the
//! workspace's `scenarios/` folder, embedded here at build time
//! (`include_str!`) and parsed when asked for, so the file a user copies
//! and edits is exactly what `--builtin NAME` runs (a test checks every
//! built-in parses and equals its file).
//!
//! Where the numbers come from (navigation-grade DTG and servo
//! accelerometer, uncompensated values before ground calibration):
//! - DTG bias 1–3 deg/h, scale-factor error 100–300 ppm, misalignment
//!   50–300 µrad, mass unbalance 0.3–2 deg/h/g: the uncompensated ranges
//!   Lawrence (Modern Inertial Technology, ch. on DTGs) gives for tuned
//!   gyros, which ground calibration brings to the noise level.
//! - Anisoelastic 0.02–0.2 deg/h/g²: the upper end of the DTG range, chosen
//!   so that, as in the paper's Fig. 3, the vibration-induced drift under
//!   6 g rms stands out from the noise (0.2 deg/h/g² × 36.7 g² ≈ 7 deg/h).
//! - Anisoinertia 0.01–0.03 deg/h/(deg/s)², temperature sensitivity
//!   0.02 deg/h/°C.
//! - Angle random walk 0.0007 deg/√h (a high-grade navigation DTG; a
//!   1 nmi/h-class INS needs ≲ 0.002), giving 0.30 deg/h rms at 50 Hz; bias
//!   instability 0.003 deg/h over 300 s.
//! - Spin 200 Hz (12,000 rpm), so 2N = 400 Hz lies in the NAVMAT flat band.
//! - Accelerometer K0 50–150 µg, K1 100–250 ppm, K2 10–25 µg/g², K3
//!   ≤ 2 µg/g³, misalignment ≤ 200 µrad, cross-coupling ≤ 20 µg/g² (the
//!   ranges of quartz-flexure servo accelerometers), noise 10 µg/√Hz, loop
//!   800 Hz with ζ = 0.7.

use super::scenario::Scenario;
use crate::vibration::PsdTable;

/// Every built-in scenario: its name and its TOML text, embedded from
/// `scenarios/NAME.toml`.
const BUILTIN_TOML: [(&str, &str); 9] = [
    (
        "paper_z_random",
        include_str!("../../../../scenarios/paper_z_random.toml"),
    ),
    (
        "triaxial_clean",
        include_str!("../../../../scenarios/triaxial_clean.toml"),
    ),
    (
        "triaxial_hidden",
        include_str!("../../../../scenarios/triaxial_hidden.toml"),
    ),
    ("demo", include_str!("../../../../scenarios/demo.toml")),
    // The test campaign (issue 12): the same unit and calibration along
    // three shaker axes, a sine sweep and a flight.
    ("x-axis", include_str!("../../../../scenarios/x-axis.toml")),
    ("y-axis", include_str!("../../../../scenarios/y-axis.toml")),
    ("z-axis", include_str!("../../../../scenarios/z-axis.toml")),
    (
        "sine-sweep",
        include_str!("../../../../scenarios/sine-sweep.toml"),
    ),
    ("flight", include_str!("../../../../scenarios/flight.toml")),
];

/// A low-frequency random profile for tri-axial tests (a long-stroke
/// multi-axis table): 3–5 Hz rising from 0.05 to 0.2 g²/Hz, flat to 15 Hz,
/// falling to 0.05 g²/Hz at 20 Hz; 1.66 g rms. Entirely below the 25-Hz
/// Nyquist frequency of 50-Hz outputs, so the vibration itself is visible
/// in the record, and slow against the 20-ms interval, so little of it
/// rectifies within an interval.
///
/// ```
/// let p = nav_sensors::sim::low_frequency_psd();
/// assert!((p.grms() - 1.66).abs() < 0.01);
/// assert_eq!(p.band_hz(), (3.0, 20.0));
/// ```
pub fn low_frequency_psd() -> PsdTable {
    PsdTable::new(vec![[3.0, 0.05], [5.0, 0.2], [15.0, 0.2], [20.0, 0.05]])
        .expect("valid built-in table")
}

impl Scenario {
    /// The paper's test: Z-axis NAVMAT P-9492 random vibration (6.06 g rms
    /// at 0 dB) for 100 s: shaker off for 5 s, then −6 dB for 25 s, 0 dB for
    /// 40 s and −3 dB for 30 s (2-s ramps, linear in dB); 5% and 3% cross-axis
    /// motion on x and y, slight fixture rocking, navigation-grade sensors,
    /// small calibration errors, no hidden effect. The vibration-induced drift
    /// (anisoelastic rectification) is 6–8 deg/h per channel at 0 dB against a
    /// 50-Hz noise floor of about 0.9 deg/h. `scenarios/paper_z_random.toml`.
    ///
    /// ```
    /// let s = nav_sensors::sim::Scenario::paper_z_random();
    /// assert_eq!((s.duration_s, s.internal_rate_hz, s.output_rate_hz), (100.0, 4000.0, 50.0));
    /// assert!(s.hidden.is_empty());
    /// ```
    pub fn paper_z_random() -> Self {
        Self::embedded("paper_z_random")
    }

    /// Tri-axial independent low-frequency random vibration at a constant
    /// level (1.66 g rms per axis, [`low_frequency_psd`]), so that the
    /// frame-resolved regressors a_I, a_O, a_S and their products are not
    /// collinear; a 6 °C temperature ramp; no temperature sensitivity and no
    /// hidden effect. The control case: a diagnosis must suggest nothing.
    /// `scenarios/triaxial_clean.toml`.
    ///
    /// ```
    /// let s = nav_sensors::sim::Scenario::triaxial_clean();
    /// assert_eq!(s.vibration.drives.len(), 3);
    /// assert!(s.hidden.is_empty());
    /// ```
    pub fn triaxial_clean() -> Self {
        Self::embedded("triaxial_clean")
    }

    /// As [`Scenario::triaxial_clean`] with two hidden effects: an
    /// anisoelastic `gg_IS` of 0.4 deg/h/g² on Y1 and a temperature
    /// sensitivity of 0.8 deg/h/°C on Z, both zeroed in the calibration.
    /// Both are several times what a real DTG shows, so that each
    /// contributes 3–5× the 50-Hz noise floor over 100 s.
    /// `scenarios/triaxial_hidden.toml`.
    ///
    /// ```
    /// let s = nav_sensors::sim::Scenario::triaxial_hidden();
    /// let ids: Vec<String> = s.hidden.iter().map(|h| format!("{}/{}", h.channel, h.term)).collect();
    /// assert_eq!(ids, ["Y1/gg_IS", "Z/temp"]);
    /// ```
    pub fn triaxial_hidden() -> Self {
        Self::embedded("triaxial_hidden")
    }

    /// The paper's test ([`Scenario::paper_z_random`]) with one effect hidden
    /// for the diagnosis loop to find: channel Y1's drift temperature
    /// sensitivity is 0.6 deg/h/°C (thirty times the other channels'), and
    /// the unit warms up from 22 °C toward 28 °C (60-s time constant), so Y1
    /// drifts by about 3 deg/h over the test. The levels step twice through
    /// −6, 0 and −3 dB, so that temperature and level are not confounded
    /// within either half of a blocked split. Temperature sensitivity is never part of a
    /// ground calibration; the record's `temp` column carries what a model
    /// needs. `dtg-vib demo` runs on this record. `scenarios/demo.toml`.
    ///
    /// ```
    /// use nav_sensors::{dtg::DtgTerm, geometry::Channel, sim::Scenario};
    /// let s = Scenario::demo();
    /// assert_eq!(s.hidden.len(), 1);
    /// assert_eq!((s.hidden[0].channel, s.hidden[0].term), (Channel::Y1, DtgTerm::Temp));
    /// assert_eq!(s.gyro(Channel::Y1).temp_deg_h_per_c, 0.6);
    /// ```
    pub fn demo() -> Self {
        Self::embedded("demo")
    }

    /// A built-in scenario by name (see [`Scenario::BUILTIN`]), parsed from
    /// its embedded TOML.
    ///
    /// ```
    /// assert!(nav_sensors::sim::Scenario::builtin("triaxial_hidden").is_some());
    /// assert!(nav_sensors::sim::Scenario::builtin("nope").is_none());
    /// ```
    pub fn builtin(name: &str) -> Option<Self> {
        Self::builtin_toml(name).map(|_| Self::embedded(name))
    }

    /// A built-in scenario's TOML text, as in `scenarios/NAME.toml`.
    ///
    /// ```
    /// let text = nav_sensors::sim::Scenario::builtin_toml("demo").unwrap();
    /// assert!(text.contains("name = \"demo\""));
    /// assert!(nav_sensors::sim::Scenario::builtin_toml("nope").is_none());
    /// ```
    pub fn builtin_toml(name: &str) -> Option<&'static str> {
        BUILTIN_TOML
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, text)| *text)
    }

    /// Names accepted by [`Scenario::builtin`].
    ///
    /// ```
    /// for name in nav_sensors::sim::Scenario::BUILTIN {
    ///     assert!(nav_sensors::sim::Scenario::builtin(name).is_some());
    /// }
    /// ```
    pub const BUILTIN: [&'static str; BUILTIN_TOML.len()] = {
        let mut names = [""; BUILTIN_TOML.len()];
        let mut i = 0;
        while i < names.len() {
            names[i] = BUILTIN_TOML[i].0;
            i += 1;
        }
        names
    };

    /// Parses an embedded built-in. The text is part of the program, not
    /// input: the tests parse and validate every one, so a failure here is
    /// a build that was never tested.
    #[track_caller]
    fn embedded(name: &str) -> Self {
        let text = Self::builtin_toml(name).expect("a built-in scenario's name");
        Self::from_toml(text, &format!("scenarios/{name}.toml"))
            .unwrap_or_else(|e| panic!("built-in scenario {name} does not parse: {e}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::simulate_unit;
    use crate::unit::Unit;

    fn scenarios_dir() -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios")
    }

    #[test]
    fn every_builtin_parses_validates_and_equals_its_file() {
        for name in Scenario::BUILTIN {
            let builtin = Scenario::builtin(name).expect("listed");
            builtin.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(builtin.name, name, "the file's name field is its name");
            let file = Scenario::load(scenarios_dir().join(format!("{name}.toml"))).unwrap();
            assert_eq!(file, builtin, "{name}");
        }
    }

    #[test]
    fn every_scenario_file_is_a_builtin() {
        let mut files: Vec<String> = std::fs::read_dir(scenarios_dir())
            .unwrap()
            .filter_map(|e| {
                let p = e.unwrap().path();
                (p.extension()? == "toml").then(|| p.file_stem().unwrap().to_string_lossy().into())
            })
            .collect();
        files.sort();
        let mut names: Vec<String> = Scenario::BUILTIN.iter().map(|n| n.to_string()).collect();
        names.sort();
        assert_eq!(files, names);
    }

    #[test]
    fn the_simulator_runs_what_the_file_says() {
        // What `--builtin NAME` runs and what `--scenario scenarios/NAME.toml`
        // runs are the same record, bit for bit (shortened for test time).
        for name in Scenario::BUILTIN {
            let short = |s: Scenario| Scenario {
                duration_s: 2.0,
                ..s
            };
            let file = Scenario::load(scenarios_dir().join(format!("{name}.toml"))).unwrap();
            let a =
                simulate_unit(&Unit::paper(), &short(Scenario::builtin(name).unwrap())).unwrap();
            let b = simulate_unit(&Unit::paper(), &short(file)).unwrap();
            assert_eq!(a.record, b.record, "{name}");
            assert_eq!(a.truth, b.truth, "{name}");
        }
    }
}
