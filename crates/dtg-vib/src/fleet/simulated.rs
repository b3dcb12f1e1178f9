//! A simulated lot, to try the fleet commands on and to measure how often
//! "out of family" names a unit of a clean lot: units of one unit file,
//! each a tri-axial random-vibration test ([`Scenario::triaxial_hidden`]'s
//! shaker, its paper effects removed) with its own coefficient of one
//! rate-gyro effect drawn around the lot's value and hidden from its
//! ground calibration; some units given a value far from the lot's (out of
//! family), some a record with a column missing (broken). Writes the
//! units' files and `lot.toml`.

use nav_sensors::rate::RateTerm;
use nav_sensors::sim::{Scenario, UnitHiddenEffect, simulate_unit};
use nav_sensors::unit::Unit;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};
use std::path::{Path, PathBuf};

/// Why a lot could not be simulated.
#[derive(Debug, thiserror::Error)]
pub enum SimulatedLotError {
    /// The unit.
    #[error(transparent)]
    Unit(#[from] nav_sensors::unit::UnitError),
    /// The simulation.
    #[error(transparent)]
    Simulation(#[from] nav_sensors::sim::SimError),
    /// The design.
    #[error("{0}")]
    Design(String),
    /// A file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
}

/// What to simulate.
#[derive(Debug, Clone, PartialEq)]
pub struct LotDesign {
    /// The unit: a built-in name or a unit file.
    pub unit: String,
    /// How many units.
    pub units: usize,
    /// The gyro that carries the effect.
    pub channel: String,
    /// The rate-gyro effect (`g_y`, `gg_zz`, …).
    pub effect: String,
    /// The lot's value of the coefficient (the effect's unit).
    pub lot_value: f64,
    /// The unit-to-unit standard deviation of the coefficient.
    pub spread: f64,
    /// Units (by index) whose coefficient is this value instead of a draw.
    pub outliers: Vec<(usize, f64)>,
    /// Units (by index) whose record lacks this column.
    pub broken: Vec<(usize, String)>,
    /// Each test's length, s.
    pub duration_s: f64,
    /// The seed of the draws and of each unit's test (the unit's seed is `seed + index`).
    pub seed: u64,
    /// The manifest's `[options]` and `[spec]` lines, as TOML.
    pub manifest_tail: String,
}

/// One simulated unit.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulatedUnit {
    /// Its id.
    pub id: String,
    /// Its true coefficient.
    pub value: f64,
    /// Whether it was put out of family.
    pub outlier: bool,
    /// The column its record lacks, if broken.
    pub broken: Option<String>,
}

/// The lot written.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulatedLot {
    /// Its manifest.
    pub manifest: PathBuf,
    /// Its units.
    pub units: Vec<SimulatedUnit>,
}

/// The id of unit `k`.
pub fn id(k: usize) -> String {
    format!("SN{:04}", k + 1)
}

/// The test of one unit: the tri-axial shaker with `value` of the effect
/// on the channel, hidden from its calibration.
fn scenario(d: &LotDesign, k: usize, value: f64) -> Result<Scenario, SimulatedLotError> {
    let term: RateTerm = d
        .effect
        .parse()
        .map_err(|e| SimulatedLotError::Design(format!("effect '{}': {e}", d.effect)))?;
    let mut s = Scenario::triaxial_hidden();
    s.name = format!("lot unit {}", id(k));
    s.hidden.clear();
    s.duration_s = d.duration_s;
    s.seed = d.seed + k as u64;
    s.unit
        .rate
        .entry(d.channel.clone())
        .or_default()
        .set(term, value);
    s.unit.hidden.push(UnitHiddenEffect {
        channel: d.channel.clone(),
        term: d.effect.clone(),
    });
    Ok(s)
}

/// The CSV text without the column `name`.
fn without_column(csv: &str, name: &str) -> String {
    let col = csv
        .lines()
        .next()
        .and_then(|h| h.split(',').position(|c| c == name));
    let Some(col) = col else {
        return csv.to_string();
    };
    csv.lines()
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            let kept: Vec<&str> = cells
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != col)
                .map(|(_, c)| *c)
                .collect();
            kept.join(",") + "\n"
        })
        .collect()
}

/// Simulates the lot `d` into `dir`: `dir/SNxxxx/` per unit (record,
/// calibration, truth) and `dir/lot.toml`.
pub fn write(d: &LotDesign, dir: &Path) -> Result<SimulatedLot, SimulatedLotError> {
    let unit = Unit::resolve(&d.unit)?;
    let normal = Normal::new(d.lot_value, d.spread)
        .map_err(|e| SimulatedLotError::Design(format!("spread {}: {e}", d.spread)))?;
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(d.seed);
    let mut units = Vec::new();
    let mut toml = format!(
        "name = \"simulated lot of {} {} units\"\nunit = \"{}\"\n{}\n",
        d.units,
        unit.name().split(':').next().unwrap_or("").trim(),
        d.unit,
        d.manifest_tail
    );
    for k in 0..d.units {
        let drawn = normal.sample(&mut rng);
        let outlier = d.outliers.iter().find(|(i, _)| *i == k).map(|(_, v)| *v);
        let value = outlier.unwrap_or(drawn);
        let broken = d
            .broken
            .iter()
            .find(|(i, _)| *i == k)
            .map(|(_, c)| c.clone());
        let sim = simulate_unit(&unit, &scenario(d, k, value)?)?;
        let udir = dir.join(id(k));
        sim.write_dir(&udir)?;
        if let Some(c) = &broken {
            let path = udir.join("record.csv");
            let text = std::fs::read_to_string(&path).map_err(|source| SimulatedLotError::Io {
                path: path.clone(),
                source,
            })?;
            outfile::write_bytes(&path, without_column(&text, c))
                .map_err(|source| SimulatedLotError::Io { path, source })?;
        }
        toml.push_str(&format!(
            "\n[[entry]]\nid = \"{0}\"\ndata = [\"{0}/record.csv\"]\ncalib = \"{0}/calibration.json\"\n",
            id(k)
        ));
        units.push(SimulatedUnit {
            id: id(k),
            value,
            outlier: outlier.is_some(),
            broken,
        });
    }
    let manifest = dir.join("lot.toml");
    outfile::write_bytes(&manifest, toml).map_err(|source| SimulatedLotError::Io {
        path: manifest.clone(),
        source,
    })?;
    Ok(SimulatedLot { manifest, units })
}
