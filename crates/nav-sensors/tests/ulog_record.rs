//! A PX4 ULog file goes through the one record reader
//! ([`Record::read_with_unit`]) and gives the records of the CSV pyulog
//! made of it: the three logs of `../shared/realdata/ulog/` (PX4/pyulog's
//! test logs, BSD-3-Clause, `LICENSE-pyulog.md` there) against their CSVs
//! in `data/realdata/` (the README there says which came from which). Same
//! segments, time bit for bit, every gyro and accelerometer value within the
//! CSV's 6 printed significant digits, and the Allan deviation of every
//! gyro on every segment (what `allan` prints) within 1e-4 relative (the
//! CSV's rounding, at most 5e-6 relative per value, averaged).
//!
//! `../shared` is beside the project on developers' machines and in CI;
//! where it is absent these tests print a notice and pass.

use std::path::PathBuf;

use nav_sensors::noise::AllanCurve;
use nav_sensors::record::{Record, RecordError, UnitRecords};
use nav_sensors::unit::Unit;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The ULog file, or `None` (with a notice) where `../shared` is absent.
fn ulg(name: &str) -> Option<PathBuf> {
    let path = root().join("../shared/realdata/ulog").join(name);
    if !path.exists() {
        eprintln!("notice: {} absent; skipping", path.display());
        return None;
    }
    Some(path)
}

fn triad() -> Unit {
    Unit::builtin("triad").unwrap()
}

fn read(path: &std::path::Path) -> UnitRecords {
    Record::read_with_unit(path, &triad()).unwrap_or_else(|e| panic!("{e}"))
}

/// `b` within `rel` of `a`, relative (absolute near 0: the CSV's 6 digits
/// of a value printed around its own magnitude).
fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()) + 1e-12
}

fn same_records(ulg_name: &str, csv_name: &str) {
    let Some(path) = ulg(ulg_name) else { return };
    let from_ulog = read(&path);
    let from_csv = read(&root().join("data/realdata").join(csv_name));
    assert_eq!(
        from_ulog.time.gaps.len(),
        from_csv.time.gaps.len(),
        "{ulg_name}"
    );
    assert_eq!(
        from_ulog.records.len(),
        from_csv.records.len(),
        "{ulg_name}"
    );
    for (u, c) in from_ulog.records.iter().zip(&from_csv.records) {
        assert_eq!(u.len(), c.len(), "{ulg_name}");
        assert_eq!(u.gyro_names(), c.gyro_names());
        assert_eq!(u.accel_names(), c.accel_names());
        // The time bit for bit: a step exactly at the gap threshold (sample.ulg
        // has two of 12 ms against a 4 ms median) is judged alike.
        assert_eq!(u.t(), c.t(), "{ulg_name}");
        for k in 0..3 {
            for (a, b) in u.gyro_at(k).iter().zip(c.gyro_at(k)) {
                assert!(
                    close(*a, *b, 5.1e-6),
                    "{ulg_name} gyro {k}: {a} vs {b} deg/h"
                );
            }
            for (a, b) in u.accel_at(k).iter().zip(c.accel_at(k)) {
                assert!(close(*a, *b, 5.1e-6), "{ulg_name} accel {k}: {a} vs {b} g");
            }
        }
        // `allan`'s figures on the segment: the overlapping Allan deviation
        // of every gyro at every octave.
        if u.len() < 64 {
            continue;
        }
        for k in 0..3 {
            let cu = AllanCurve::octaves(u.gyro_at(k), u.dt(), 0.683).unwrap();
            let cc = AllanCurve::octaves(c.gyro_at(k), c.dt(), 0.683).unwrap();
            assert_eq!(cu.tau_s().len(), cc.tau_s().len());
            for (a, b) in cu.tau_s().iter().zip(cc.tau_s()) {
                assert!(close(*a, b, 1e-6), "{ulg_name}: τ {a} vs {b}");
            }
            for (a, b) in cu.adev().iter().zip(cc.adev()) {
                assert!(close(*a, b, 1e-4), "{ulg_name} gyro {k}: ADEV {a} vs {b}");
            }
        }
    }
}

#[test]
fn sample_ulg_reads_as_px4_auav_x21_handheld_csv() {
    same_records("sample.ulg", "px4_auav_x21_handheld.csv");
}

