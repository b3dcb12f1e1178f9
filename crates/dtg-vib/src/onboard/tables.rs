//! A causal model as the flat tables the `dtg-onboard` evaluator and the
//! exported C read (layout in docs/formats.md, "Onboard tables").

use super::error::ExportError;
use crate::effects::{Effect, rate_without_each_channel};
use crate::model::CompensationModel;
use crate::signal::LowPass;
use dtg_onboard::{FIXED_HEADER_WORDS, FLAG_CALIBRATION, FLAG_FADE, MAGIC, VERSION, kind};
use nav_sensors::dtg::DtgTerm;
use nav_sensors::geometry::{Axis, Channel, ChannelFrame, least_squares_operator};

/// A model as onboard tables, with the names of the extra columns each step
/// takes (in order).
#[derive(Debug, Clone, PartialEq)]
pub struct Tables {
    /// The bytes (layout version [`dtg_onboard::VERSION`]).
    pub bytes: Vec<u8>,
    /// Extra record columns a step takes, in order.
    pub extra: Vec<String>,
}

/// One effect in the tables: kind, index, parameters.
fn effect_entry(
    channel: Channel,
    effect: &Effect,
    extra: &[String],
) -> Result<(u32, u32, Vec<f64>), ExportError> {
    let frame = ChannelFrame::of(channel);
    let ax = |c: char| match c {
        'I' => frame.input,
        'O' => frame.other,
        _ => frame.spin,
    };
    let v3 = |v: nalgebra::Vector3<f64>| vec![v.x, v.y, v.z];
    match effect {
        Effect::Column(name) => {
            let idx = extra
                .iter()
                .position(|e| e == name)
                .expect("extra columns are collected from the effects");
            Ok((kind::COLUMN, idx as u32, vec![]))
        }
        Effect::Term(t) => {
            let id = t.id();
            let axes: Vec<char> = id.rsplit('_').next().unwrap_or("").chars().collect();
            if DtgTerm::SPECIFIC_FORCE[..3].contains(t) {
                Ok((kind::LINEAR_G, 0, v3(ax(axes[0]))))
            } else if DtgTerm::SPECIFIC_FORCE.contains(t) {
                let mut p = v3(ax(axes[0]));
                p.extend(v3(ax(axes[1])));
                Ok((kind::QUADRATIC_G, 0, p))
            } else if DtgTerm::ANISOINERTIA.contains(t) {
                // (a·op·m/3600)(b·op·m/3600): the channel's rate without its
                // own output, resolved, in deg/s.
                let op = rate_without_each_channel()[channel.index()];
                let row = |c: char| {
                    let r = ax(c).transpose() * op / 3600.0;
                    r.iter().copied().collect::<Vec<f64>>()
                };
                let mut p = row(axes[0]);
                p.extend(row(axes[1]));
                Ok((kind::RATE_PRODUCT, 0, p))
            } else {
                Err(ExportError::Unsupported {
                    channel: channel.to_string(),
                    what: format!("effect {id}"),
                    supported: "g_*, gg_*, ai_* and col:NAME effects",
                })
            }
        }
    }
}

/// The extra record columns a model reads: windowed extra signals first,
/// then effect columns, each once, in order of first use.
pub fn extra_columns(model: &CompensationModel) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut add = |n: &str| {
        if !out.iter().any(|e| e == n) {
            out.push(n.to_string());
        }
    };
    for s in model.preprocess().window.signals() {
        if !Axis::ALL.iter().any(|a| a.column() == s) {
            add(s);
        }
    }
    for c in model.channels() {
        for e in c.effects() {
            if let Effect::Column(n) = e {
                add(n);
            }
        }
    }
    out
}

/// A low-pass's sections as the layout's numbers (b0 b1 b2 a1 a2 and the
/// steady state of a unit input, each).
pub(super) fn sections(lp: &Option<LowPass>) -> Vec<f64> {
    let Some(lp) = lp else { return vec![] };
    let zi = lp.steady_state();
    lp.sections()
        .iter()
        .zip(zi)
        .flat_map(|(s, z)| [s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], z[0], z[1]])
        .collect()
}

