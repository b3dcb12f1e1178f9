//! The page of a model on records, for any unit: the paper's page (its
//! figures and sections) for a model of the paper's unit in the paper's
//! record format, whose writers still read the paper's types, and the
//! unit's page otherwise. A bridge until the report writers take any
//! unit's model: then this file goes, and every unit gets the one page.

use crate::allan::AllanAnalysis;
use crate::apply::Applied as PaperApplied;
use crate::error::DtgVibError;
use crate::model::CompensationModel;
use crate::report::{Baseline, DiagnosisExtra, NoiseFloor, Provenance, ReportExtras, build_report};
use crate::unit_page::{Page, write_page as write_unit_page};
use crate::unit_sensor::UnitModel;
use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::record::Record;
use std::path::{Path, PathBuf};
use sysid::diagnose::{ChannelDiagnosis, Diagnosis};

/// What a page shows besides the model and its records.
pub struct PageSpec<'a> {
    /// The model file (provenance).
    pub model_path: &'a Path,
    /// The records' files (provenance, and the page's name for them).
    pub data: &'a [PathBuf],
    /// How the page names the records' source ("simulated (…)", a file).
    pub source: String,
    /// Files the provenance lists, beyond the model, records and baseline.
    pub files: Vec<(String, PathBuf)>,
    /// A baseline model and its file.
    pub baseline: Option<(&'a UnitModel, &'a Path)>,
    /// Paragraphs first on the page.
    pub lead: Vec<String>,
    /// Other pages to link.
    pub links: Vec<(PathBuf, String)>,
    /// Another directory to write the page into too (its figures linked
    /// from the page's own directory): the demo's `out/index.html`.
    pub also_into: Option<PathBuf>,
    /// The Allan analysis to show.
    pub allan: Option<&'a AllanAnalysis>,
    /// A diagnosis of the model shown inline: the diagnosis, what it is of,
    /// the ranking's least ERR and its own page.
    pub diagnosis: Option<(&'a Diagnosis<String, Axis>, String, f64, PathBuf)>,
    /// Each channel's per-sample noise floor and where it comes from.
    pub noise_floor: Option<(Vec<&'a [f64]>, String)>,
}

/// Writes the page of `model` on `records` into `dir`; returns the page.
pub fn write_page(
    model: &UnitModel,
    records: &[(String, Record)],
    spec: PageSpec<'_>,
    dir: &Path,
) -> Result<PathBuf, DtgVibError> {
    let paper = match (records, CompensationModel::of_unit(model)) {
        ([(_, record)], Some(m)) => Some((record, m)),
        _ => None,
    };
    let Some((record, m)) = paper else {
        let page = Page {
            model_path: spec.model_path,
            data: spec.data,
            baseline: spec.baseline,
            lead: spec.lead,
            links: spec.links,
            also_into: spec.also_into,
        };
        return Ok(write_unit_page(model, records, page, dir)?.0);
    };
    let applied = PaperApplied::new(&m, record)?;
    let base = match spec.baseline {
        Some((b, _)) => {
            let bm = CompensationModel::of_unit(b).ok_or_else(|| not_paper(b))?;
            let ba = PaperApplied::new(&bm, record)?;
            Some((bm, ba))
        }
        None => None,
    };
    let mut files: Vec<(String, PathBuf)> = vec![("model".into(), spec.model_path.into())];
    files.extend(spec.data.iter().map(|d| ("data".to_string(), d.clone())));
    files.extend(spec.files);
    if let Some((_, p)) = spec.baseline {
        files.push(("baseline model".into(), p.to_path_buf()));
    }
    let provenance = Provenance::of_this_process(files);
    let diagnosis = match &spec.diagnosis {
        Some((d, _, _, _)) => Some(paper_diagnosis(d).ok_or_else(|| not_paper(model))?),
        None => None,
    };
    let noise_floor = spec.noise_floor.as_ref().and_then(|(s, source)| {
        let per_sample: [&[f64]; 6] = s.clone().try_into().ok()?;
        Some(NoiseFloor {
            per_sample,
            source: source.clone(),
        })
    });
    let extras = ReportExtras {
        provenance: Some(&provenance),
        allan: spec.allan,
        links: spec.links,
        diagnosis: diagnosis.as_ref().zip(spec.diagnosis.as_ref()).map(
            |(d, (_, of, min_err, page))| DiagnosisExtra {
                diagnosis: d,
                of: of.clone(),
                min_err: *min_err,
                page: page.clone(),
            },
        ),
        noise_floor,
    };
    let (summary, page) = build_report(
        &m,
        &applied,
        record,
        &spec.source,
        base.as_ref().map(|(model, applied)| Baseline {
            label: "baseline",
            model,
            applied,
        }),
        &extras,
        dir,
    )?;
    page.write(dir)?;
    if let Some(other) = &spec.also_into {
        page.write(other)?;
    }
    Ok(summary.index)
}

fn not_paper(m: &UnitModel) -> DtgVibError {
    DtgVibError::ModelCorrupt {
        path: m.unit().file().into(),
        reason: "the baseline is not a model of the paper's unit".into(),
    }
}

/// The diagnosis of a model of the paper's unit with its channels as the
/// paper's.
fn paper_diagnosis(d: &Diagnosis<String, Axis>) -> Option<Diagnosis<Channel, Axis>> {
    let channels = d
        .channels
        .iter()
        .map(|c| {
            Some(ChannelDiagnosis {
                channel: c.channel.parse().ok()?,
                effects: c.effects.clone(),
                rms: c.rms,
                compare: c.compare,
                segments: c.segments.clone(),
                bands: c.bands.clone(),
                regimes: c.regimes.clone(),
                checks: c.checks.clone(),
                failing: c.failing.clone(),
                candidates: c.candidates.clone(),
                unexcited: c.unexcited.clone(),
                suggested: c.suggested.clone(),
                p_threshold: c.p_threshold,
                findings: c.findings.clone(),
                series: c.series.clone(),
            })
        })
        .collect::<Option<Vec<_>>>()?;
    Some(Diagnosis {
        records: d.records.clone(),
        channels,
    })
}
