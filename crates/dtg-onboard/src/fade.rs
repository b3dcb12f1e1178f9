//! The fade of the network part outside the training range
//! (`sysid::operating::fade`): the smoothed weight of one window, read from
//! the tables' fade block and the rings of calibrated accelerations.

use crate::maths::{abs, sqrt};
use crate::model::Model;

/// The smoothed fade weight of the window that ends at the newest sample
/// (the fade block at byte `at`, its rings in `st` with the oldest sample
/// at `pos`): each accelerometer's window mean and level (and with the
/// shape block its vibration shape, `sysid::operating::shape`), the
/// distance beyond the training range, the smoothstep, the one-pole
/// smoother (started at the first window's own weight).
pub(crate) fn fade_weight(m: &Model, at: usize, st: &mut [f64], pos: usize, first: bool) -> f64 {
    let l = m.window_len;
    let n = l as f64;
    let na4 = 4 * m.n_accels;
    let scale = m.f(at + 8 * na4);
    let mut d2 = 0.0;
    for k in 0..m.n_accels {
        let win = &st[m.st.fade + 2 * l * k + pos..][..l];
        let mut sum = 0.0;
        for v in win {
            sum += *v;
        }
        let mean = sum / n;
        let mut ss = 0.0;
        for v in win {
            ss += (*v - mean) * (*v - mean);
        }
        let var = ss / n;
        let level = sqrt(var);
        let b = at + 8 * 4 * k;
        let em = excess(mean, m.f(b), m.f(b + 8)) / scale;
        let el = excess(level, m.f(b + 16), m.f(b + 24)) / scale;
        d2 += em * em + el * el;
        if m.fade_shape {
            let es = shape_term(
                m,
                at + 8 * (na4 + 4 + m.n_channels),
                k,
                win,
                var,
                level,
                scale,
            );
            d2 += es * es;
        }
    }
    let (tolerance, width, alpha) = (
        m.f(at + 8 * (na4 + 1)),
        m.f(at + 8 * (na4 + 2)),
        m.f(at + 8 * (na4 + 3)),
    );
    let d = sqrt(d2);
    let w0 = if d <= tolerance {
        1.0
    } else {
        let u = (d - tolerance) / width;
        let u = if u < 1.0 { u } else { 1.0 };
        1.0 - u * u * (3.0 - 2.0 * u)
    };
    let ws = m.st.fade + 2 * l * m.n_accels + m.n_channels;
    st[ws] = if first {
        w0
    } else {
        // Toward a lower weight the shape block's fall gain (sysid's
        // FadeSettings::fall_alpha; without the block the weight falls as
        // it rises). Within 1e-9 of its input the one-pole takes it
        // (sysid's SNAP).
        let gain = if m.fade_shape && w0 < st[ws] {
            m.f(at + 8 * (na4 + 4 + m.n_channels + 2 * m.n_accels + 1))
        } else {
            alpha
        };
        let w = st[ws] + gain * (w0 - st[ws]);
        if abs(w0 - w) <= 1e-9 { w0 } else { w }
    };
    st[ws]
}

/// Accelerometer `k`'s shape term of the distance (the shape block at byte
/// `sb`): the window's vibration shape (`sysid::operating::shape::shape`,
/// summed in its order), its excess beyond the training interval over the
/// shape scale, gated by the level (0 up to one `scale`, 1 from two).
fn shape_term(
    m: &Model,
    sb: usize,
    k: usize,
    win: &[f64],
    var: f64,
    level: f64,
    scale: f64,
) -> f64 {
    let l = win.len();
    let rho = if l < 2 || var <= 0.0 {
        0.0
    } else {
        let mut dd = 0.0;
        for i in 1..l {
            let d = win[i] - win[i - 1];
            dd += d * d;
        }
        sqrt(dd / (2.0 * (l - 1) as f64) / var)
    };
    let g = (level - scale) / scale;
    let g = if g < 0.0 {
        0.0
    } else if g > 1.0 {
        1.0
    } else {
        g
    };
    let b = sb + 8 * 2 * k;
    g * excess(rho, m.f(b), m.f(b + 8)) / m.f(sb + 8 * 2 * m.n_accels)
}

/// How far `v` lies beyond `[lo, hi]` (0 inside).
#[inline(always)]
fn excess(v: f64, lo: f64, hi: f64) -> f64 {
    let e = if lo - v > v - hi { lo - v } else { v - hi };
    if e > 0.0 { e } else { 0.0 }
}
