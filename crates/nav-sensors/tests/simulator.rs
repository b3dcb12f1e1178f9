//! The simulator's physics and files, tested through the public API.

use nav_sensors::accel::{AccelCoefficients, AccelNoise};
use nav_sensors::calibration::GyroCoefficients;
use nav_sensors::dtg::{DtgCoefficients, DtgNoise, DtgTerm};
use nav_sensors::geometry::{Channel, ChannelFrame, residues};
use nav_sensors::record::Axis;
use nav_sensors::record::Record;
use nav_sensors::sim::{
    CalibrationError, HiddenEffect, Scenario, ScenarioError, SimError, UnitSimulation,
    simulate_unit,
};
use nav_sensors::unit::Unit;
use nav_sensors::vibration::{Drive, LevelSchedule, PsdTable, Segment, VibrationConfig};
use stats::mean;

/// The paper's unit simulated on `s`.
fn simulate(s: &Scenario) -> Result<UnitSimulation, SimError> {
    simulate_unit(&Unit::paper(), s)
}

/// The record compensated with the simulation's ground calibration.
fn compensate(sim: &UnitSimulation) -> Record {
    sim.calibration.compensate(&sim.unit, &sim.record).unwrap()
}

/// The ground calibration's DTG table of a channel.
fn calibrated(sim: &UnitSimulation, channel: &str) -> DtgCoefficients {
    match sim.calibration.gyros[channel] {
        GyroCoefficients::Dtg(t) => t,
        GyroCoefficients::Rate(_) => panic!("{channel} is a DTG channel"),
    }
}

/// The default site and rates with ideal, noiseless sensors, no vibration,
/// constant temperature at the reference and an exact calibration.
fn ideal(duration_s: f64) -> Scenario {
    let mut s = Scenario {
        duration_s,
        ..Scenario::default()
    };
    s.vibration = VibrationConfig::default();
    s.gyros.channels.clear();
    s.accels.axes.clear();
    s.gyros.noise = DtgNoise::default();
    s.accels.noise = AccelNoise::default();
    s.thermal.vibration_heating_c = 0.0;
    s.thermal.sensor_noise_c = 0.0;
    s.calibration_error = CalibrationError::none();
    s
}

fn earth_on(channel: Channel, s: &Scenario) -> f64 {
    let w = s.site.earth_rate_cluster_deg_h().unwrap();
    ChannelFrame::of(channel).resolve(&w).i
}

fn sine_z(frequency_hz: f64, amplitude_g: f64) -> VibrationConfig {
    VibrationConfig {
        drives: vec![Drive::Sine {
            axis: Axis::Z,
            frequency_hz,
            amplitude_g,
            phase_deg: 0.0,
            transverse: Default::default(),
        }],
        ..Default::default()
    }
}

#[test]
fn ideal_stationary_unit_reads_earth_rate_and_one_g_with_zero_residues() {
    let s = ideal(4.0);
    let sim = simulate(&s).unwrap();
    let r = &sim.record;
    for c in Channel::ALL {
        for v in r.gyro_named(c.name()).unwrap() {
            assert!((v - earth_on(c, &s)).abs() < 1e-9, "{c}: {v}");
        }
    }
    for i in 0..r.len() {
        assert!((r.accel_named(Axis::Z.column()).unwrap()[i] - 1.0).abs() < 1e-12);
        assert!(r.accel_named(Axis::X.column()).unwrap()[i].abs() < 1e-12);
        for k in residues(&r.gyro_row(i).try_into().unwrap()) {
            assert!(k.abs() < 1e-9);
        }
    }
    // x north, z up at 8.5° N: Ω·cos φ on X, Ω·sin φ on Z.
    let lat = 8.5f64.to_radians();
    assert!((r.gyro_named(Channel::X.name()).unwrap()[0] - 15.041067 * lat.cos()).abs() < 1e-6);
    assert!((r.gyro_named(Channel::Z.name()).unwrap()[0] - 15.041067 * lat.sin()).abs() < 1e-6);
}

