//! The lot manifest (TOML, docs/formats.md): the lot's name, the unit file
//! every entry uses, the `explain` options of every unit, the acceptance
//! limits, and one `[[entry]]` per unit with its records and calibration.
//! Paths are relative to the manifest. Everything a task will need is
//! checked at load — every file exists, ids are unique and usable as a
//! folder name, every option is one `explain` takes, every limit names an
//! effect of the unit — and a refusal is one line naming the entry, the
//! option or the limit.

use crate::unit_sensor::UnitSensor;
use nav_sensors::unit::Unit;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use sysid::Sensor;

/// The keys of `[options]` a task sets itself, per entry or for its own
/// output, with why.
pub const SET_BY_THE_LOT: [(&str, &str); 7] = [
    ("unit", "give it as the manifest's `unit` (or an entry's)"),
    ("data", "give each entry's records as its `data`"),
    ("calib", "give each entry's calibration as its `calib`"),
    (
        "out",
        "each unit's model is written to DIR/units/ID/model.json",
    ),
    (
        "report",
        "each unit's diagnosis page is written to DIR/units/ID/diagnosis",
    ),
    (
        "json",
        "each unit's explain JSON is written to DIR/units/ID/explain.json",
    ),
    ("quiet", "a task always runs explain quietly"),
];

/// How an `explain` flag takes its value, as its command line defines it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlagKind {
    /// Present or absent (`causal = true`).
    Switch,
    /// One value (`max_rounds = 3`).
    Value,
    /// A list joined by this delimiter (`window_signals = ["ax", "az"]`).
    Joined(char),
    /// A list given as the flag repeated (`add_effect = ["g2=g_y"]`).
    Repeated,
}

/// The options `explain` takes, by their manifest key (the long flag with
/// `_` for `-`): the command line hands its own definition in, so the
/// manifest takes exactly what `explain` takes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Catalogue {
    /// Each option's key and kind.
    pub flags: BTreeMap<String, FlagKind>,
}

/// One option of `[options]`, as `explain`'s arguments.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ExplainOption {
    /// The manifest key.
    pub key: String,
    /// The arguments it becomes (`--max-rounds 3`).
    pub args: Vec<String>,
}

/// The acceptance limits of `[spec]`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Spec {
    /// Largest |coefficient| by effect id, in the effect's unit, on every channel that has it.
    pub effects: BTreeMap<String, f64>,
    /// Largest validation rms after compensation of every channel, deg/h.
    pub rms_after_deg_h: Option<f64>,
}

/// A unit as the manifest names it, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitRef {
    /// As written.
    pub given: String,
    /// What `explain --unit` gets: the file's absolute path, or the built-in name.
    pub arg: String,
    /// The unit.
    pub unit: Unit,
}

/// One unit of the lot.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Its id: the folder of its outputs.
    pub id: String,
    /// Its unit (the manifest's unless it names its own).
    pub unit: UnitRef,
    /// Its records, as written and resolved.
    pub data: Vec<(String, PathBuf)>,
    /// Its ground calibration, as written and resolved.
    pub calib: Option<(String, PathBuf)>,
}

/// A lot manifest, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Manifest {
    /// The manifest file, absolute.
    pub path: PathBuf,
    /// The lot's name.
    pub name: String,
    /// The options of every unit's `explain`, in key order.
    pub options: Vec<ExplainOption>,
    /// The acceptance limits.
    pub spec: Spec,
    /// The units, in file order (entry K is `--index K`).
    pub entries: Vec<Entry>,
}

