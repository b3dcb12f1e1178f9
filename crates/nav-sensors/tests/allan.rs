//! The simulator's noise model seen through the Allan deviation: what it
//! puts in (angle random walk, Gauss–Markov bias instability, rate random
//! walk) is what `noise` reads back.

use nav_sensors::accel::AccelNoise;
use nav_sensors::dtg::DtgNoise;
use nav_sensors::geometry::{Channel, Residue, residues};
use nav_sensors::noise::{AllanCurve, NoiseTerms, overlapping_adev};
use nav_sensors::sim::{CalibrationError, Scenario, SimError, UnitSimulation, simulate_unit};
use nav_sensors::unit::Unit;
use nav_sensors::vibration::VibrationConfig;

/// The paper's unit simulated on `s`.
fn simulate(s: &Scenario) -> Result<UnitSimulation, SimError> {
    simulate_unit(&Unit::paper(), s)
}

/// The default unit (every deterministic term, the presets' noise) on a
/// shaker that stays off, so the gyros read a constant plus their noise.
fn quiet(duration_s: f64, noise: DtgNoise) -> Scenario {
    let mut s = Scenario {
        duration_s,
        ..Scenario::default()
    };
    s.vibration = VibrationConfig::default();
    s.gyros.noise = noise;
    s.accels.noise = AccelNoise::default();
    s.thermal.vibration_heating_c = 0.0;
    s.calibration_error = CalibrationError::none();
    s
}

/// 200 s at 50 Hz of the presets' noise (ARW 0.0007 deg/√h, bias
/// instability 0.003 deg/h over 300 s): the ARW read on the τ^−½ region is
/// within 10% of the truth on every channel (its 68% interval is ±1.2%:
/// EDF ≈ 6,700 at τ = 0.02 s), and on every parity residue it is the
/// channels' ARW times the norm of the residue's row of eq. 6 (2 for
/// K0–K2, √6 for K3–K5).
#[test]
fn simulated_angle_random_walk_is_recovered_within_ten_percent() {
    let s = Scenario::default();
    let truth = s.gyros.noise.arw_deg_per_rt_h;
    let sim = simulate(&quiet(200.0, s.gyros.noise)).unwrap();
    let r = &sim.record;
    for c in Channel::ALL {
        let curve = AllanCurve::octaves(r.gyro_named(c.name()).unwrap(), r.dt(), 0.683).unwrap();
        let arw = NoiseTerms::fit(&curve).arw;
        let e = arw.estimate().unwrap_or_else(|| panic!("{c}: {arw:?}"));
        assert!((e.value / truth - 1.0).abs() < 0.1, "{c}: {e:?} vs {truth}");
        assert!(e.high / e.low < 1.05, "{c}: interval {e:?}");
    }
    let mut k: [Vec<f64>; 6] = Default::default();
    for i in 0..r.len() {
        for (series, v) in k
            .iter_mut()
            .zip(residues(&r.gyro_row(i).try_into().unwrap()))
        {
            series.push(v);
        }
    }
    for res in Residue::ALL {
        let gain = if res.index() < 3 { 2.0 } else { 6f64.sqrt() };
        let curve = AllanCurve::octaves(&k[res.index()], r.dt(), 0.683).unwrap();
        let e = *NoiseTerms::fit(&curve).arw.estimate().unwrap();
        assert!(
            (e.value / (gain * truth) - 1.0).abs() < 0.1,
            "{res:?}: {e:?} vs {}",
            gain * truth
        );
    }
}

