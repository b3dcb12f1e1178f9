//! The unit file as written (the TOML contract) and its validation into a
//! [`Unit`]. The keys here are a user contract: tests and scripts outside
//! the project write such files, so a key is never renamed.

use std::collections::BTreeMap;

use nalgebra::{DMatrix, Vector3};
use serde::{Deserialize, Serialize};

use super::error::UnitError;
use super::{
    Accelerometer, Columns, Gyro, GyroModel, NamedResidue, PERPENDICULAR_TOLERANCE,
    RESIDUE_TOLERANCE, RateUnit, SpecificForceUnit, Unit, Units,
};

/// `[columns]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ColumnsFile {
    #[serde(default = "default_time")]
    pub time: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_scale: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<String>,
}

fn default_time() -> String {
    "t".to_string()
}

impl Default for ColumnsFile {
    fn default() -> Self {
        Self {
            time: default_time(),
            time_scale: None,
            temperature: None,
        }
    }
}

/// `[units]`: defaults are the units used inside (deg/h, g).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct UnitsFile {
    #[serde(default)]
    pub rate: RateUnit,
    #[serde(default)]
    pub specific_force: SpecificForceUnit,
}

/// The `model` key of a `[[gyro]]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum ModelName {
    Rate,
    Dtg,
}

/// One `[[gyro]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct GyroFile {
    pub name: String,
    pub model: ModelName,
    pub input: [f64; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub imu: Option<String>,
}

/// One `[[accel]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct AccelFile {
    pub name: String,
    pub input: [f64; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub imu: Option<String>,
}

/// One `[[residue]]`: a named parity residue, its weight on each gyro's
/// output by gyro name (a gyro not listed weighs zero).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ResidueFile {
    pub name: String,
    pub weights: BTreeMap<String, f64>,
}

/// The whole file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct UnitFile {
    pub name: String,
    #[serde(default)]
    pub columns: ColumnsFile,
    #[serde(default)]
    pub units: UnitsFile,
    #[serde(default)]
    pub gyro: Vec<GyroFile>,
    #[serde(default)]
    pub accel: Vec<AccelFile>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub residue: Vec<ResidueFile>,
}

impl UnitFile {
    /// Parses the TOML; errors carry the file, line and column on one line.
    pub fn parse(text: &str, file: &str) -> Result<Self, UnitError> {
        toml::from_str(text).map_err(|e| {
            let (line, column) = e
                .span()
                .map(|s| line_column(text, s.start))
                .unwrap_or((1, 1));
            UnitError::Parse {
                file: file.to_string(),
                line,
                column,
                message: e.message().trim().replace('\n', " "),
            }
        })
    }

    /// Checks every rule of the contract and builds the unit.
    pub fn validate(self, file: &str) -> Result<Unit, UnitError> {
        let f = file.to_string();
        let mut names: Vec<(String, String)> = Vec::new();
        let mut claim = |key: String, name: &str, owner: String| -> Result<(), UnitError> {
            if name.trim().is_empty() {
                return Err(UnitError::EmptyName {
                    file: f.clone(),
                    key,
                });
            }
            if let Some((_, first)) = names.iter().find(|(n, _)| n == name) {
                return Err(UnitError::DuplicateName {
                    file: f.clone(),
                    key,
                    name: name.to_string(),
                    first: first.clone(),
                });
            }
            names.push((name.to_string(), owner));
            Ok(())
        };
        claim(
            "columns.time".into(),
            &self.columns.time,
            "columns.time".into(),
        )?;
        if let Some(t) = &self.columns.temperature {
            claim(
                "columns.temperature".into(),
                t,
                "columns.temperature".into(),
            )?;
        }
        let time_scale = self.columns.time_scale.unwrap_or(1.0);
        if !(time_scale.is_finite() && time_scale > 0.0) {
            return Err(UnitError::TimeScale {
                file: f.clone(),
                value: time_scale,
            });
        }
        let mut gyros = Vec::with_capacity(self.gyro.len());
        for (k, g) in self.gyro.iter().enumerate() {
            claim(format!("gyro[{k}].name"), &g.name, format!("gyro[{k}]"))?;
            gyros.push(g.validate(file, k)?);
        }
        let mut accels = Vec::with_capacity(self.accel.len());
        for (k, a) in self.accel.iter().enumerate() {
            claim(format!("accel[{k}].name"), &a.name, format!("accel[{k}]"))?;
            accels.push(Accelerometer {
                name: a.name.clone(),
                input: axis(file, &format!("accel[{k}].input"), &a.name, a.input)?,
                imu: a.imu.clone(),
            });
        }
        for (k, r) in self.residue.iter().enumerate() {
            claim(
                format!("residue[{k}].name"),
                &r.name,
                format!("residue[{k}]"),
            )?;
        }
        for (key, what, axes) in [
            (
                "gyro",
                "gyros",
                gyros.iter().map(|g| g.input).collect::<Vec<_>>(),
            ),
            (
                "accel",
                "accelerometers",
                accels.iter().map(|a| a.input).collect(),
            ),
        ] {
            let rank = rank(&axes);
            if axes.len() < 3 || rank < 3 {
                return Err(UnitError::TooFew {
                    file: f.clone(),
                    key,
                    what,
                    count: axes.len(),
                    rank,
                });
            }
        }
        let imus = imus(file, &gyros, &accels)?;
        let residues = residues(file, &self.residue, &gyros)?;
        Ok(Unit::assemble(
            self.name,
            Columns {
                time: self.columns.time,
                time_scale,
                temperature: self.columns.temperature,
            },
            Units {
                rate: self.units.rate,
                specific_force: self.units.specific_force,
            },
            gyros,
            accels,
            residues,
            imus,
            file.to_string(),
        ))
    }
}