/// Sine vibration of amplitude A on an anisoelastic coefficient D: the
/// 50-Hz output drifts by the analytic mean D·A²/2 — and compensation with
/// the exact coefficient at 50 Hz (D·mean(a)²) cannot remove it.
#[test]
fn sine_rectifies_through_anisoelastic_terms_as_d_a_squared_over_two() {
    let (d, amp) = (0.1, 5.0);
    let mut s = ideal(4.0);
    // 150 Hz: exactly three cycles per 20-ms interval.
    s.vibration = sine_z(150.0, amp);
    s.gyros.channels.insert(
        Channel::Z,
        DtgCoefficients {
            gg_ii_deg_h_g2: d,
            ..Default::default()
        },
    );
    // X1: f_I = f_S = −f_z/√2, so gg_IS sees f_z²/2.
    s.gyros.channels.insert(
        Channel::X1,
        DtgCoefficients {
            gg_is_deg_h_g2: d,
            ..Default::default()
        },
    );
    let sim = simulate(&s).unwrap();
    let analytic = d * amp * amp / 2.0;
    let z = sim.record.gyro_named(Channel::Z.name()).unwrap();
    let x1 = sim.record.gyro_named(Channel::X1.name()).unwrap();
    for i in 0..sim.record.len() {
        let drift_z = z[i] - earth_on(Channel::Z, &s) - d; // d·1 g² from gravity
        assert!(
            (drift_z - analytic).abs() < 0.01 * analytic,
            "Z sample {i}: {drift_z}"
        );
        let drift_x1 = x1[i] - earth_on(Channel::X1, &s) - d / 2.0;
        assert!(
            (drift_x1 - analytic / 2.0).abs() < 0.01 * analytic / 2.0,
            "X1 sample {i}"
        );
    }
    let compensated = compensate(&sim);
    let left = mean(compensated.gyro_named(Channel::Z.name()).unwrap()) - earth_on(Channel::Z, &s);
    assert!(
        (left - analytic).abs() < 0.01 * analytic,
        "compensation left {left}"
    );
}

#[test]
fn non_commensurate_sine_rectifies_to_the_same_mean() {
    let (d, amp) = (0.05, 3.0);
    let mut s = ideal(20.0);
    s.vibration = sine_z(137.3, amp);
    s.gyros.channels.insert(
        Channel::Z,
        DtgCoefficients {
            gg_ii_deg_h_g2: d,
            ..Default::default()
        },
    );
    let sim = simulate(&s).unwrap();
    let drift =
        mean(sim.record.gyro_named(Channel::Z.name()).unwrap()) - earth_on(Channel::Z, &s) - d;
    let analytic = d * amp * amp / 2.0;
    assert!(
        (drift - analytic).abs() < 0.01 * analytic,
        "{drift} vs {analytic}"
    );
}

/// Angular vibration (fixture rocking driven by a 400-Hz sine) rectifies
/// through the 2N term at twice the 200-Hz spin frequency and through
/// anisoinertia, by the analytic means.
#[test]
fn angular_vibration_rectifies_through_2n_and_anisoinertia() {
    use nav_sensors::vibration::{Rocking, STANDARD_GRAVITY_M_S2};
    let (f, amp) = (400.0, 2.0); // Hz, g: 2N of the default 200-Hz spin
    let (rx, ry) = (0.5, 0.3); // rad/s per m/s about x and y
    let mut s = ideal(4.0);
    s.vibration = sine_z(f, amp);
    s.vibration.rocking = Rocking {
        rad_s_per_m_s: [[0.0, 0.0, rx], [0.0, 0.0, ry], [0.0; 3]],
    };
    let (k2n, kai) = (2.0, 0.5);
    // X: I = x, so ω_I is the rocking about x. X1: I = X1 = (0, h, −h),
    // O = x, so ω_I·ω_O = h·ω_y·ω_x.
    s.gyros.channels.insert(
        Channel::X,
        DtgCoefficients {
            rect_2n_deg_h_per_deg_s2: k2n,
            ..Default::default()
        },
    );
    s.gyros.channels.insert(
        Channel::X1,
        DtgCoefficients {
            ai_io_deg_h_per_deg_s2: kai,
            ..Default::default()
        },
    );
    let sim = simulate(&s).unwrap();
    // Velocity amplitude A·g0/(2πf); rocking amplitudes in deg/s.
    let v = amp * STANDARD_GRAVITY_M_S2 / (std::f64::consts::TAU * f);
    let (wx, wy) = ((rx * v).to_degrees(), (ry * v).to_degrees());
    let h = std::f64::consts::FRAC_1_SQRT_2;
    // Skip the first 0.2 s: the 2N band-pass (Q = 10) settles in ~10 ms.
    let tail = |c: Channel| mean(&sim.record.gyro_named(c.name()).unwrap()[10..]) - earth_on(c, &s);
    let rect = tail(Channel::X);
    let expect = k2n * wx * wx / 2.0;
    assert!(
        (rect - expect).abs() < 0.02 * expect,
        "2N: {rect} vs {expect}"
    );
    let ai = tail(Channel::X1);
    let expect = kai * h * wx * wy / 2.0;
    assert!(
        (ai - expect).abs() < 0.02 * expect,
        "anisoinertia: {ai} vs {expect}"
    );
}

