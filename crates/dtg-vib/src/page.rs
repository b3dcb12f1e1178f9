//! The page of a unit's model on records of its unit, computed and
//! written: the model applied to the records (prepared as its training
//! data were, the prediction with its network part faded outside the
//! training range, the model's split), a baseline likewise, the parity
//! residues on every sample with fault detection, the Allan analysis of
//! the longest record, the provenance, and the page
//! ([`crate::report::build_page`]). `demo`, `report` and `check --report`
//! write it, for any unit.

use crate::allan::AllanAnalysis;
use crate::error::DtgVibError;
pub use crate::report::Parity;
use crate::report::{
    DiagnosisExtra, Evaluated, NoiseFloor, PageNumbers, Provenance, ReportExtras, build_page,
    parity_on_samples,
};
use crate::unit_sensor::fdi::DEFAULT_FALSE_ALARM;
use crate::unit_sensor::{UnitModel, UnitSensor, gyros_before_after, to_signals};
use nav_sensors::record::Record;
use std::path::{Path, PathBuf};
use sysid::Signals;

/// The residues and fault detection of `m` on `records` (segments of its
/// unit's logs), every sample from the model's first full window on; σ
/// given or read from the record, false-alarm probability `p_fa` per
/// sample.
pub fn parity(
    m: &UnitModel,
    records: &[(String, Record)],
    sigma: Option<f64>,
    p_fa: f64,
) -> Result<Parity, DtgVibError> {
    let unit = m.unit();
    if unit.residue_names().is_empty() {
        return Ok(Parity {
            residues: Vec::new(),
            fdi: None,
        });
    }
    let g = gyros_before_after(m, records)?;
    Ok(parity_on_samples(unit, &g.before, &g.after, sigma, p_fa))
}

/// What a unit's page is made of besides the model and its records.
pub struct Page<'a> {
    /// The model file (provenance).
    pub model_path: &'a Path,
    /// The records' files (provenance, and the page's name for them).
    pub data: &'a [PathBuf],
    /// A baseline model and its file.
    pub baseline: Option<(&'a UnitModel, &'a Path)>,
    /// Paragraphs first on the page.
    pub lead: Vec<String>,
    /// Other pages to link.
    pub links: Vec<(PathBuf, String)>,
    /// Another directory to write the page into too (its figures linked
    /// from the page's own directory): the demo's `out/index.html`.
    pub also_into: Option<PathBuf>,
    /// How the page names the records (default: their files).
    pub source: Option<String>,
    /// Other files read, for the provenance (a calibration): `(role, path)`.
    pub files: Vec<(String, PathBuf)>,
    /// A diagnosis of the model, shown in short ("Where it fails",
    /// "Diagnosis") and linked.
    pub diagnosis: Option<DiagnosisExtra<'a, String>>,
    /// The records' noise floor per channel, when known (a simulation's).
    pub noise_floor: Option<NoiseFloor<'a>>,
    /// The call the provenance names, where it is not this process's
    /// command line (a call of the Python package).
    pub command: Option<String>,
    /// The folder in which inputs handed over from memory (a DataFrame, a
    /// model) were written for the page: the provenance shows their paths
    /// without it.
    pub staged: Option<&'a Path>,
}

impl<'a> Page<'a> {
    /// A page of the model at `model_path` on the records `data`, with
    /// nothing else.
    pub fn new(model_path: &'a Path, data: &'a [PathBuf]) -> Self {
        Self {
            model_path,
            data,
            baseline: None,
            lead: Vec::new(),
            links: Vec::new(),
            also_into: None,
            source: None,
            files: Vec::new(),
            diagnosis: None,
            noise_floor: None,
            command: None,
            staged: None,
        }
    }
}

/// What [`write_page`] wrote and the numbers it shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// The page (`dir/index.html`).
    pub index: PathBuf,
    /// The residues on every sample and fault detection.
    pub parity: Parity,
    /// The residues on the validation rows and each channel's scores.
    pub numbers: PageNumbers,
}