/// The `imu` keys checked: no empty name, and every IMU a gyro names has
/// accelerometers whose input axes span 3-D (its specific force is what
/// the gyro's model reads). Gives every IMU whose accelerometers span 3-D
/// with their indices, in order of first appearance.
fn imus(
    file: &str,
    gyros: &[Gyro],
    accels: &[Accelerometer],
) -> Result<Vec<(String, Vec<usize>)>, UnitError> {
    let keys = gyros
        .iter()
        .enumerate()
        .map(|(k, g)| (format!("gyro[{k}].imu"), &g.imu))
        .chain(
            accels
                .iter()
                .enumerate()
                .map(|(k, a)| (format!("accel[{k}].imu"), &a.imu)),
        );
    for (key, imu) in keys {
        if imu.as_ref().is_some_and(|n| n.trim().is_empty()) {
            return Err(UnitError::EmptyImu {
                file: file.to_string(),
                key,
            });
        }
    }
    let members = |imu: &String| -> Vec<usize> {
        (0..accels.len())
            .filter(|&k| accels[k].imu.as_ref() == Some(imu))
            .collect()
    };
    let span = |m: &[usize]| rank(&m.iter().map(|&k| accels[k].input).collect::<Vec<_>>());
    for (k, g) in gyros.iter().enumerate() {
        let Some(imu) = &g.imu else { continue };
        let m = members(imu);
        let rank = span(&m);
        if rank < 3 {
            return Err(UnitError::ImuAccelerometers {
                file: file.to_string(),
                key: format!("gyro[{k}].imu"),
                imu: imu.clone(),
                count: m.len(),
                rank,
            });
        }
    }
    let mut spanning: Vec<(String, Vec<usize>)> = Vec::new();
    for imu in accels.iter().filter_map(|a| a.imu.as_ref()) {
        let m = members(imu);
        if !spanning.iter().any(|(n, _)| n == imu) && span(&m) == 3 {
            spanning.push((imu.clone(), m));
        }
    }
    Ok(spanning)
}

/// The `[[residue]]` tables checked against the gyros: every weight names
/// a gyro and is finite, each residue cancels any rate (its weights lie in
/// H's left null space to [`RESIDUE_TOLERANCE`]), and together they span
/// the whole parity space (n − 3 dimensions), so no fault escapes them.
fn residues(
    file: &str,
    tables: &[ResidueFile],
    gyros: &[Gyro],
) -> Result<Vec<NamedResidue>, UnitError> {
    if tables.is_empty() {
        return Ok(Vec::new());
    }
    let mut out = Vec::with_capacity(tables.len());
    for (k, r) in tables.iter().enumerate() {
        let mut weights = vec![0.0; gyros.len()];
        for (gyro, &w) in &r.weights {
            let key = format!("residue[{k}].weights.{gyro}");
            let j = gyros.iter().position(|g| &g.name == gyro).ok_or_else(|| {
                UnitError::ResidueGyro {
                    file: file.to_string(),
                    key: key.clone(),
                    gyros: gyros.iter().map(|g| g.name.clone()).collect(),
                }
            })?;
            if !w.is_finite() {
                return Err(UnitError::ResidueWeight {
                    file: file.to_string(),
                    key,
                    value: w,
                });
            }
            weights[j] = w;
        }
        let scale: f64 = weights.iter().map(|w| w.abs()).sum();
        let rate: Vector3<f64> = gyros.iter().zip(&weights).map(|(g, w)| g.input * *w).sum();
        if scale == 0.0 || rate.amax() > RESIDUE_TOLERANCE * scale {
            return Err(UnitError::ResidueSeesRate {
                file: file.to_string(),
                key: format!("residue[{k}]"),
                name: r.name.clone(),
                rate: [rate.x, rate.y, rate.z],
                scale,
            });
        }
        out.push(NamedResidue {
            name: r.name.clone(),
            weights,
        });
    }
    let w = DMatrix::from_fn(out.len(), gyros.len(), |i, j| out[i].weights[j]);
    let sv = w.singular_values();
    let rank = sv.iter().filter(|s| **s > 1e-6 * sv.max()).count();
    let needed = gyros.len().saturating_sub(3);
    if rank != needed {
        return Err(UnitError::ResiduesSpan {
            file: file.to_string(),
            rank,
            needed,
        });
    }
    Ok(out)
}

