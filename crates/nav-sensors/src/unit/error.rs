//! Everything that can be wrong with a unit file. Every message is one line
//! that starts with the file and names the key (`gyro[2].input`), so a
//! script writing unit files can point at the line to fix.

/// What is wrong with a unit file (or a built-in unit's name).
///
/// ```
/// use nav_sensors::unit::{Unit, UnitError};
/// let text = "name = \"u\"\n[[gyro]]\nname = \"g\"\nmodel = \"rate\"\ninput = [0.0, 0.0, 0.0]\n";
/// let err = Unit::from_toml(text, "u.toml").unwrap_err();
/// assert!(matches!(err, UnitError::Axis { .. }));
/// assert_eq!(err.to_string(), "u.toml: gyro[0].input (g): the axis is zero; give a direction such as [0.0, 0.0, 1.0]");
/// ```
#[derive(Debug, thiserror::Error)]
pub enum UnitError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The TOML is malformed, has an unknown or missing key, or a value of
    /// the wrong type (the parser's message, with line and column).
    #[error("{file}:{line}:{column}: {message}")]
    Parse {
        /// The file.
        file: String,
        /// 1-based line (1 when the parser gives no position).
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// `--unit NAME` that is neither a built-in unit nor a `.toml` file.
    #[error("unknown unit '{given}' (built-in: {}; or give a FILE.toml)", valid.join(", "))]
    UnknownBuiltin {
        /// The name given.
        given: String,
        /// The built-in names.
        valid: Vec<&'static str>,
    },
    /// An empty sensor or column name.
    #[error("{file}: {key} is empty; give the record's column name")]
    EmptyName {
        /// The file.
        file: String,
        /// The key, e.g. `gyro[1].name`.
        key: String,
    },
    /// A zero or non-finite axis.
    #[error(
        "{file}: {key} ({name}): the axis is {problem}; give a direction such as [0.0, 0.0, 1.0]"
    )]
    Axis {
        /// The file.
        file: String,
        /// The key, e.g. `gyro[1].input`.
        key: String,
        /// The sensor's name.
        name: String,
        /// "zero" or "not finite".
        problem: &'static str,
    },
    /// A `dtg` gyro without its spin or output axis.
    #[error("{file}: {key} ({name}) is missing: a \"dtg\" gyro needs input, spin and output axes")]
    DtgAxisMissing {
        /// The file.
        file: String,
        /// The missing key, e.g. `gyro[0].spin`.
        key: String,
        /// The sensor's name.
        name: String,
    },
    /// A `rate` gyro given a spin or output axis.
    #[error(
        "{file}: {key} ({name}): only a \"dtg\" gyro has spin and output axes; remove it or set model = \"dtg\""
    )]
    RateAxisGiven {
        /// The file.
        file: String,
        /// The key given, e.g. `gyro[2].spin`.
        key: String,
        /// The sensor's name.
        name: String,
    },
    /// A `dtg` gyro's input, spin and output axes are not mutually
    /// perpendicular to [`PERPENDICULAR_TOLERANCE`](super::PERPENDICULAR_TOLERANCE).
    #[error(
        "{file}: {key} ({name}): {a} and {b} are not perpendicular (cosine {cosine:e}, tolerance 1e-6 after normalising)"
    )]
    NotPerpendicular {
        /// The file.
        file: String,
        /// The gyro's key, e.g. `gyro[0]`.
        key: String,
        /// The sensor's name.
        name: String,
        /// First axis key (`input`, `spin`).
        a: &'static str,
        /// Second axis key (`spin`, `output`).
        b: &'static str,
        /// The cosine of the angle between them after normalising.
        cosine: f64,
    },
    /// Two sensors (or a sensor and the time or temperature column) with one name.
    #[error("{file}: {key} = \"{name}\" is already {first}'s name; every column has one role")]
    DuplicateName {
        /// The file.
        file: String,
        /// The second key, e.g. `accel[0].name`.
        key: String,
        /// The name.
        name: String,
        /// The first key using it, e.g. `gyro[3]`.
        first: String,
    },
    /// Fewer than three gyros or accelerometers, or input axes that do not
    /// span three dimensions.
    #[error(
        "{file}: [[{key}]]: {count} {what} whose input axes span {rank} dimension(s); a unit needs at least three spanning all three"
    )]
    TooFew {
        /// The file.
        file: String,
        /// `gyro` or `accel`.
        key: &'static str,
        /// "gyros" or "accelerometers".
        what: &'static str,
        /// How many there are.
        count: usize,
        /// The dimension their input axes span.
        rank: usize,
    },
    /// `columns.time_scale` not positive and finite.
    #[error(
        "{file}: columns.time_scale = {value}: must be positive and finite (1 for seconds, 1e-6 for microseconds)"
    )]
    TimeScale {
        /// The file.
        file: String,
        /// The value given.
        value: f64,
    },
    /// A `[[residue]]` weight keyed by a name that is no gyro's.
    #[error("{file}: {key}: no such gyro (the unit's gyros: {})", gyros.join(", "))]
    ResidueGyro {
        /// The file.
        file: String,
        /// The key, e.g. `residue[0].weights.X2`.
        key: String,
        /// The unit's gyro names.
        gyros: Vec<String>,
    },
    /// A `[[residue]]` weight that is not finite.
    #[error("{file}: {key} = {value}: a weight must be finite")]
    ResidueWeight {
        /// The file.
        file: String,
        /// The key, e.g. `residue[0].weights.X`.
        key: String,
        /// The value given.
        value: f64,
    },
    /// A `[[residue]]` whose weights do not cancel the rate (not a parity
    /// residue: it would carry the unit's motion), or are all zero.
    #[error(
        "{file}: {key} ({name}): its weights do not cancel the rate (Σ weight·input axis = [{:e}, {:e}, {:e}] against Σ|weight| = {scale}; tolerance 1e-6 of it): a parity residue is a combination of the gyros that no rate enters",
        rate[0], rate[1], rate[2]
    )]
    ResidueSeesRate {
        /// The file.
        file: String,
        /// The residue's key, e.g. `residue[2]`.
        key: String,
        /// The residue's name.
        name: String,
        /// Σ weight·input axis.
        rate: [f64; 3],
        /// Σ |weight|.
        scale: f64,
    },
    /// Named residues that do not span the parity space.
    #[error(
        "{file}: [[residue]]: the named residues span {rank} of the unit's {needed} parity dimension(s); name residues spanning all of them, or none (then they are P0, P1, …)"
    )]
    ResiduesSpan {
        /// The file.
        file: String,
        /// The dimension the named residues span.
        rank: usize,
        /// n − 3.
        needed: usize,
    },
    /// An empty `imu` name.
    #[error("{file}: {key} is empty; name the IMU or leave the key out")]
    EmptyImu {
        /// The file.
        file: String,
        /// The key, e.g. `gyro[2].imu`.
        key: String,
    },
    /// A gyro's IMU without accelerometers spanning three dimensions.
    #[error(
        "{file}: {key} = \"{imu}\": IMU {imu} has {count} accelerometer(s) whose input axes span {rank} dimension(s); a gyro's IMU needs accelerometers spanning all three (give them imu = \"{imu}\"), or leave the gyro's imu out"
    )]
    ImuAccelerometers {
        /// The file.
        file: String,
        /// The gyro's key, e.g. `gyro[3].imu`.
        key: String,
        /// The IMU's name.
        imu: String,
        /// How many accelerometers the IMU has.
        count: usize,
        /// The dimension their input axes span.
        rank: usize,
    },
}
