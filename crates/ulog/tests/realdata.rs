//! The three PX4 logs of `../shared/realdata/ulog/` (PX4/pyulog's test
//! logs, BSD-3-Clause, `LICENSE-pyulog.md` there) against the CSVs pyulog
//! 1.3.0 made from them (`data/realdata/convert.py`; the copies in
//! `data/realdata/`): the same rows, the time exact to the µs, every gyro
//! and accelerometer value equal once rounded to the CSV's 6 significant
//! digits, and the temperature within its printed 0.001 °C.
//!
//! `../shared` is beside the project on developers' machines and in CI;
//! where it is absent these tests print a notice and pass.

use std::path::PathBuf;

use ulog::{FieldSource, Ulog, UlogTable};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The log, or `None` (with a notice) where `../shared` is absent.
fn log(name: &str) -> Option<Ulog> {
    let path = root().join("../shared/realdata/ulog").join(name);
    if !path.exists() {
        eprintln!(
            "notice: {} absent; skipping (../shared is beside the project in CI)",
            path.display()
        );
        return None;
    }
    Some(Ulog::read(&path).unwrap())
}

/// The CSV's header and rows.
fn csv(name: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(root().join("data/realdata").join(name)).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// `v` rounded to 6 significant digits, as `%.6g` prints it.
fn six_digits(v: f64) -> f64 {
    format!("{v:.5e}").parse().unwrap()
}

const TRIAD: [&str; 6] = ["gx", "gy", "gz", "ax", "ay", "az"];

/// Reads the triad (plus `temp` if mapped) and compares every row.
fn same_samples(ulg: &str, csv_name: &str, table: UlogTable) {
    let Some(log) = log(ulg) else { return };
    let (header, rows) = csv(csv_name);
    let mut columns = TRIAD.to_vec();
    if table.columns.contains_key("temp") {
        columns.push("temp");
    }
    let joined = table.join(&log, &columns, 3.0).unwrap();
    assert_eq!(joined.t_s.len(), rows.len(), "{ulg}: rows");
    assert_eq!(joined.rows_dropped, 0, "{ulg}");
    for (k, name) in columns.iter().enumerate() {
        assert_eq!(header[k + 1], *name);
    }
    for (i, row) in rows.iter().enumerate() {
        let us = joined.time_us[i] - joined.start_us;
        assert_eq!((row[0] * 1e6).round() as u64, us, "{ulg} row {i}: t");
        assert_eq!(
            format!("{:.6}", joined.t_s[i]).parse::<f64>().unwrap(),
            row[0]
        );
        for (k, name) in columns.iter().enumerate() {
            let v = joined.column(name).unwrap()[i];
            let (want, got) = (row[k + 1], v);
            match *name {
                "gx" | "gy" | "gz" => assert_eq!(
                    six_digits(got * 180.0 / std::f64::consts::PI),
                    want,
                    "{ulg} row {i} {name}"
                ),
                "temp" => assert!(
                    (got - want).abs() <= 0.0005 + 1e-9,
                    "{ulg} row {i} temp {got} vs {want}"
                ),
                _ => assert_eq!(six_digits(got), want, "{ulg} row {i} {name}"),
            }
        }
    }
    // sensor_combined's accelerometer time offset is 0 in these logs (the
    // README's claim): every accelerometer row is on its own sample.
    let accel = joined
        .streams
        .iter()
        .find(|s| s.columns.contains(&"ax".to_string()))
        .unwrap();
    assert_eq!(
        (accel.exact_rows, accel.interpolated_rows),
        (rows.len(), 0),
        "{ulg}: {}",
        accel.line()
    );
    assert!(joined.interpolated_columns().is_empty());
}

fn triad() -> UlogTable {
    UlogTable::sensor_combined(["gx", "gy", "gz"], ["ax", "ay", "az"])
}

#[test]
fn sample_ulg_is_px4_auav_x21_handheld_csv() {
    same_samples("sample.ulg", "px4_auav_x21_handheld.csv", triad());
}

#[test]
fn sample_appended_multiple_ulg_is_px4_fmuv4pro_bench_csv() {
    // Its three appended data sections are read; the temperature is
    // sensor_combined's own baro_temp_celcius, on the same rows.
    let mut table = triad();
    table.columns.insert(
        "temp".into(),
        FieldSource::new("sensor_combined", "baro_temp_celcius"),
    );
    same_samples(
        "sample_appended_multiple.ulg",
        "px4_fmuv4pro_bench.csv",
        table,
    );
    let log = log("sample_appended_multiple.ulg");
    if let Some(log) = log {
        assert_eq!(log.header().appended_offsets.len(), 3);
        assert_eq!(log.integrity().appended_sections, 3);
        assert!(log.integrity().is_clean(), "{}", log.integrity().summary());
    }
}

#[test]
fn sample_log_small_ulg_is_px4_cubeorange_vtol_ground_csv() {
    same_samples(
        "sample_log_small.ulg",
        "px4_cubeorange_vtol_ground.csv",
        triad(),
    );
}

/// The CSV's temperature is sensor_gyro[0]'s (1 Hz), linearly interpolated
/// by numpy onto the gyro's time and held past its ends. The join
/// interpolates the same way inside its span and drops the rows outside
/// (it never extrapolates): the rows it keeps match the CSV to 0.001 °C.
#[test]
fn a_slow_topic_is_interpolated_within_its_span_only() {
    let Some(log) = log("sample_log_small.ulg") else {
        return;
    };
    let mut table = triad();
    table.columns.insert(
        "temp".into(),
        FieldSource::new("sensor_gyro", "temperature"),
    );
    let joined = table.join(&log, &["gx", "temp"], 3.0).unwrap();
    let gyro_t = log.series("sensor_gyro", 0, &[]).unwrap().time_us;
    let all = log.series("sensor_combined", 0, &[]).unwrap().time_us;
    let inside = all
        .iter()
        .filter(|&&t| t >= gyro_t[0] && t <= *gyro_t.last().unwrap())
        .count();
    assert_eq!(joined.time_us.len(), inside);
    assert_eq!(joined.rows_dropped, all.len() - inside);
    let temp = joined
        .streams
        .iter()
        .find(|s| s.columns == ["temp"])
        .unwrap();
    assert_eq!(temp.rows_outside, all.len() - inside, "{}", temp.line());
    assert_eq!(temp.exact_rows + temp.interpolated_rows, inside);
    let (_, rows) = csv("px4_cubeorange_vtol_ground.csv");
    let first = all.iter().position(|&t| t == joined.time_us[0]).unwrap();
    for (i, &v) in joined.column("temp").unwrap().iter().enumerate() {
        let want = rows[first + i][7];
        assert!(
            (v - want).abs() <= 0.0005 + 1e-9,
            "row {}: {v} vs {want}",
            first + i
        );
    }
}

/// Multi-instance topics: the three IMUs of the CubeOrange log, each its
/// own series, told apart by instance; a missing instance names those that
/// exist.
#[test]
fn multi_instance_topics_are_listed_and_read_by_instance() {
    let Some(log) = log("sample_log_small.ulg") else {
        return;
    };
    let gyros: Vec<u8> = log
        .topics()
        .iter()
        .filter(|t| t.name == "sensor_gyro")
        .map(|t| t.instance)
        .collect();
    assert_eq!(gyros, [0, 1, 2]);
    let ids: Vec<f64> = (0..3)
        .map(|k| log.series("sensor_gyro", k, &["device_id"]).unwrap().values[0][0])
        .collect();
    assert!(
        ids[0] != ids[1] && ids[1] != ids[2] && ids[0] != ids[2],
        "{ids:?}"
    );
    let err = log
        .series("sensor_gyro", 3, &["x"])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("has no instance 3 with data (it has: 0, 1, 2)"),
        "{err}"
    );
    // vehicle_imu's delta angles over their interval are rates (rad/s):
    // still on the ground, near zero.
    let mut table = UlogTable {
        base: None,
        columns: Default::default(),
    };
    for k in 0..3u8 {
        let mut s = FieldSource::new("vehicle_imu", "delta_angle[0]").instance(k);
        s.time = "timestamp_sample".into();
        s.interval = Some("delta_angle_dt".into());
        table.columns.insert(format!("g{k}"), s);
    }
    let joined = table.join(&log, &["g0", "g1", "g2"], 3.0).unwrap();
    for (name, v) in &joined.columns {
        assert!(v.iter().all(|x| x.abs() < 0.05), "{name}: {v:?}");
    }
    assert_eq!(joined.streams.len(), 3);
    // The two other IMUs sample at their own instants: their rows are
    // interpolated onto instance 0's, and the join says so.
    let resampled: Vec<&str> = joined
        .interpolated_columns()
        .iter()
        .map(|(c, _)| *c)
        .collect();
    assert_eq!(resampled, ["g1", "g2"]);
}

#[test]
fn dropouts_are_listed() {
    let Some(log) = log("sample.ulg") else { return };
    let d = &log.integrity().dropouts;
    assert_eq!(d.len(), 4);
    assert_eq!(d.iter().map(|d| d.duration_ms as u32).sum::<u32>(), 119);
    assert!(
        log.integrity()
            .summary()
            .starts_with("4 logger dropout(s), 119 ms in all")
    );
}

/// Every field of every topic of the three logs is found by its flattened
/// name and read, as many values as time stamps.
#[test]
fn every_listed_field_of_every_topic_reads() {
    for name in [
        "sample.ulg",
        "sample_appended_multiple.ulg",
        "sample_log_small.ulg",
    ] {
        let Some(log) = log(name) else { return };
        for t in log.topics() {
            let fields = log.fields(&t.name, t.instance).unwrap();
            let names: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
            let s = log.series(&t.name, t.instance, &names).unwrap();
            assert!(
                s.values.iter().all(|v| v.len() == t.samples),
                "{name}: {}",
                s.label()
            );
            assert_eq!(s.column("timestamp").unwrap()[0], s.time_us[0] as f64);
        }
    }
}