/// Rate random walk alone, K = 3 deg/h/√h: the outputs are exact interval
/// means, so σ(τ) = K·√(τ/10800) from the shortest τ on (pooled over the
/// six channels: EDF ≥ 1000 up to τ = 1.28 s), and the fit reads K back.
#[test]
fn simulated_rate_random_walk_rises_as_root_tau_over_three() {
    let k = 3.0;
    let sim = simulate(&quiet(
        200.0,
        DtgNoise {
            rrw_deg_h_per_rt_h: k,
            ..DtgNoise::default()
        },
    ))
    .unwrap();
    let r = &sim.record;
    let factors = [1, 4, 16, 64];
    let mut pooled = [0.0; 4];
    for c in Channel::ALL {
        let adev = overlapping_adev(r.gyro_named(c.name()).unwrap(), r.dt(), &factors).unwrap();
        for (p, a) in pooled.iter_mut().zip(adev) {
            *p += a * a / 6.0;
        }
        let curve = AllanCurve::octaves(r.gyro_named(c.name()).unwrap(), r.dt(), 0.683).unwrap();
        let rrw = NoiseTerms::fit(&curve).rrw;
        let e = rrw.estimate().unwrap_or_else(|| panic!("{c}: {rrw:?}"));
        assert!((e.value / k - 1.0).abs() < 0.2, "{c}: {e:?}");
    }
    for (m, v) in factors.iter().zip(pooled) {
        let tau = *m as f64 * r.dt();
        let expected = k * (tau / 10_800.0).sqrt();
        assert!(
            (v.sqrt() / expected - 1.0).abs() < 0.1,
            "τ = {tau} s: {} vs {expected}",
            v.sqrt()
        );
    }
}

/// The Gauss–Markov bias instability (σ_b, correlation time T) peaks at
/// 0.617·σ_b near τ = 1.89·T (the closed form
/// σ²(τ) = σ_b²·(2x − 3 + 4e^−x − e^−2x)/x², x = τ/T), which is how the
/// simulator's `bias_instability_deg_h` relates to the flat-region B.
#[test]
fn gauss_markov_bias_peaks_where_the_closed_form_says() {
    let (sigma_b, t_c) = (0.5, 1.0);
    let sim = simulate(&quiet(
        200.0,
        DtgNoise {
            bias_instability_deg_h: sigma_b,
            bias_instability_tau_s: t_c,
            ..DtgNoise::default()
        },
    ))
    .unwrap();
    let r = &sim.record;
    let closed = |tau: f64| {
        let x = tau / t_c;
        sigma_b * ((2.0 * x - 3.0 + 4.0 * (-x).exp() - (-2.0 * x).exp()) / (x * x)).sqrt()
    };
    let factors = [25, 50, 100, 200];
    let mut pooled = [0.0; 4];
    for c in Channel::ALL {
        let adev = overlapping_adev(r.gyro_named(c.name()).unwrap(), r.dt(), &factors).unwrap();
        for (p, a) in pooled.iter_mut().zip(adev) {
            *p += a * a / 6.0;
        }
    }
    for (m, v) in factors.iter().zip(pooled) {
        let tau = *m as f64 * r.dt();
        // The GM sampled at 50 Hz is the continuous one to O(dt/T) = 2%.
        assert!(
            (v.sqrt() / closed(tau) - 1.0).abs() < 0.15,
            "τ = {tau} s: {} vs {}",
            v.sqrt(),
            closed(tau)
        );
    }
    assert!((closed(1.89 * t_c) / sigma_b - 0.617).abs() < 1e-3);
}

/// allantools 2024.6 (`allantools.oadev(y, rate=50, data_type="freq",
/// taus=m·0.02)`) on a fixed series: 1000 values of a linear congruential
/// generator, x ← (1103515245·x + 12345) mod 2³¹ from x = 12345, as
/// x/2³¹ − 0.5 + 1e-4·k. Printed by `peers/scripts/allan.py fixture`.
#[test]
fn agrees_with_allantools_on_a_fixed_series() {
    const ALLANTOOLS: [(usize, f64); 7] = [
        (1, 0.2926653652038885),
        (2, 0.20412704958184263),
        (4, 0.1342510750094769),
        (8, 0.10368465612831859),
        (16, 0.07414277246142748),
        (32, 0.046771270266729725),
        (64, 0.03049281158583224),
    ];
    let mut x: u64 = 12345;
    let y: Vec<f64> = (0..1000)
        .map(|k| {
            x = (1_103_515_245 * x + 12345) % (1 << 31);
            x as f64 / (1u64 << 31) as f64 - 0.5 + 1e-4 * k as f64
        })
        .collect();
    let factors: Vec<usize> = ALLANTOOLS.iter().map(|(m, _)| *m).collect();
    let ours = overlapping_adev(&y, 0.02, &factors).unwrap();
    for ((m, theirs), o) in ALLANTOOLS.iter().zip(ours) {
        assert!((o / theirs - 1.0).abs() < 1e-12, "m = {m}: {o} vs {theirs}");
    }
}
