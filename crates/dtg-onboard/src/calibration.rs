//! The ground calibration of one sample, as `UnitCalibration::compensate`
//! applies it: the specific force from the accelerometers (the triad's
//! static inverse when the tables hold it), the within-interval covariance
//! of the pending sample, and each gyro's inverse model with the gyros side
//! by side in lanes ([`crate::lanes`]).
//!
//! A gyro's drift splits into what the rate does not move (the bias and
//! the g and g² terms, summed once per sample) and a DTG's few rate terms
//! (the O- and S-rate terms and anisoinertia, in each of the two passes
//! at the least-squares rate), so a sample takes the g² regressors once
//! rather than twice per gyro.

use crate::interval::FACTORS;
use crate::lanes::row;
use crate::layout::{ACCEL_CAL, MAX_CHANNELS, gyro};
use crate::maths::{abs, rd};
use crate::model::Model;

/// Newton's iterations (the calibration's inverses) stop once the next
/// step would be within this many ulps of the estimate (its residual is
/// checked before the division), or after four as in the batch: later
/// steps would move only the last bits, so the two agree to a few ulps, and
/// an inverse takes one division where the batch takes four.
pub(crate) const NEWTON_SETTLED: f64 = 4.0 * f64::EPSILON;

/// The calibrated specific force (unit frame, g) of one sample's raw
/// accelerations, and its calibrated accelerometers in `cal`: the triad's
/// static inverse when the tables calibrate it (on x, y, z ordered through
/// the specific-force operator, a permutation then), else the accelerations
/// as given through the operator (layout 2: ax, ay, az are x, y, z).
pub(crate) fn calibrated_force(m: &Model, raw: &[f64], cal: &mut [f64]) -> [f64; 3] {
    let na = m.n_accels;
    let mut f = match m.force_op {
        None => [raw[0], raw[1], raw[2]],
        Some(op) => core::array::from_fn(|i| {
            let mut s = 0.0;
            for (k, x) in raw.iter().enumerate() {
                s += m.f(op + 8 * (na * i + k)) * x;
            }
            s
        }),
    };
    if m.accel_triad {
        f = compensate_triad(m, &f);
    }
    match (m.force_op, m.accel_triad) {
        (Some(op), true) => {
            // The operator is a permutation: each accelerometer is one axis.
            for (k, c) in cal.iter_mut().enumerate() {
                *c = (0..3)
                    .map(|i| m.f(op + 8 * (na * i + k)) * f[i])
                    .fold(0.0, |s, v| s + v);
            }
        }
        (Some(_), false) => cal.copy_from_slice(raw),
        (None, _) => cal.copy_from_slice(&f),
    }
    f
}

/// The accelerometer triad's static inverse (nav_sensors::accel::compensate_triad:
/// three Gauss–Seidel sweeps, Newton on each axis). A sweep after the first
/// starts each axis's Newton at the last sweep's root, which the µg-sized
/// coupling moves only slightly.
fn compensate_triad(m: &Model, measured: &[f64; 3]) -> [f64; 3] {
    let mut a = *measured;
    let cal = |k: usize, i: usize| rd(m.bytes, m.accel_cal + 8 * (ACCEL_CAL * k + i));
    let target: [f64; 3] = core::array::from_fn(|k| measured[k] / (1.0 + 1e-6 * cal(k, 1)));
    for sweep in 0..3 {
        for k in 0..3 {
            let c = |i: usize| cal(k, i);
            let (bias, k2, k3, mo, mp, kip, kio) = (c(0), c(2), c(3), c(4), c(5), c(6), c(7));
            let (ap, ao) = (a[(k + 1) % 3], a[(k + 2) % 3]);
            let mut x = if sweep == 0 { target[k] } else { a[k] };
            for _ in 0..4 {
                let core = 1e-6
                    * (bias + x * x * (k2 + k3 * x) + mo * ap - mp * ao
                        + x * (kip * ap + kio * ao));
                let g = x + core - target[k];
                let dg = 1.0 + 1e-6 * (2.0 * k2 * x + 3.0 * k3 * x * x + kip * ap + kio * ao);
                if abs(g) <= NEWTON_SETTLED * abs(dg * x) {
                    break;
                }
                x -= g / dg;
            }
            a[k] = x;
        }
    }
    a
}

/// The g² terms' axis pairs, in the calibration lanes' order.
const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