impl GyroFile {
    /// Checks the axes the gyro's model needs (a rate gyro none but its
    /// input, a DTG three perpendicular ones) and builds the gyro; `k` is
    /// its position in the file, for the error's key.
    fn validate(&self, file: &str, k: usize) -> Result<Gyro, UnitError> {
        let g = self;
        let axis = |what: &str, v: [f64; 3]| axis(file, &format!("gyro[{k}].{what}"), &g.name, v);
        let input = axis("input", g.input)?;
        let model = match g.model {
            ModelName::Rate => {
                for (what, given) in [("spin", g.spin.is_some()), ("output", g.output.is_some())] {
                    if given {
                        return Err(UnitError::RateAxisGiven {
                            file: file.to_string(),
                            key: format!("gyro[{k}].{what}"),
                            name: g.name.clone(),
                        });
                    }
                }
                GyroModel::Rate
            }
            ModelName::Dtg => {
                let missing = |what: &str| UnitError::DtgAxisMissing {
                    file: file.to_string(),
                    key: format!("gyro[{k}].{what}"),
                    name: g.name.clone(),
                };
                let spin = axis("spin", g.spin.ok_or_else(|| missing("spin"))?)?;
                let output = axis("output", g.output.ok_or_else(|| missing("output"))?)?;
                for (a, va, b, vb) in [
                    ("input", &input, "spin", &spin),
                    ("input", &input, "output", &output),
                    ("spin", &spin, "output", &output),
                ] {
                    let cosine = va.dot(vb);
                    if cosine.abs() > PERPENDICULAR_TOLERANCE {
                        return Err(UnitError::NotPerpendicular {
                            file: file.to_string(),
                            key: format!("gyro[{k}]"),
                            name: g.name.clone(),
                            a,
                            b,
                            cosine,
                        });
                    }
                }
                GyroModel::Dtg { spin, output }
            }
        };
        Ok(Gyro {
            name: g.name.clone(),
            input,
            model,
            imu: g.imu.clone(),
        })
    }
}

impl From<&Unit> for UnitFile {
    fn from(u: &Unit) -> Self {
        let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
        UnitFile {
            name: u.name().to_string(),
            columns: ColumnsFile {
                time: u.columns().time.clone(),
                time_scale: (u.columns().time_scale != 1.0).then_some(u.columns().time_scale),
                temperature: u.columns().temperature.clone(),
            },
            units: UnitsFile {
                rate: u.units().rate,
                specific_force: u.units().specific_force,
            },
            gyro: u
                .gyros()
                .iter()
                .map(|g| {
                    let (model, spin, output) = match &g.model {
                        GyroModel::Rate => (ModelName::Rate, None, None),
                        GyroModel::Dtg { spin, output } => {
                            (ModelName::Dtg, Some(arr(spin)), Some(arr(output)))
                        }
                    };
                    GyroFile {
                        name: g.name.clone(),
                        model,
                        input: arr(&g.input),
                        spin,
                        output,
                        imu: g.imu.clone(),
                    }
                })
                .collect(),
            accel: u
                .accels()
                .iter()
                .map(|a| AccelFile {
                    name: a.name.clone(),
                    input: arr(&a.input),
                    imu: a.imu.clone(),
                })
                .collect(),
            residue: u
                .named_residues()
                .iter()
                .map(|r| ResidueFile {
                    name: r.name.clone(),
                    weights: u
                        .gyros()
                        .iter()
                        .zip(&r.weights)
                        .filter(|(_, w)| **w != 0.0)
                        .map(|(g, w)| (g.name.clone(), *w))
                        .collect(),
                })
                .collect(),
        }
    }
}

/// A finite, non-zero axis, normalised. An axis already of unit length to
/// rounding (within 4 ε) is kept as written, so a file that spells the
/// paper's 1/√2 to the last bit gives today's constants bit for bit.
fn axis(file: &str, key: &str, name: &str, v: [f64; 3]) -> Result<Vector3<f64>, UnitError> {
    let bad = |problem| UnitError::Axis {
        file: file.to_string(),
        key: key.to_string(),
        name: name.to_string(),
        problem,
    };
    if v.iter().any(|x| !x.is_finite()) {
        return Err(bad("not finite"));
    }
    let v = Vector3::from(v);
    let norm = v.norm();
    if norm == 0.0 {
        return Err(bad("zero"));
    }
    Ok(if (norm - 1.0).abs() <= 4.0 * f64::EPSILON {
        v
    } else if norm.is_finite() {
        v / norm
    } else {
        // Components near f64::MAX: the norm overflows, their ratio does not.
        let v = v / v.amax();
        v / v.norm()
    })
}

/// The dimension the axes span: singular values above 1e-6 of the largest
/// (unit axes, so an axis within 1e-6 rad of the others' plane counts as in it).
pub(crate) fn rank(axes: &[Vector3<f64>]) -> usize {
    if axes.is_empty() {
        return 0;
    }
    let m = nalgebra::DMatrix::from_fn(axes.len(), 3, |i, j| axes[i][j]);
    let sv = m.singular_values();
    let max = sv.max();
    sv.iter().filter(|s| **s > 1e-6 * max).count()
}

/// 1-based line and column of a byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |p| p + 1) + 1;
    (line, column)
}