/// A model on the signals of its records: prepared, predicted, split.
struct Applied {
    prepared: sysid::Prepared<UnitSensor>,
    predicted: Vec<Vec<f64>>,
    train: Vec<usize>,
    val: Vec<usize>,
}

impl Applied {
    /// `m` on `named` (all together), its prediction faded outside the
    /// training range as compensation fades it; every row a validation
    /// row when the model's split does not fit the records.
    fn new(m: &UnitModel, named: &[(String, &Signals)]) -> Result<Self, DtgVibError> {
        let prepared = m.inner().prepare_many(named)?;
        let predicted = m.inner().predict_faded(&prepared)?.predicted;
        let (train, val) = match m.inner().rows(&prepared) {
            Ok((train, val)) if !val.is_empty() => (train, val),
            _ => (Vec::new(), (0..prepared.rows()).collect()),
        };
        Ok(Self {
            prepared,
            predicted,
            train,
            val,
        })
    }

    fn evaluated<'a>(&'a self, m: &'a UnitModel) -> Evaluated<'a, UnitSensor> {
        Evaluated {
            model: m.inner(),
            prepared: &self.prepared,
            predicted: &self.predicted,
            train: &self.train,
            val: &self.val,
        }
    }
}

/// Writes the page of `m` on `records` (segments of its unit's logs) into
/// `dir`: the one page of every unit, the paper's included.
pub fn write_page(
    m: &UnitModel,
    records: &[(String, Record)],
    page: Page<'_>,
    dir: &Path,
) -> Result<Written, DtgVibError> {
    let signals = records
        .iter()
        .map(|(n, r)| Ok((n.clone(), to_signals(r)?)))
        .collect::<Result<Vec<(String, Signals)>, DtgVibError>>()?;
    let named: Vec<(String, &Signals)> = signals.iter().map(|(n, s)| (n.clone(), s)).collect();
    let applied = Applied::new(m, &named)?;
    let base = match page.baseline {
        Some((b, _)) => Some(Applied::new(b, &named)?),
        None => None,
    };
    let parity = parity(m, records, None, DEFAULT_FALSE_ALARM)?;
    // The longest segment's curves; one too short for an Allan curve has
    // none worth drawing, and the page goes without.
    let allan: Option<AllanAnalysis> = records
        .iter()
        .max_by_key(|(_, r)| r.len())
        .and_then(|(_, r)| AllanAnalysis::new(m.unit(), Some(m), r, 0.683).ok());
    let mut files: Vec<(String, PathBuf)> = vec![("model".into(), page.model_path.to_path_buf())];
    files.extend(page.data.iter().map(|d| ("data".to_string(), d.clone())));
    files.extend(page.files.iter().cloned());
    if let Some((_, p)) = page.baseline {
        files.push(("baseline model".into(), p.to_path_buf()));
    }
    let mut provenance = Provenance::of_this_process(files);
    if let Some(command) = page.command {
        provenance.command = command;
    }
    provenance.staged = page.staged.map(Path::to_path_buf);
    let source = page.source.clone().unwrap_or_else(|| {
        page.data
            .iter()
            .map(|d| provenance.shown(d).display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    });
    let extras = ReportExtras {
        provenance: Some(&provenance),
        allan: allan.as_ref(),
        links: page.links,
        diagnosis: page.diagnosis,
        noise_floor: page.noise_floor,
        parity: Some(&parity),
        lead: page.lead,
    };
    let base_on = base
        .as_ref()
        .zip(page.baseline)
        .map(|(a, (b, _))| a.evaluated(b));
    let raw: Vec<&Record> = records.iter().map(|(_, r)| r).collect();
    let (html, numbers) = build_page(
        m.unit(),
        &applied.evaluated(m),
        base_on.as_ref().map(|e| ("baseline", e)),
        &raw,
        &source,
        &extras,
        dir,
    )?;
    let index = html.write(dir)?;
    if let Some(other) = &page.also_into {
        html.write(other)?;
    }
    Ok(Written {
        index,
        parity,
        numbers,
    })
}