/// K2 rectifies random vibration into a bias K2·σ² on the accelerometer.
#[test]
fn accelerometer_k2_rectifies_random_vibration_into_k2_sigma_squared() {
    let mut s = ideal(20.0);
    let psd = PsdTable::navmat_p9492();
    s.vibration = VibrationConfig {
        drives: vec![Drive::Random {
            axis: Axis::Z,
            psd: psd.clone(),
            gain_db: 0.0,
            transverse: Default::default(),
        }],
        ..Default::default()
    };
    let k2 = 20.0; // µg/g²
    s.accels.axes.insert(
        Axis::Z,
        AccelCoefficients {
            k2_ug_per_g2: k2,
            ..Default::default()
        },
    );
    s.accels.noise.density_ug_per_rt_hz = 10.0;
    let with_k2 = simulate(&s).unwrap();
    s.accels.axes.clear();
    let without = simulate(&s).unwrap();
    // Same seed, same vibration and noise: the difference of the az means is
    // the K2 term alone, K2·mean((1 g + v)²) = K2·(1 + σ²) with gravity in the
    // square. (A plain mean of az would also hold the servo loop's end
    // transient, group delay × last sample / N ≈ 30 µg here; the loop is
    // linear, so it cancels in the difference.)
    let shift_ug = (mean(with_k2.record.accel_named(Axis::Z.column()).unwrap())
        - mean(without.record.accel_named(Axis::Z.column()).unwrap()))
        * 1e6;
    let expect_ug = k2 * (1.0 + psd.grms().powi(2));
    // 1%: the realised variance matches the table's to < 0.01%.
    assert!(
        (shift_ug - expect_ug).abs() < 0.01 * expect_ug,
        "{shift_ug} µg vs {expect_ug} µg"
    );
}

#[test]
fn same_seed_gives_byte_identical_files_and_another_seed_differs() {
    let s = Scenario {
        duration_s: 6.0,
        ..Scenario::default()
    };
    let bytes = |s: &Scenario| {
        let sim = simulate(s).unwrap();
        let mut csv = Vec::new();
        sim.record.write_to(&mut csv, "mem").unwrap();
        (csv, sim.calibration.to_json(), sim.truth.to_json())
    };
    let a = bytes(&s);
    let b = bytes(&s);
    assert!(a == b, "two runs of one scenario differ");
    let c = bytes(&Scenario {
        seed: s.seed + 1,
        ..s.clone()
    });
    assert!(a.0 != c.0 && a.1 != c.1);
}

#[test]
fn scenario_files_are_the_builtin_scenarios() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    for name in Scenario::BUILTIN {
        let from_file = Scenario::load(dir.join(format!("{name}.toml"))).unwrap();
        assert_eq!(from_file, Scenario::builtin(name).unwrap(), "{name}");
    }
    assert_eq!(
        Scenario::default(),
        Scenario::builtin("paper_z_random").unwrap()
    );
}