/// The model as onboard tables. Refuses a zero-phase model and what the
/// evaluator does not compute (a kernel other than the Gaussian, input
/// scaling, a polynomial tail).
pub fn tables(model: &CompensationModel) -> Result<Tables, ExportError> {
    let pre = model.preprocess();
    if !pre.causal {
        return Err(ExportError::NotCausal);
    }
    let extra = extra_columns(model);
    // The effects are subtracted unfiltered (θ·z, as the batch
    // compensation does): their coefficients were estimated on the filtered
    // output and regressors alike, and the filtered regressor would leave
    // the effect's part above the cut-off in the output. The targets'
    // filter is then nothing the evaluator runs.
    let out_filter: Option<LowPass> = None;
    let in_filter = input_filter(&pre.input_filter, model.dt_s())?;
    let n_sections = out_filter.as_ref().map_or(0, |f| f.sections().len());
    let n_in_sections = in_filter.as_ref().map_or(0, |f| f.sections().len());
    let (words, params) = header_words(model, &extra, [n_sections, n_in_sections])?;
    let mut f = geometry_and_calibration(model);
    f.extend(sections(&out_filter));
    f.extend(sections(&in_filter));
    f.extend(sections(&smoother_filter(pre.smoother, model.dt_s())));
    for (c, p) in model.channels().iter().zip(&params) {
        network_floats(c, p, &mut f)?;
    }
    if let Some(block) = super::fade::fade_block(model)? {
        f.extend(block);
    }
    assemble(&words, &f, extra)
}

/// An accelerometer's calibration in the layout's order.
pub(super) fn accel_floats(c: &nav_sensors::accel::AccelCoefficients) -> [f64; 8] {
    [
        c.bias_ug,
        c.scale_factor_ppm,
        c.k2_ug_per_g2,
        c.k3_ug_per_g3,
        c.misalignment_o_urad,
        c.misalignment_p_urad,
        c.kip_ug_per_g2,
        c.kio_ug_per_g2,
    ]
}

/// The tables' bytes: the header `words`, then the numbers `f`, checked by
/// the evaluator (a refusal is an exporter bug).
pub(super) fn assemble(
    words: &[u32],
    f: &[f64],
    extra: Vec<String>,
) -> Result<Tables, ExportError> {
    let mut bytes = Vec::with_capacity(4 * words.len() + 8 * f.len());
    for w in words {
        bytes.extend(w.to_le_bytes());
    }
    for v in f {
        bytes.extend(v.to_le_bytes());
    }
    dtg_onboard::Model::parse(&bytes).map_err(|e| ExportError::Tables(e.to_string()))?;
    Ok(Tables { bytes, extra })
}

/// The header words (sizes, signal codes, each effect's kind and index)
/// and each channel's effect parameters, in the layout's order.
fn header_words(
    model: &CompensationModel,
    extra: &[String],
    [n_sections, n_in_sections]: [usize; 2],
) -> Result<(Vec<u32>, Vec<Vec<f64>>), ExportError> {
    let pre = model.preprocess();
    let signals = pre.window.signals();
    let mut words: Vec<u32> = vec![
        u32::from_le_bytes(MAGIC),
        VERSION,
        0, // header words, below
        if model.calibration().is_some() {
            FLAG_CALIBRATION
        } else {
            0
        } | if super::fade::fade_block(model)?.is_some() {
            FLAG_FADE
        } else {
            0
        },
        extra.len() as u32,
        n_sections as u32,
        n_in_sections as u32,
        pre.window.length() as u32,
        signals.len() as u32,
    ];
    words.extend(model.channels().iter().map(|c| c.effects().len() as u32));
    words.extend(model.channels().iter().map(|c| c.n_centres() as u32));
    debug_assert_eq!(words.len(), FIXED_HEADER_WORDS);
    for s in signals {
        let code = match Axis::ALL.iter().position(|a| a.column() == s) {
            Some(i) => i,
            None => 3 + extra.iter().position(|e| e == s).expect("collected above"),
        };
        words.push(code as u32);
    }
    let mut params: Vec<Vec<f64>> = Vec::new();
    for c in model.channels() {
        let mut p = Vec::new();
        for e in c.effects() {
            let (k, i, v) = effect_entry(c.channel(), e, extra)?;
            words.extend([k, i]);
            p.extend(v);
        }
        params.push(p);
    }
    words.extend(input_and_smoother_words(
        pre.input,
        pre.smoother,
        model.dt_s(),
    ));
    if !words.len().is_multiple_of(2) {
        words.push(0);
    }
    words[2] = words.len() as u32;
    Ok((words, params))
}

