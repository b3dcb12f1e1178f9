//! Several IMUs on one vehicle (issue 34 §3): a unit file groups sensors
//! into IMUs (`imu = "NAME"` on `[[gyro]]` and `[[accel]]`), a unit of k
//! triads with several accelerometer triads is accepted, each IMU has its
//! own specific force beside the unit's, and ground calibration
//! compensates each IMU's accelerometer triad. `units/multi-imu.toml`
//! describes the real three-IMU flights of `data/realdata/multi-imu/`
//! (checked against them).

use nav_sensors::accel::{AccelCoefficients, compensate_triad};
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, simulate_unit};
use nav_sensors::unit::Unit;

fn multi_imu() -> Unit {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../units/multi-imu.toml");
    Unit::load(path).unwrap()
}

/// The header of both flights (their README).
const HEADER: &str = "t,g1x,g1y,g1z,g2x,g2y,g2z,g3x,g3y,g3z,ax,ay,az,a2x,a2y,a2z,a3x,a3y,a3z";

#[test]
fn the_multi_imu_unit_is_three_aligned_triads_named_as_the_flights_columns() {
    let u = multi_imu();
    let mut columns = vec![u.columns().time.as_str()];
    columns.extend(u.gyro_names());
    columns.extend(u.accel_names());
    assert_eq!(columns.join(","), HEADER);
    assert_eq!(u.imu_names(), ["imu1", "imu2", "imu3"]);
    assert_eq!(u.residue_names(), ["P0", "P1", "P2", "P3", "P4", "P5"]);
    assert_eq!(u.imu_accel_names(0), ["ax", "ay", "az"]);
    assert_eq!(u.imu_accel_names(8), ["a3x", "a3y", "a3z"]);
    // Written and read back with its IMUs.
    assert!(u.to_toml().contains("imu = \"imu2\""));
    assert_eq!(Unit::from_toml(&u.to_toml(), "copy.toml").unwrap(), u);
    let json = serde_json::to_string(&u).unwrap();
    assert_eq!(serde_json::from_str::<Unit>(&json).unwrap(), u);
}

#[test]
fn each_imu_has_its_own_specific_force_and_the_unit_the_least_squares_one() {
    let u = multi_imu();
    let a = [0.1, -0.2, 0.98, 0.12, -0.21, 1.01, 0.08, -0.19, 0.99];
    for (k, imu) in ["imu1", "imu2", "imu3"].iter().enumerate() {
        let f = u.imu_specific_force(imu, &a).unwrap();
        assert_eq!([f.x, f.y, f.z], [a[3 * k], a[3 * k + 1], a[3 * k + 2]]);
        assert_eq!(u.gyro_specific_force(3 * k + 2, &a), f);
    }
    // Three triads on the same axes: the least-squares force is their mean.
    let f = u.specific_force(&a);
    for j in 0..3 {
        let mean = (a[j] + a[3 + j] + a[6 + j]) / 3.0;
        assert!((f[j] - mean).abs() < 1e-15, "{j}");
    }
    assert!(u.imu_specific_force("imu4", &a).is_none());
}