/// Each gyro's drift at zero rate less its DTG rate terms (the bias, the g
/// and the g² terms, with the covariance's factors `e`), term by term with
/// the gyros side by side (`lanes`: the calibration lanes).
fn drift_at_rest(
    lanes: &[f64],
    n: usize,
    f: &[f64; 3],
    e: &[[f64; 3]; FACTORS],
) -> [f64; MAX_CHANNELS] {
    let r = |row: usize| &lanes[row * n..][..n];
    // The specific force and the covariance's factors along each gyro's
    // three regressor axes.
    let mut p = [[[0.0; MAX_CHANNELS]; 3]; 1 + FACTORS];
    for (v, pv) in [f, &e[0], &e[1], &e[2], &e[3]]
        .into_iter()
        .zip(p.iter_mut())
    {
        for (a, pa) in pv.iter_mut().enumerate() {
            let (x, y, z) = (r(3 * a), r(3 * a + 1), r(3 * a + 2));
            for (((p, x), y), z) in pa.iter_mut().zip(x).zip(y).zip(z) {
                *p = x * v[0] + y * v[1] + z * v[2];
            }
        }
    }
    let mut g = [0.0; MAX_CHANNELS];
    g[..n].copy_from_slice(r(row::BIAS));
    for (a, pa) in p[0].iter().enumerate() {
        for ((g, p), c) in g.iter_mut().zip(pa).zip(r(row::FORCE + a)) {
            *g += p * c;
        }
    }
    for (t, &(a, b)) in PAIRS.iter().enumerate() {
        let c = r(row::GG + t);
        for k in 0..n {
            let z = p.iter().fold(0.0, |z, pv| z + pv[a][k] * pv[b][k]);
            g[k] += z * c[k];
        }
    }
    g
}

/// Each gyro's inverse model, two passes (UnitCalibration::compensate): the
/// least-squares rate from the raw outputs, then from the first pass's.
/// `gyro` holds the raw outputs and is left holding the calibrated ones; a
/// rate gyro's inverse, (output − drift)/(1 + 10⁻⁶·scale factor), does not
/// depend on the rate, a DTG's starts from the same division and takes
/// Newton's steps on its scale-factor nonlinearity.
pub(crate) fn compensate_gyros(
    m: &Model,
    lanes: &[f64],
    gyro: &mut [f64],
    f: &[f64; 3],
    e: &[[f64; 3]; FACTORS],
) {
    // (n ≤ MAX_CHANNELS said so that the arrays' indices need no checks.)
    let n = gyro.len().min(MAX_CHANNELS);
    let r = |row: usize| &lanes[row * n..][..n];
    let at_rest = drift_at_rest(lanes, n, f, e);
    let mut raw = [0.0; MAX_CHANNELS];
    raw[..n].copy_from_slice(gyro);
    let (scale, nl) = (r(row::SCALE), r(row::NONLINEARITY));
    for _ in 0..2 {
        let rate: [f64; 3] = core::array::from_fn(|i| {
            let op = r(row::RATE_OPERATOR + i);
            let mut s = 0.0;
            for k in 0..n {
                s += op[k] * gyro[k];
            }
            s
        });
        let mut next = [0.0; MAX_CHANNELS];
        let (o, s) = ((r(3), r(4), r(5)), (r(6), r(7), r(8)));
        let (rate_o, rate_s) = (r(row::RATE_O), r(row::RATE_S));
        let (ai_io, ai_is, ai_os) = (r(row::AI_IO), r(row::AI_IS), r(row::AI_OS));
        for k in 0..n {
            let w1 = o.0[k] * rate[0] + o.1[k] * rate[1] + o.2[k] * rate[2];
            let w2 = s.0[k] * rate[0] + s.1[k] * rate[1] + s.2[k] * rate[2];
            let a0 = at_rest[k] + (w1 * rate_o[k] + w2 * rate_s[k]) + (w1 * w2) * ai_os[k];
            let b = scale[k] + (w1 * ai_io[k] + w2 * ai_is[k]);
            let w = (raw[k] - a0) / b;
            next[k] = if m.channels[k].model == gyro::DTG {
                newton(w, (a0, b, nl[k]), raw[k])
            } else {
                w
            };
        }
        gyro.copy_from_slice(&next[..n]);
    }
}

/// A DTG's rate about its input axis from `measured = a0 + b·ω + 10⁻⁶·nl·|ω|ω/3600`,
/// Newton's steps from `wi` (nav_sensors DtgCoefficients::compensate_deg_h).
#[inline(always)]
fn newton(mut wi: f64, (a0, b, nl): (f64, f64, f64), measured: f64) -> f64 {
    for _ in 0..4 {
        let per_s = abs(wi) * (1.0 / 3600.0);
        let fx = a0 + b * wi + 1e-6 * nl * per_s * wi - measured;
        let df = b + 2e-6 * nl * per_s;
        if abs(fx) <= NEWTON_SETTLED * abs(df * wi) {
            break;
        }
        wi -= fx / df;
    }
    wi
}