/// Why a manifest is refused: one line, naming the entry, option or limit.
#[derive(Debug, thiserror::Error)]
pub enum ManifestError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The manifest.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// Not TOML, or a key of the wrong type.
    #[error("{path}:{line}:{column}: {message}")]
    Parse {
        /// The manifest.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// Something of the lot as a whole.
    #[error("{path}: {problem}")]
    Lot {
        /// The manifest.
        path: String,
        /// What is wrong and how to fix it.
        problem: String,
    },
    /// An entry.
    #[error("{path}: entry {index} (id '{id}'): {problem}")]
    Entry {
        /// The manifest.
        path: String,
        /// Its index (`--index`).
        index: usize,
        /// Its id (empty if it has none).
        id: String,
        /// What is wrong and how to fix it.
        problem: String,
    },
    /// An option of `[options]`.
    #[error("{path}: [options] {key}: {problem}")]
    Option {
        /// The manifest.
        path: String,
        /// The key.
        key: String,
        /// What is wrong and how to fix it.
        problem: String,
    },
    /// A limit of `[spec]`.
    #[error("{path}: [spec] {key}: {problem}")]
    Spec {
        /// The manifest.
        path: String,
        /// The key.
        key: String,
        /// What is wrong and how to fix it.
        problem: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawManifest {
    name: String,
    unit: Option<String>,
    #[serde(default)]
    options: toml::Table,
    #[serde(default)]
    spec: toml::Table,
    #[serde(default)]
    entry: Vec<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEntry {
    id: String,
    unit: Option<String>,
    data: Vec<String>,
    calib: Option<String>,
}

/// Where a manifest's text refuses: its path, for every message.
struct At<'a> {
    path: String,
    dir: &'a Path,
}

impl At<'_> {
    fn lot(&self, problem: impl Into<String>) -> ManifestError {
        ManifestError::Lot {
            path: self.path.clone(),
            problem: problem.into(),
        }
    }

    fn entry(&self, index: usize, id: &str, problem: impl Into<String>) -> ManifestError {
        ManifestError::Entry {
            path: self.path.clone(),
            index,
            id: id.to_string(),
            problem: problem.into(),
        }
    }

    /// A file named in the manifest, resolved against its folder.
    fn file(&self, given: &str) -> Result<(String, PathBuf), String> {
        let p = self.dir.join(given);
        match p.is_file() {
            true => Ok((given.to_string(), p)),
            false => Err(format!(
                "'{given}' is not a file ({}); paths are relative to the manifest",
                p.display()
            )),
        }
    }

    /// A unit file relative to the manifest, or a built-in unit's name.
    fn unit(&self, given: &str) -> Result<UnitRef, String> {
        let file = self.dir.join(given);
        let arg = match file.is_file() {
            true => file.display().to_string(),
            false => given.to_string(),
        };
        let unit = Unit::resolve(&arg).map_err(|e| format!("unit '{given}': {e}"))?;
        Ok(UnitRef {
            given: given.to_string(),
            arg,
            unit,
        })
    }
}

impl Manifest {
    /// Reads and checks the manifest at `path`, taking the options
    /// `catalogue` lists.
    pub fn load(path: impl AsRef<Path>, catalogue: &Catalogue) -> Result<Self, ManifestError> {
        let given = path.as_ref();
        let io = |source| ManifestError::Io {
            path: given.display().to_string(),
            source,
        };
        let text = std::fs::read_to_string(given).map_err(io)?;
        let path = std::path::absolute(given).map_err(io)?;
        let dir = path.parent().unwrap_or(Path::new("/")).to_path_buf();
        let at = At {
            path: given.display().to_string(),
            dir: &dir,
        };
        let raw: RawManifest = toml::from_str(&text).map_err(|e| {
            let (line, column) = line_column(&text, e.span().map_or(0, |s| s.start));
            ManifestError::Parse {
                path: at.path.clone(),
                line,
                column,
                message: e.message().to_string(),
            }
        })?;
        let unit = raw
            .unit
            .as_deref()
            .map(|u| at.unit(u).map_err(|p| at.lot(p)))
            .transpose()?;
        let entries = entries(&at, &raw.entry, unit.as_ref())?;
        let options = raw
            .options
            .iter()
            .map(|(k, v)| option(k, v, catalogue).map_err(|problem| option_error(&at, k, problem)))
            .collect::<Result<Vec<_>, _>>()?;
        let units: Vec<&Unit> = entries.iter().map(|e| &e.unit.unit).collect();
        let spec = spec(&at, &raw.spec, &units)?;
        Ok(Self {
            path,
            name: raw.name,
            options,
            spec,
            entries,
        })
    }

    /// The arguments of every option, in key order.
    pub fn option_args(&self) -> Vec<String> {
        self.options.iter().flat_map(|o| o.args.clone()).collect()
    }

    /// The entry `--index K` names, or why there is none.
    pub fn entry(&self, index: usize) -> Result<&Entry, ManifestError> {
        self.entries.get(index).ok_or_else(|| ManifestError::Lot {
            path: self.path.display().to_string(),
            problem: format!(
                "--index {index}: the lot has {} entries (--index 0 to {})",
                self.entries.len(),
                self.entries.len().saturating_sub(1)
            ),
        })
    }
}

fn option_error(at: &At<'_>, key: &str, problem: String) -> ManifestError {
    ManifestError::Option {
        path: at.path.clone(),
        key: key.to_string(),
        problem,
    }
}

/// 1-based line and column of byte `offset` in `text`.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// Whether `id` can name a folder on every engine's file system.
fn usable_id(id: &str) -> bool {
    !id.is_empty()
        && !id.starts_with('.')
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'))
}

fn entries(
    at: &At<'_>,
    raw: &[toml::Value],
    unit: Option<&UnitRef>,
) -> Result<Vec<Entry>, ManifestError> {
    if raw.is_empty() {
        return Err(at.lot("no [[entry]]: give one per unit (id, data, optional calib)"));
    }
    let mut out: Vec<Entry> = Vec::new();
    for (index, v) in raw.iter().enumerate() {
        let id_of = || {
            v.get("id")
                .and_then(|i| i.as_str())
                .unwrap_or("")
                .to_string()
        };
        let e = RawEntry::deserialize(v.clone())
            .map_err(|err| at.entry(index, &id_of(), err.message().trim().to_string()))?;
        let bad = |problem: String| at.entry(index, &e.id, problem);
        if !usable_id(&e.id) {
            return Err(bad(
                "an id names the unit's output folder: use letters, digits, '.', '_' and '-', not first '.'".into(),
            ));
        }
        if let Some(first) = out.iter().position(|o| o.id == e.id) {
            return Err(bad(format!(
                "entry {first} has the same id: give each unit its own"
            )));
        }
        let unit = match (&e.unit, unit) {
            (Some(u), _) => at.unit(u).map_err(bad)?,
            (None, Some(u)) => u.clone(),
            (None, None) => {
                return Err(bad(
                    "no unit: give the manifest's `unit` or the entry's".into()
                ));
            }
        };
        if e.data.is_empty() {
            return Err(bad("data = []: give at least one record".into()));
        }
        let data = e
            .data
            .iter()
            .map(|d| at.file(d).map_err(|p| bad(format!("data {p}"))))
            .collect::<Result<Vec<_>, _>>()?;
        let same =
            |a: &Path, b: &Path| std::fs::canonicalize(a).ok() == std::fs::canonicalize(b).ok();
        for (i, (g, p)) in data.iter().enumerate() {
            if let Some((h, _)) = data[..i].iter().find(|(_, q)| same(p, q)) {
                return Err(bad(format!(
                    "data '{g}' is the same file as '{h}': give each record once"
                )));
            }
        }
        let calib = e
            .calib
            .as_deref()
            .map(|c| at.file(c).map_err(|p| bad(format!("calib {p}"))))
            .transpose()?;
        out.push(Entry {
            id: e.id.clone(),
            unit,
            data,
            calib,
        });
    }
    Ok(out)
}

/// An option's value as `explain`'s arguments.
fn option(key: &str, v: &toml::Value, catalogue: &Catalogue) -> Result<ExplainOption, String> {
    if let Some((_, why)) = SET_BY_THE_LOT.iter().find(|(k, _)| *k == key) {
        return Err(format!("set by the lot, not an option: {why}"));
    }
    let Some(kind) = catalogue.flags.get(key) else {
        let valid: Vec<&str> = catalogue
            .flags
            .keys()
            .map(String::as_str)
            .filter(|k| !SET_BY_THE_LOT.iter().any(|(s, _)| s == k))
            .collect();
        return Err(format!(
            "not an option of explain (its options: {})",
            valid.join(", ")
        ));
    };
    let flag = format!("--{}", key.replace('_', "-"));
    let scalar = |v: &toml::Value| -> Result<String, String> {
        match v {
            toml::Value::String(s) => Ok(s.clone()),
            toml::Value::Integer(i) => Ok(i.to_string()),
            toml::Value::Float(f) => Ok(f.to_string()),
            other => Err(format!(
                "{other} is a {}: give a string or a number",
                other.type_str()
            )),
        }
    };
    let list = || -> Result<Vec<String>, String> {
        match v {
            toml::Value::Array(a) => a.iter().map(scalar).collect(),
            one => Ok(vec![scalar(one)?]),
        }
    };
    let args = match kind {
        FlagKind::Switch => match v {
            toml::Value::Boolean(true) => vec![flag],
            toml::Value::Boolean(false) => Vec::new(),
            other => return Err(format!("{other}: a switch takes true or false")),
        },
        FlagKind::Value => match v {
            toml::Value::Array(_) => {
                return Err(format!("{v}: takes one value, not a list"));
            }
            one => vec![flag, scalar(one)?],
        },
        FlagKind::Joined(d) => vec![flag, list()?.join(&d.to_string())],
        FlagKind::Repeated => list()?
            .into_iter()
            .flat_map(|x| [flag.clone(), x])
            .collect(),
    };
    Ok(ExplainOption {
        key: key.to_string(),
        args,
    })
}

/// The limits of `[spec]`: each effect id must be one the lot's units know.
fn spec(at: &At<'_>, raw: &toml::Table, units: &[&Unit]) -> Result<Spec, ManifestError> {
    let mut spec = Spec::default();
    for (key, v) in raw {
        let bad = |problem: String| ManifestError::Spec {
            path: at.path.clone(),
            key: key.clone(),
            problem,
        };
        let limit = match v {
            toml::Value::Integer(i) => *i as f64,
            toml::Value::Float(f) => *f,
            other => return Err(bad(format!("{other}: give a number"))),
        };
        if !(limit.is_finite() && limit > 0.0) {
            return Err(bad(format!("{limit}: a limit is a positive number")));
        }
        if key == "rms_after_deg_h" {
            spec.rms_after_deg_h = Some(limit);
            continue;
        }
        let known = units.iter().any(|u| {
            let s = UnitSensor::new((*u).clone());
            (0..u.gyros().len()).any(|k| s.parse_effect(k, key).is_ok())
        });
        if !known {
            return Err(bad(format!(
                "not an effect id of the lot's unit{} (e.g. g_y, gg_zz, col:temp for a rate gyro; g_I, gg_IS for a DTG), nor rms_after_deg_h",
                if units.len() > 1 { "s" } else { "" }
            )));
        }
        spec.effects.insert(key.clone(), limit);
    }
    Ok(spec)
}