#[test]
fn ground_calibration_compensates_each_imus_triad() {
    let u = multi_imu();
    let s = Scenario {
        duration_s: 1.0,
        ..Scenario::triaxial_clean()
    };
    let sim = simulate_unit(&u, &s).unwrap();
    // Each triad is compensated with its own three tables, jointly.
    let out = sim.calibration.compensate(&u, &sim.record).unwrap();
    for imu in 0..3 {
        let names = u.imu_accel_names(3 * imu);
        let tables = [0, 1, 2].map(|j| sim.calibration.accels[names[j]]);
        for i in [0, 17, 49] {
            let raw =
                nalgebra::Vector3::from([0, 1, 2].map(|j| sim.record.accel_at(3 * imu + j)[i]));
            let want = compensate_triad(&tables, &raw);
            for j in 0..3 {
                assert_eq!(
                    out.accel_at(3 * imu + j)[i],
                    want[j],
                    "imu {imu} sample {i}"
                );
                assert_ne!(out.accel_at(3 * imu + j)[i], raw[j]);
            }
        }
    }
    // One IMU's table moves its triad only.
    let mut cal = UnitCalibration::ideal(&u);
    cal.accels.insert(
        "a2z".into(),
        AccelCoefficients {
            bias_ug: 1000.0,
            ..Default::default()
        },
    );
    let moved = cal.compensate(&u, &sim.record).unwrap();
    assert!((sim.record.accel_at(5)[10] - moved.accel_at(5)[10] - 1e-3).abs() < 1e-6);
    assert_eq!(moved.accel_at(2), sim.record.accel_at(2));
    assert_eq!(moved.accel_at(8), sim.record.accel_at(8));
}

#[test]
fn imu_keys_are_checked() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../units/multi-imu.toml"
    ))
    .unwrap();
    let err = |t: &str| Unit::from_toml(t, "u.toml").unwrap_err().to_string();
    assert_eq!(
        err(&text.replacen("imu = \"imu1\"", "imu = \" \"", 1)),
        "u.toml: gyro[0].imu is empty; name the IMU or leave the key out"
    );
    // A gyro's IMU without accelerometers spanning 3-D.
    let one = text.replacen("imu = \"imu1\"", "imu = \"imu9\"", 1);
    assert_eq!(
        err(&one),
        "u.toml: gyro[0].imu = \"imu9\": IMU imu9 has 0 accelerometer(s) whose input axes span 0 dimension(s); a gyro's IMU needs accelerometers spanning all three (give them imu = \"imu9\"), or leave the gyro's imu out"
    );
    // An IMU of accelerometers alone, or sensors naming none, are fine.
    let no_gyro_imu = text.replace(
        "model = \"rate\"\ninput = [1.0, 0.0, 0.0]\nimu = \"imu1\"",
        "model = \"rate\"\ninput = [1.0, 0.0, 0.0]",
    );
    let u = Unit::from_toml(&no_gyro_imu, "u.toml").unwrap();
    assert_eq!(u.imu_accel_names(0).len(), 9);
}

/// The real flights (in-tree, data/realdata/multi-imu/): read with the unit, one
/// segment each at 120 Hz, and the README's rms of g1 and of g1 − g2
/// (deg/s) come back.
#[test]
fn the_real_flights_read_with_the_unit() {
    let u = multi_imu();
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/realdata/multi-imu");
    let table = [
        (
            "qdr_horizontal_path11.csv",
            6613,
            [40.6, 15.2, 4.5],
            [1.881, 4.140, 0.582],
        ),
        (
            "qdr_vertical_path1.csv",
            3901,
            [11.6, 23.5, 5.4],
            [1.464, 0.896, 0.475],
        ),
    ];
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
    for (file, rows, g1, g1_g2) in table {
        let read = Record::read_with_unit(dir.join(file), &u).unwrap();
        assert_eq!(read.records.len(), 1, "{file}");
        let r = &read.records[0];
        assert_eq!(r.len(), rows, "{file}");
        assert!(
            (1.0 / read.time.median_step_s - 120.0).abs() < 0.1,
            "{file}"
        );
        for j in 0..3 {
            let deg_s =
                |k: usize| -> Vec<f64> { r.gyro_at(k).iter().map(|v| v / 3600.0).collect() };
            assert!((rms(&deg_s(j)) - g1[j]).abs() < 0.05, "{file} g1 axis {j}");
            let d: Vec<f64> = deg_s(j)
                .iter()
                .zip(deg_s(3 + j))
                .map(|(a, b)| a - b)
                .collect();
            assert!(
                (rms(&d) - g1_g2[j]).abs() < 0.0005,
                "{file} g1-g2 axis {j}: {}",
                rms(&d)
            );
        }
    }
}
