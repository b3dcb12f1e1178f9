//! Joining topics of different rates onto the base stream's time stamps:
//! the base never resampled, the others linearly interpolated inside their
//! span and not across their gaps, every dropped or interpolated row
//! counted, and the refusals.

mod common;

use common::{IMU, VEC3, Writer, imu};
use ulog::{FieldSource, Ulog, UlogError, UlogTable};

/// `imu` instance 0 every 4 ms from 0 to 116 ms (gyro[0] = t in ms),
/// instance 1 every 10 ms from 12 to 122 ms (acc.x = 2 t − 1 in ms, linear,
/// so interpolation is exact) without its samples at 72, 82 and 92 ms: a
/// gap of 40 ms, over 3 × its median step of 10 ms.
fn two_rates() -> Ulog {
    let mut w = Writer::new(false);
    w.format(VEC3)
        .format(IMU)
        .subscribe(0, 1, "imu")
        .subscribe(1, 2, "imu");
    for k in 0..30u64 {
        let t = 4000 * k;
        w.data(1, &imu(t, [(t / 1000) as f32, 0.0, 0.0], 0, [0.0; 3]));
    }
    for k in 0..12u64 {
        let t = 12_000 + 10_000 * k;
        if (72_000..=92_000).contains(&t) {
            continue;
        }
        w.data(
            2,
            &imu(t, [0.0; 3], 250, [(2 * t / 1000 - 1) as f32, 0.0, 0.0]),
        );
    }
    Ulog::parse(&w.bytes, "t.ulg").unwrap()
}

fn table() -> UlogTable {
    let mut t = UlogTable {
        base: None,
        columns: Default::default(),
    };
    t.columns
        .insert("g".into(), FieldSource::new("imu", "gyro[0]"));
    t.columns
        .insert("a".into(), FieldSource::new("imu", "acc.x").instance(1));
    t
}

#[test]
fn the_base_rows_stay_and_a_slower_topic_is_interpolated_inside_its_span_and_not_across_a_gap() {
    let log = two_rates();
    let j = table().join(&log, &["g", "a"], 3.0).unwrap();
    // Rows 12–60 ms and 104–116 ms remain: 0–8 ms are before instance 1's
    // first sample, 64–100 ms inside its gap.
    let want: Vec<u64> = (0..30u64)
        .map(|k| 4000 * k)
        .filter(|&t| (12_000..=60_000).contains(&t) || t >= 104_000)
        .collect();
    assert_eq!(j.time_us, want);
    assert_eq!(j.start_us, 12_000);
    assert_eq!(j.t_s[1], 0.004);
    // The base's values are its own; the other's, linear in t, exact.
    for (i, &t) in j.time_us.iter().enumerate() {
        assert_eq!(j.column("g").unwrap()[i], (t / 1000) as f64);
        let a = j.column("a").unwrap()[i];
        assert!(
            (a - (2.0 * t as f64 / 1000.0 - 1.0)).abs() < 1e-12,
            "{t}: {a}"
        );
    }
    let [base, other] = &j.streams[..] else {
        panic!()
    };
    assert_eq!((base.exact_rows, base.interpolated_rows), (30, 0));
    assert_eq!(other.stream, "imu[1]");
    assert_eq!(other.median_step_s, 0.01);
    assert_eq!((other.exact_rows, other.interpolated_rows), (4, 13)); // 12, 32, 52, 112 ms on its samples
    assert_eq!((other.rows_outside, other.rows_in_gap), (3, 10));
    assert_eq!(j.rows_dropped, 13);
    let resampled: Vec<&str> = j.interpolated_columns().iter().map(|(c, _)| *c).collect();
    assert_eq!(resampled, ["a"]);
    assert_eq!(
        other.line(),
        "imu[1] (a): 9 samples, median step 10.000 ms; rows: 4 on its samples, 13 interpolated linearly, 3 outside its span and 10 in its gaps dropped"
    );
}