/// The default scenario is built for the paper's experiment: after a perfect
/// ground calibration, what the vibration leaves on every channel is several
/// times the noise floor and scales with the vibration power.
#[test]
fn default_vibration_error_dominates_the_floor_and_follows_the_level() {
    let sim = simulate(&Scenario::default()).unwrap();
    let t = sim.record.t();
    for c in Channel::ALL {
        let ct = &sim.truth.channels[c.index()];
        let ratio = ct.rectification_expected_rms_deg_h / ct.noise_floor_deg_h;
        assert!(ratio > 4.0, "{c}: expected/floor {ratio}");
        assert!(ct.noise_floor_deg_h > ct.noise_rms_deg_h);
        // Mean unmodelled drift at 0 dB (40–68 s) against −6 dB (10–28 s): ×4 in power.
        let u = sim.components.get(&format!("{c}_unmodelled")).unwrap();
        let seg = |lo: f64, hi: f64| {
            let v: Vec<f64> = t
                .iter()
                .zip(u)
                .filter(|(t, _)| **t > lo && **t < hi)
                .map(|(_, u)| *u)
                .collect();
            mean(&v)
        };
        let r = seg(40.0, 68.0) / seg(10.0, 28.0);
        assert!((r - 4.0).abs() < 0.4, "{c}: 0 dB / −6 dB = {r}");
    }
    // Under a single-axis Z drive, channel X's a_O and a_S both follow a_z.
    let x = &sim.truth.channels[Channel::X.index()];
    assert!(
        x.collinear
            .iter()
            .any(|p| p.a == DtgTerm::GO.id() && p.b == DtgTerm::GS.id())
    );
}

#[test]
fn triaxial_scenarios_hide_what_they_say_and_nothing_else() {
    let clean = simulate(&Scenario::triaxial_clean()).unwrap();
    for ct in &clean.truth.channels {
        let c = &ct.channel;
        assert!(ct.collinear.is_empty(), "{c}: {:?}", ct.collinear);
        assert!(
            ct.calibration_error_rms_deg_h < 0.05 * ct.noise_floor_deg_h,
            "{c}: calibration error {} vs floor {}",
            ct.calibration_error_rms_deg_h,
            ct.noise_floor_deg_h
        );
    }
    assert!(clean.truth.hidden.is_empty());
    let hidden = simulate(&Scenario::triaxial_hidden()).unwrap();
    assert_eq!(hidden.truth.hidden.len(), 2);
    for h in &hidden.truth.hidden {
        let term: DtgTerm = h.term.parse().unwrap();
        assert_eq!(calibrated(&hidden, &h.channel).get(term), 0.0);
        assert!(h.coefficient != 0.0);
        // Visible but not trivially so: 7.2× on Y1 (gg_IS), 5.3× on Z
        // (temp) against floors that condition on the 50-Hz accelerations.
        assert!(
            (3.0..8.0).contains(&h.ratio_to_noise_floor),
            "{}/{}: {}",
            h.channel,
            h.term,
            h.ratio_to_noise_floor
        );
    }
    // The temperature ramp is in the record.
    let temp = hidden.record.extra("temp").unwrap();
    assert!(temp[temp.len() - 1] - temp[0] > 4.0);
}

#[test]
fn noise_floor_of_a_quiet_unit_is_the_angle_random_walk() {
    let mut s = ideal(40.0);
    s.gyros.noise.arw_deg_per_rt_h = 0.001;
    let sim = simulate(&s).unwrap();
    let expect = 60.0 * 0.001 / 0.02f64.sqrt();
    for c in Channel::ALL {
        let f = sim.truth.channels[c.index()].noise_floor_deg_h;
        // 2000 samples: the sample standard deviation is within ±5% with
        // probability > 0.99.
        assert!((f / expect - 1.0).abs() < 0.05, "{c}: {f} vs {expect}");
    }
}

#[test]
fn exact_calibration_compensates_a_quiet_record_to_earth_rate() {
    let mut s = Scenario {
        duration_s: 4.0,
        ..Scenario::default()
    };
    s.vibration = VibrationConfig::default();
    s.gyros.noise = DtgNoise::default();
    s.accels.noise = AccelNoise::default();
    s.thermal.vibration_heating_c = 0.0;
    s.thermal.sensor_noise_c = 0.0;
    s.calibration_error = CalibrationError::none();
    let sim = simulate(&s).unwrap();
    let comp = compensate(&sim);
    for c in Channel::ALL {
        let raw = sim.record.gyro_named(c.name()).unwrap()[0] - earth_on(c, &s);
        assert!(raw.abs() > 0.1, "{c} has errors to compensate");
        for v in comp.gyro_named(c.name()).unwrap() {
            assert!((v - earth_on(c, &s)).abs() < 1e-6, "{c}: {v}");
        }
    }
    for v in comp.accel_named(Axis::Z.column()).unwrap() {
        assert!((v - 1.0).abs() < 1e-12);
    }
}