/// The words after the effect pairs: the network's input kind and the
/// prediction smoother's sections.
pub(super) fn input_and_smoother_words(
    input: sysid::ModelInput,
    smoother: Option<sysid::Smoother>,
    dt_s: f64,
) -> [u32; 2] {
    let input = match input {
        sysid::ModelInput::Raw => dtg_onboard::input::RAW,
        sysid::ModelInput::Statistics => dtg_onboard::input::STATISTICS,
    };
    [
        input,
        smoother_filter(smoother, dt_s).map_or(0, |f| f.sections().len()) as u32,
    ]
}

/// The prediction smoother's filter, as the loop designs it.
pub(super) fn smoother_filter(smoother: Option<sysid::Smoother>, dt_s: f64) -> Option<LowPass> {
    smoother?.design(dt_s).ok()
}

/// The causal low-pass of the windowed signals, as the loop designs it.
pub(super) fn input_filter(
    spec: &Option<sysid::FilterSpec>,
    dt_s: f64,
) -> Result<Option<LowPass>, ExportError> {
    spec.map(|f| LowPass::butterworth(f.order, f.cutoff_hz, 1.0 / dt_s))
        .transpose()
        .map_err(|e| ExportError::Tables(e.to_string()))
}

/// The sample interval, the channel frames, the least-squares rate
/// operator and the ground calibration, as the layout's first floats.
fn geometry_and_calibration(model: &CompensationModel) -> Vec<f64> {
    let mut f: Vec<f64> = vec![model.dt_s()];
    for fr in ChannelFrame::all() {
        for v in [fr.input, fr.other, fr.spin] {
            f.extend([v.x, v.y, v.z]);
        }
    }
    let ls = least_squares_operator();
    for i in 0..3 {
        f.extend((0..6).map(|j| ls[(i, j)]));
    }
    if let Some(cal) = model.calibration() {
        for ch in Channel::ALL {
            let g = cal.gyro(ch);
            f.extend(g.to_array());
            f.push(g.scale_factor_nonlinearity_ppm_per_deg_s);
        }
        for a in Axis::ALL {
            f.extend(accel_floats(&cal.accel(a)));
        }
    }
    f
}

/// One channel's bias, effect coefficients and parameters `p`, widths,
/// weights and centres; refuses what the evaluator does not compute (a
/// kernel other than the Gaussian, input scaling, a polynomial tail).
pub(super) fn network_floats<C: std::fmt::Display + Clone, E>(
    c: &sysid::ChannelModel<C, E>,
    p: &[f64],
    f: &mut Vec<f64>,
) -> Result<(), ExportError> {
    let ch = c.channel().to_string();
    let rbf = c.rbf();
    let unsupported = |what: String, supported| ExportError::Unsupported {
        channel: ch.clone(),
        what,
        supported,
    };
    if rbf.kernel() != rbf::Kernel::Gaussian {
        return Err(unsupported(
            format!("the {:?} kernel", rbf.kernel()),
            "the Gaussian kernel",
        ));
    }
    if rbf.scaling().is_some() {
        return Err(unsupported(
            "input scaling".into(),
            "unscaled windows (dtg-vib fit does not scale)",
        ));
    }
    // A unit-box tail (rbf's `degree`) has its own map and terms that
    // the onboard layout does not carry; dtg-vib fit never sets one, but
    // a model file may come from elsewhere.
    if rbf.tail().is_some() || rbf.degree().is_some() {
        return Err(unsupported("a polynomial tail".into(), "no tail"));
    }
    f.push(c.bias());
    f.extend(c.effect_coefficients());
    f.extend(p);
    let k = rbf.n_centres();
    f.extend((0..k).map(|j| rbf.widths().get(j)));
    f.extend((0..k).map(|j| rbf.weights()[(j, 0)]));
    let centres = rbf.centres();
    for j in 0..k {
        f.extend((0..centres.ncols()).map(|d| centres[(j, d)]));
    }
    Ok(())
}