#[test]
fn sample_appended_multiple_ulg_reads_as_px4_fmuv4pro_bench_csv() {
    same_records("sample_appended_multiple.ulg", "px4_fmuv4pro_bench.csv");
}

#[test]
fn sample_log_small_ulg_reads_as_px4_cubeorange_vtol_ground_csv() {
    same_records("sample_log_small.ulg", "px4_cubeorange_vtol_ground.csv");
}

/// A log is told by its bytes, not its name: a ULog named `.csv` reads as
/// ULog, and a unit without a `[ulog]` table (not a triad on x, y, z) is
/// refused naming the table to add.
#[test]
fn a_ulog_is_told_by_its_bytes_and_a_unit_without_a_table_is_refused() {
    let Some(path) = ulg("sample_log_small.ulg") else {
        return;
    };
    let renamed = std::env::temp_dir().join(format!(
        "nav-sensors-test-ulog-named-{}.csv",
        std::process::id()
    ));
    std::fs::copy(&path, &renamed).unwrap();
    let named = read(&renamed);
    std::fs::remove_file(&renamed).unwrap();
    assert_eq!(named.records, read(&path).records);
    let err = Record::read_with_unit(&path, &Unit::builtin("tetra").unwrap()).unwrap_err();
    assert!(matches!(err, RecordError::NoUlogTable { .. }), "{err}");
    assert!(err.to_string().contains("[ulog]"), "{err}");
}

/// A unit file's `[ulog]` table: the three gyros from `sensor_gyro`
/// instance 0 (`x`, `y`, `z`, timed by `timestamp_sample`), the
/// accelerometers from `sensor_accel`, the temperature from
/// `sensor_gyro.temperature`. The rows are the gyro's own samples, the
/// accelerometers are interpolated onto them, the temperature is °C.
#[test]
fn a_unit_files_ulog_table_names_other_topics() {
    let Some(path) = ulg("sample_log_small.ulg") else {
        return;
    };
    let toml = Unit::builtin_toml("triad")
        .unwrap()
        .replace("time = \"t\"", "time = \"t\"\ntemperature = \"imu_temp\"")
        + r#"
[ulog]
base = "gx"
[ulog.columns]
gx = { topic = "sensor_gyro", field = "x", time = "timestamp_sample" }
gy = { topic = "sensor_gyro", field = "y", time = "timestamp_sample" }
gz = { topic = "sensor_gyro", field = "z", time = "timestamp_sample" }
ax = { topic = "sensor_accel", field = "x", time = "timestamp_sample" }
ay = { topic = "sensor_accel", field = "y", time = "timestamp_sample" }
az = { topic = "sensor_accel", field = "z", time = "timestamp_sample" }
imu_temp = { topic = "sensor_gyro", field = "temperature", time = "timestamp_sample" }
"#;
    let unit = Unit::from_toml(&toml, "raw-imu.toml").unwrap_or_else(|e| panic!("{e}"));
    let r = Record::read_with_unit(&path, &unit).unwrap_or_else(|e| panic!("{e}"));
    let rec = &r.records[0];
    let temp = rec.temperature().unwrap();
    // The README: the CubeOrange's sensor_gyro reads 40.0–40.4 °C.
    assert!(temp.iter().all(|t| (39.5..41.0).contains(t)), "{temp:?}");
    // On the ground: the specific force is about 1 g, and the raw gyro
    // reads under 5 deg/s.
    let i = rec.len() / 2;
    let f = (0..3)
        .map(|k| rec.accel_at(k)[i].powi(2))
        .sum::<f64>()
        .sqrt();
    assert!((f - 1.0).abs() < 0.1, "{f} g");
    for k in 0..3 {
        assert!(
            rec.gyro_at(k)[i].abs() < 5.0 * 3600.0,
            "{}",
            rec.gyro_at(k)[i]
        );
    }
    // A table that forgets a gyro is refused when the unit loads.
    let forgot = toml.replace(
        "gz = { topic = \"sensor_gyro\", field = \"z\", time = \"timestamp_sample\" }\n",
        "",
    );
    let err = Unit::from_toml(&forgot, "raw-imu.toml").unwrap_err();
    assert!(err.to_string().contains("no entry for 'gz'"), "{err}");
}