#[test]
fn a_time_source_and_an_interval_are_per_column() {
    let log = two_rates();
    let mut t = table();
    let a = t.columns.get_mut("a").unwrap();
    a.time_offset = Some("rel".into());
    a.interval = Some("timestamp".into());
    let j = t.join(&log, &["g", "a"], 3.0).unwrap();
    assert_eq!(j.streams[1].stream, "imu[1] at timestamp + rel");
    // Instance 1's samples sit at timestamp + 0.25 ms, so the first row is
    // 16 ms, between its samples of 12.25 and 22.25 ms; each value is
    // divided by its own sample's `timestamp` field (µs → s) before the
    // interpolation.
    assert_eq!(j.start_us, 16_000);
    let v = |ts: f64| (2.0 * ts / 1000.0 - 1.0) / (ts * 1e-6);
    let want = v(12_000.0) + (v(22_000.0) - v(12_000.0)) * (16_000.0 - 12_250.0) / 10_000.0;
    let a0 = j.column("a").unwrap()[0];
    assert!((a0 - want).abs() < 1e-9 * want.abs(), "{a0} vs {want}");
    assert_eq!(j.columns[0].0, "g");
}

#[test]
fn the_base_is_the_first_column_unless_the_table_names_one() {
    let log = two_rates();
    let mut t = table();
    let j = t.join(&log, &["a", "g"], 3.0).unwrap();
    assert_eq!(j.streams[0].stream, "imu[1]");
    assert_eq!(j.time_us.len(), 8); // its 122-ms sample is past instance 0's last
    assert_eq!(j.streams[1].rows_outside, 1);
    t.base = Some("g".into());
    let j = t.join(&log, &["a"], 3.0).unwrap();
    assert_eq!(j.streams[0].columns, ["g"]);
    assert_eq!(j.columns.len(), 1);
    assert_eq!(j.time_us.len(), 17);
}

#[test]
fn refusals() {
    let log = two_rates();
    let err = table()
        .join(&log, &["g", "temp"], 3.0)
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "ulog.columns has no entry for column 'temp' (it maps: a, g); add `temp = { topic = \"…\", field = \"…\" }`"
    );
    let mut t = table();
    t.columns.get_mut("a").unwrap().field = "acc.w".into();
    let err = t.join(&log, &["g", "a"], 3.0).unwrap_err().to_string();
    assert!(
        err.starts_with(
            "ulog.columns.a: t.ulg: imu[1] has no field 'acc.w' (its fields: timestamp,"
        ),
        "{err}"
    );
    let mut t = table();
    t.columns.get_mut("a").unwrap().interval = Some("rel".into());
    t.columns.get_mut("a").unwrap().time = "rel".into();
    let err = t.join(&log, &["g", "a"], 3.0).unwrap_err();
    assert!(
        matches!(&err, UlogError::Column { source, .. } if matches!(**source, UlogError::NotIncreasing { index: 1, previous: 250, value: 250, .. })),
        "{err}"
    );
    let mut t = table();
    t.columns.get_mut("a").unwrap().interval = Some("gyro[0]".into());
    let err = t.join(&log, &["g", "a"], 3.0).unwrap_err().to_string();
    assert_eq!(
        err,
        "ulog.columns.a: t.ulg: imu[1] sample 0: interval gyro[0] = 0 µs; a rate needs a positive interval"
    );
    let mut w = Writer::new(false);
    w.format(VEC3)
        .format(IMU)
        .subscribe(0, 1, "imu")
        .subscribe(1, 2, "imu");
    w.data(1, &imu(1000, [0.0; 3], 0, [0.0; 3]))
        .data(1, &imu(2000, [0.0; 3], 0, [0.0; 3]));
    w.data(2, &imu(5000, [0.0; 3], 0, [0.0; 3]))
        .data(2, &imu(6000, [0.0; 3], 0, [0.0; 3]));
    let log = Ulog::parse(&w.bytes, "t.ulg").unwrap();
    let err = table()
        .join(&log, &["g", "a"], 3.0)
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "t.ulg: 0 row(s) of imu[0] have a value of every column, a record needs two: \
         imu[0] (g): 2 samples, median step 1.000 ms; rows: 2 on its samples; \
         imu[1] (a): 2 samples, median step 1.000 ms; rows: 0 on its samples, 2 outside its span and 0 in its gaps dropped"
    );
}
