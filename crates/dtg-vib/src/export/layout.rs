//! The numbers of onboard tables (the paper's layout version 2 and any
//! unit's version 3) read back as the evaluator reads them, for the C
//! generators ([`super::c`], [`super::c_unit`]). Each centre set's centres
//! are kept once (a channel that shares a set points at its leader's).

use super::c::{floats, words};
use crate::onboard::ExportError;
use dtg_onboard::{Model, UNIT_FIXED_HEADER_WORDS, gyro_cal_len, kind_params_of};

/// The numbers of onboard tables of either layout, read back as the
/// evaluator reads them (the paper's: six DTG channels, three
/// accelerometers, no log units or specific-force operator).
pub(super) struct Layout {
    pub(super) n: usize,
    pub(super) n_a: usize,
    pub(super) calibrated: bool,
    pub(super) triad: bool,
    pub(super) n_sections: usize,
    pub(super) n_in_sections: usize,
    pub(super) l: usize,
    pub(super) n_signals: usize,
    pub(super) n_effects: Vec<usize>,
    pub(super) n_centres: Vec<usize>,
    pub(super) models: Vec<usize>,
    pub(super) signal_codes: Vec<usize>,
    pub(super) kinds: Vec<usize>,
    pub(super) indices: Vec<usize>,
    pub(super) input: usize,
    pub(super) n_smooth: usize,
    pub(super) dim: usize,
    pub(super) dt: f64,
    pub(super) rate_to_deg_h: f64,
    pub(super) force_to_g: f64,
    pub(super) frames: Vec<f64>,
    pub(super) ls: Vec<f64>,
    pub(super) force_op: Vec<f64>,
    pub(super) gyro_cal: Vec<f64>,
    pub(super) cal_offset: Vec<usize>,
    pub(super) accel_cal: Vec<f64>,
    pub(super) out_sos: Vec<f64>,
    pub(super) in_sos: Vec<f64>,
    pub(super) smooth_sos: Vec<f64>,
    pub(super) bias: Vec<f64>,
    pub(super) coeff: Vec<f64>,
    pub(super) params: Vec<f64>,
    pub(super) param_offset: Vec<usize>,
    pub(super) widths: Vec<f64>,
    pub(super) weights: Vec<f64>,
    /// The leaders' centre blocks only; each channel's block offset (in
    /// centres) and its leader.
    pub(super) centres: Vec<f64>,
    pub(super) centre_offset: Vec<usize>,
    pub(super) centre_set: Vec<usize>,
    pub(super) fade: Vec<f64>,
}

impl Layout {
    pub(super) fn read(bytes: &[u8]) -> Result<Self, ExportError> {
        let m = Model::parse(bytes).map_err(|e| ExportError::Tables(e.to_string()))?;
        let b = bytes;
        let (n, n_a) = (m.n_channels(), m.n_accels());
        let unit = m.version() == dtg_onboard::UNIT_VERSION;
        let flags = words(b, 3, 1)[0];
        let calibrated = flags & dtg_onboard::FLAG_CALIBRATION as usize != 0;
        let triad = if unit {
            flags & dtg_onboard::FLAG_ACCEL_TRIAD as usize != 0
        } else {
            calibrated
        };
        let n_sections = words(b, 5, 1)[0];
        let n_in_sections = words(b, 6, 1)[0];
        let n_signals = words(b, 8, 1)[0];
        // Where the per-channel lists and the signal codes start.
        let (effects_at, centres_at, signals_at) = if unit {
            let w0 = UNIT_FIXED_HEADER_WORDS;
            (w0, w0 + n, w0 + 3 * n)
        } else {
            (9, 15, dtg_onboard::FIXED_HEADER_WORDS)
        };
        let n_effects = words(b, effects_at, n);
        let n_centres = words(b, centres_at, n);
        let models = if unit {
            words(b, centres_at + n, n)
        } else {
            vec![dtg_onboard::gyro::DTG as usize; n]
        };
        let signal_codes = words(b, signals_at, n_signals);
        let total: usize = n_effects.iter().sum();
        let pairs = words(b, signals_at + n_signals, 2 * total);
        let kinds: Vec<usize> = pairs.iter().step_by(2).copied().collect();
        let indices: Vec<usize> = pairs.iter().skip(1).step_by(2).copied().collect();
        let after = words(b, signals_at + n_signals + 2 * total, 2);
        let dim = m.input_dim();
        let mut at = 4 * words(b, 2, 1)[0];
        let mut take = |k: usize| {
            let v = floats(b, at, k);
            at += 8 * k;
            v
        };
        let dt = take(1)[0];
        let scales = if unit { take(2) } else { vec![1.0, 1.0] };
        let frames = take(9 * n);
        let ls = take(3 * n);
        let force_op = if unit { take(3 * n_a) } else { vec![] };
        let (mut gyro_cal, mut cal_offset) = (vec![], vec![]);
        if calibrated {
            for &g in &models {
                cal_offset.push(gyro_cal.len());
                gyro_cal.extend(take(gyro_cal_len(g as u32).unwrap_or(0)));
            }
        } else {
            cal_offset = vec![0; n];
        }
        let accel_cal = if triad { take(24) } else { vec![] };
        let out_sos = take(7 * n_sections);
        let in_sos = take(7 * n_in_sections);
        let smooth_sos = take(7 * after[1]);
        let (mut bias, mut coeff, mut params, mut widths, mut weights) =
            (vec![], vec![], vec![], vec![], vec![]);
        let (mut centres, mut centre_offset, mut centre_set) = (vec![], vec![], vec![]);
        let mut param_offset = Vec::new();
        let mut e0 = 0;
        let mut leader_offset = vec![0; n];
        for c in 0..n {
            bias.push(take(1)[0]);
            coeff.extend(take(n_effects[c]));
            let mut np = 0;
            for &k in &kinds[e0..e0 + n_effects[c]] {
                param_offset.push(params.len() + np);
                np += kind_params_of(k as u32, n).unwrap_or(0);
            }
            params.extend(take(np));
            widths.extend(take(n_centres[c]));
            weights.extend(take(n_centres[c]));
            let block = take(n_centres[c] * dim);
            let leader = m.centre_set(c);
            if leader == c {
                leader_offset[c] = centres.len() / dim.max(1);
                centres.extend(block);
            }
            centre_offset.push(leader_offset[leader]);
            centre_set.push(leader);
            e0 += n_effects[c];
        }
        let fade = if m.fades() {
            take(dtg_onboard::fade_floats(n_a, n))
        } else {
            vec![]
        };
        Ok(Self {
            n,
            n_a,
            calibrated,
            triad,
            n_sections,
            n_in_sections,
            l: m.window_len(),
            n_signals,
            n_effects,
            n_centres,
            models,
            signal_codes,
            kinds,
            indices,
            input: after[0],
            n_smooth: after[1],
            dim,
            dt,
            rate_to_deg_h: scales[0],
            force_to_g: scales[1],
            frames,
            ls,
            force_op,
            gyro_cal,
            cal_offset,
            accel_cal,
            out_sos,
            in_sos,
            smooth_sos,
            bias,
            coeff,
            params,
            param_offset,
            widths,
            weights,
            centres,
            centre_offset,
            centre_set,
            fade,
        })
    }
}
