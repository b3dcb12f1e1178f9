//! The test campaign (issue 12): every built-in simulates and writes its
//! files, truth included; the flight moves gravity among the sensor axes
//! and varies the rates the gyros see.

use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::sim::{Scenario, SimError, UnitSimulation, UnitTruth, simulate_unit};
use nav_sensors::unit::Unit;
use stats::{mean, std_dev};

/// The paper's unit simulated on `s`.
fn simulate(s: &Scenario) -> Result<UnitSimulation, SimError> {
    simulate_unit(&Unit::paper(), s)
}

#[test]
fn every_builtin_simulates_and_writes_its_truth() {
    let dir = std::env::temp_dir().join(format!("nav-sensors-campaign-{}", std::process::id()));
    for name in Scenario::BUILTIN {
        // Two seconds of each: what is tested is that the scenario runs
        // and its files are written, not its physics.
        let s = Scenario {
            duration_s: 2.0,
            ..Scenario::builtin(name).unwrap()
        };
        let sim = simulate(&s).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(sim.record.len(), 100, "{name}");
        let out = dir.join(name);
        sim.write_dir(&out).unwrap();
        let text = std::fs::read_to_string(out.join("truth.json")).unwrap();
        // The paper's truth file (no `unit` key) reads as the unit's truth.
        let top: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(top.get("unit").is_none(), "{name}");
        let truth = UnitTruth::from_json(&text, "truth.json").unwrap();
        // JSON keeps the numbers to rounding, the scenario exactly.
        assert_eq!(truth.scenario, sim.truth.scenario, "{name}");
        for (ch, want) in truth.channels.iter().zip(&sim.truth.channels) {
            let want = want.noise_floor_deg_h;
            assert!(
                (ch.noise_floor_deg_h - want).abs() <= 1e-12 * want,
                "{name} {}",
                ch.channel
            );
        }
        assert!(out.join("record.csv").is_file() && out.join("calibration.json").is_file());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn campaign_runs_drive_their_own_axis() {
    // 30 s of each shaker run at full level (the schedule's 0-dB part
    // starts at 30 s): the driven axis carries the vibration.
    for (name, axis) in [
        ("x-axis", Axis::X),
        ("y-axis", Axis::Y),
        ("z-axis", Axis::Z),
    ] {
        let s = Scenario {
            duration_s: 45.0,
            ..Scenario::builtin(name).unwrap()
        };
        let sim = simulate(&s).unwrap();
        let tail = |a: Axis| std_dev(&sim.record.accel_named(a.column()).unwrap()[32 * 50..]);
        let driven = tail(axis);
        for other in Axis::ALL.into_iter().filter(|&a| a != axis) {
            assert!(
                driven > 5.0 * tail(other),
                "{name}: {axis:?} {driven} g vs {other:?} {} g",
                tail(other)
            );
        }
        // The unit stands z up on every shaker run.
        assert!((mean(sim.record.accel_named(Axis::Z.column()).unwrap()) - 1.0).abs() < 0.01);
    }
}

/// The flight, whole: 12 minutes at 4 kHz (about 20 s in release).
#[test]
fn flight_moves_gravity_among_the_axes_and_varies_the_rates() {
    let s = Scenario::builtin("flight").unwrap();
    assert!(s.duration_s >= 600.0, "at least 10 minutes");
    let sim = simulate(&s).unwrap();
    let rec = &sim.record;
    let ax = rec.accel_named(Axis::X.column()).unwrap();
    let ay = rec.accel_named(Axis::Y.column()).unwrap();
    let az = rec.accel_named(Axis::Z.column()).unwrap();
    // One-second means, to look through the vibration.
    let secs = |x: &[f64]| -> Vec<f64> { x.chunks(50).map(mean).collect() };
    let (mx, my, mz) = (secs(ax), secs(ay), secs(az));
    let max = |v: &[f64]| v.iter().cloned().fold(f64::MIN, f64::max);
    let min = |v: &[f64]| v.iter().cloned().fold(f64::MAX, f64::min);
    // On the ground, level: gravity on z alone.
    assert!(mx[..50].iter().all(|v| v.abs() < 0.05) && my[..50].iter().all(|v| v.abs() < 0.05));
    // The take-off roll pushes x; the climb's pitch keeps gravity on x.
    assert!(max(&mx[80..120]) > 0.15, "take-off: {}", max(&mx[80..120]));
    assert!(mean(&mx[140..260]) > 0.1, "climb: {}", mean(&mx[140..260]));
    // S-turns roll gravity onto y both ways, and z drops below 1 g.
    // Phases (s): taxi 0–80, take-off roll 80–115, rotation and climb
    // 115–270, level-off and cruise 270–380, left turn 380–440, cruise
    // 440–480, right turn 480–540, S-turns 540–630, descent and approach.
    let s_turns = &my[545..630];
    assert!(
        max(s_turns) > 0.4 && min(s_turns) < -0.4,
        "y: {} to {}",
        min(s_turns),
        max(s_turns)
    );
    assert!(min(&mz[545..630]) < 0.9);
    // Coordinated turns load z (1/cos bank) and leave y near zero.
    assert!(
        mean(&mz[390..438]) > 1.05,
        "left turn load: {}",
        mean(&mz[390..438])
    );
    assert!(mean(&my[390..438]).abs() < 0.05, "{}", mean(&my[390..438]));
    assert!(
        mean(&mz[490..538]) > 1.1,
        "right turn load: {}",
        mean(&mz[490..538])
    );
    // The rates vary: a gyro's one-second means move by deg/s in the
    // S-turns, by little more than its drift noise in steady cruise.
    for c in Channel::ALL {
        let g = secs(rec.gyro_named(c.name()).unwrap());
        let spread = std_dev(&g[545..630]);
        assert!(
            spread > 1000.0,
            "{c}: rate spread in the S-turns {spread} deg/h"
        );
        assert!(
            std_dev(&g[300..380]) < 10.0,
            "{c}: cruise {} deg/h",
            std_dev(&g[300..380])
        );
    }
    // The temperature ramps.
    let temp = rec.extra("temp").unwrap();
    assert!(temp[temp.len() - 1] - temp[0] > 3.0);
}