#[test]
fn invalid_scenarios_are_typed_errors() {
    let mut s = Scenario::default();
    s.hidden.push(HiddenEffect {
        channel: Channel::X,
        term: DtgTerm::GgIS,
    });
    s.gyros
        .channels
        .get_mut(&Channel::X)
        .unwrap()
        .gg_is_deg_h_g2 = 0.0;
    assert!(matches!(
        simulate(&s),
        Err(SimError::Scenario(ScenarioError::HiddenIsZero {
            channel: Channel::X,
            term: DtgTerm::GgIS
        }))
    ));
    let s = Scenario {
        internal_rate_hz: 2000.0,
        ..Scenario::default()
    };
    assert!(matches!(
        s.validate(),
        Err(ScenarioError::OutOfRange {
            field: "internal_rate_hz",
            ..
        })
    ));
    let s = Scenario {
        output_rate_hz: 30.0,
        ..Scenario::default()
    };
    assert!(s.validate().is_err(), "4000/30 is not whole");
    let text = Scenario::default()
        .to_toml()
        .unwrap()
        .replace("seed =", "sed =");
    let err = Scenario::from_toml(&text, "typo.toml").unwrap_err();
    assert!(err.to_string().contains("sed"), "{err}");
    let mut s = Scenario::default();
    s.vibration.schedule = LevelSchedule::new(vec![Segment {
        duration_s: 1.0,
        level_db: Some(0.0),
        ramp_s: 2.0,
    }]);
    assert!(matches!(s.validate(), Err(ScenarioError::Vibration(_))));
}

/// The complete scenario example in docs/formats.md parses and runs.
#[test]
fn formats_doc_example_parses_and_simulates() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/formats.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let start = doc.find("```toml\n").expect("a toml block") + "```toml\n".len();
    let end = start + doc[start..].find("\n```").unwrap();
    let s = Scenario::from_toml(&doc[start..end], "formats.md").unwrap();
    assert_eq!(s.vibration.drives.len(), 3);
    assert_eq!(s.gyros.pulse_arcsec, Some(0.1));
    let sim = simulate(&s).unwrap();
    assert_eq!(sim.record.len(), 500);
    assert_eq!(sim.truth.hidden.len(), 1);
    assert_eq!(calibrated(&sim, "Y1").gg_is_deg_h_g2, 0.0);
}

/// Pulse quantisation: every output is a whole number of pulses per
/// interval, and the accumulated angle stays within one pulse of the
/// unquantised one (the remainder is carried).
#[test]
fn pulse_quantisation_carries_the_remainder() {
    let mut s = ideal(4.0);
    s.gyros.noise.arw_deg_per_rt_h = 0.001;
    let exact = simulate(&s).unwrap();
    let q_arcsec = 0.5;
    s.gyros.pulse_arcsec = Some(q_arcsec);
    let quant = simulate(&s).unwrap();
    let lsb_deg_h = q_arcsec / 0.02; // one pulse per interval, deg/h
    for c in Channel::ALL {
        let (mut a, mut b) = (0.0, 0.0);
        for (e, q) in exact
            .record
            .gyro_named(c.name())
            .unwrap()
            .iter()
            .zip(quant.record.gyro_named(c.name()).unwrap())
        {
            let pulses = q / lsb_deg_h;
            assert!((pulses - pulses.round()).abs() < 1e-6, "{c}: {q}");
            a += e;
            b += q;
            assert!(
                (a - b).abs() <= lsb_deg_h * (1.0 + 1e-9),
                "{c}: drifted by {}",
                a - b
            );
        }
    }
    // On X (14.9 deg/h of Earth rate, pulses every other interval or so) the
    // quantisation noise shows in the truth's sensor-noise part. (On Y, with
    // no Earth rate, the angle may never leave the first pulse: then the
    // output is exactly the true zero rate, and so is its noise.)
    let noise = |sim: &UnitSimulation| sim.truth.channels[Channel::X.index()].noise_rms_deg_h;
    assert!(noise(&quant) > 5.0 * noise(&exact));
}

#[test]
fn unknown_drive_fields_are_rejected() {
    let text = Scenario::default()
        .to_toml()
        .unwrap()
        .replace("gain_db = 0.0", "gain_db = 0.0\ntransvers = 0.1");
    let err = Scenario::from_toml(&text, "typo.toml").unwrap_err();
    assert!(err.to_string().contains("transvers"), "{err}");
}
