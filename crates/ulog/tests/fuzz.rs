//! Mutation fuzzing of the reader: a valid log (built here, with every
//! message kind, nested types and an appended section; and the real
//! CubeOrange log where `../shared` is present) gets bytes overwritten,
//! inserted, deleted or cut, or random bytes after valid definitions. Each
//! case requires: no panic; a refusal is a typed error with a one-line
//! message naming the file; what is accepted answers every query (listing,
//! fields, series of every field, a join) without panic, each series as
//! long as its time stamps.
//!
//! Each property runs proptest's default 256 cases (about a second in all);
//! `PROPTEST_CASES=N` sets every property's count (50 000 each passed).

mod common;

use std::sync::OnceLock;

use common::{IMU, VEC3, Writer, imu, two_imus};
use proptest::prelude::*;
use proptest::test_runner::Config;
use ulog::{FieldSource, Ulog, UlogError, UlogTable};

/// proptest's defaults (256 cases, or `PROPTEST_CASES`), without writing
/// failures to disk.
fn config() -> Config {
    Config {
        failure_persistence: None,
        ..Config::default()
    }
}

/// Two IMU instances, every message kind, and an appended section.
fn synthetic() -> &'static [u8] {
    static BYTES: OnceLock<Vec<u8>> = OnceLock::new();
    BYTES.get_or_init(|| {
        let mut w = two_imus(40);
        w.bytes[16 + 3 + 8] = 1; // data appended
        let at = w.len() as u64;
        w.data(1, &imu(500_000, [1.0; 3], 3, [0.0; 3])).dropout(3);
        w.set_appended_offset(0, at);
        w.bytes
    })
}

/// The real CubeOrange log, if `../shared` is beside the project.
fn real() -> Option<&'static [u8]> {
    static BYTES: OnceLock<Option<Vec<u8>>> = OnceLock::new();
    BYTES
        .get_or_init(|| {
            let p = concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../../shared/realdata/ulog/sample_log_small.ulg"
            );
            std::fs::read(p).ok()
        })
        .as_deref()
}

#[derive(Debug, Clone)]
enum Mutation {
    Set(usize, u8),
    Insert(usize, Vec<u8>),
    Delete(usize, usize),
    Truncate(usize),
}

/// Positions as fractions: half of them in the first 4 KiB (header and
/// definitions), the rest anywhere.
fn mutation() -> impl Strategy<Value = (Mutation, bool)> {
    let m = prop_oneof![
        4 => (any::<usize>(), any::<u8>()).prop_map(|(p, v)| Mutation::Set(p, v)),
        1 => (any::<usize>(), proptest::collection::vec(any::<u8>(), 1..8)).prop_map(|(p, v)| Mutation::Insert(p, v)),
        1 => (any::<usize>(), 1usize..16).prop_map(|(p, n)| Mutation::Delete(p, n)),
        1 => any::<usize>().prop_map(Mutation::Truncate),
    ];
    (m, any::<bool>())
}

fn apply(bytes: &mut Vec<u8>, (m, early): &(Mutation, bool)) {
    let span = if *early {
        bytes.len().min(4096)
    } else {
        bytes.len()
    };
    let at = |p: &usize| if span == 0 { 0 } else { p % span };
    match m {
        Mutation::Set(p, v) if !bytes.is_empty() => {
            let i = at(p);
            bytes[i] = *v;
        }
        Mutation::Insert(p, v) => {
            let i = at(p);
            bytes.splice(i..i, v.iter().copied());
        }
        Mutation::Delete(p, n) if !bytes.is_empty() => {
            let i = at(p);
            let end = (i + n).min(bytes.len());
            bytes.drain(i..end);
        }
        Mutation::Truncate(p) => bytes.truncate(at(p)),
        _ => {}
    }
}

/// Every query on whatever was read; none may panic.
fn exercise(bytes: &[u8]) {
    let log = match Ulog::parse(bytes, "fuzz.ulg") {
        Ok(log) => log,
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with("fuzz.ulg: ") && !m.contains('\n'), "{m}");
            return;
        }
    };
    let _ = log.integrity().summary();
    let _ = log.describe();
    for t in log.topics() {
        let fields = log.fields(&t.name, t.instance).unwrap();
        let names: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
        // Every listed field is found by name (only a missing `timestamp`
        // may refuse the series).
        match log.series(&t.name, t.instance, &names) {
            Ok(s) => {
                assert_eq!(s.time_us.len(), t.samples);
                assert!(s.values.iter().all(|v| v.len() == t.samples));
            }
            Err(UlogError::NoField { field, .. }) => assert_eq!(field, "timestamp"),
            Err(e) => assert!(matches!(e, UlogError::NotMicroseconds { .. }), "{e}"),
        }
        if names.len() >= 2 {
            let mut table = UlogTable {
                base: None,
                columns: Default::default(),
            };
            table.columns.insert(
                "a".into(),
                FieldSource::new(&t.name, names[1]).instance(t.instance),
            );
            table
                .columns
                .insert("b".into(), FieldSource::new("imu", "acc.x").instance(1));
            table.columns.insert(
                "c".into(),
                FieldSource::new("sensor_combined", "gyro_rad[0]"),
            );
            for cols in [&["a", "b"][..], &["a", "c"]] {
                if let Ok(j) = table.join(&log, cols, 3.0) {
                    assert!(j.columns.iter().all(|(_, v)| v.len() == j.time_us.len()));
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(config())]
    #[test]
    fn mutated_synthetic_logs_never_panic(ms in proptest::collection::vec(mutation(), 1..5)) {
        let mut bytes = synthetic().to_vec();
        for m in &ms {
            apply(&mut bytes, m);
        }
        exercise(&bytes);
    }

    #[test]
    fn random_data_after_valid_definitions_never_panics(tail in proptest::collection::vec(any::<u8>(), 0..3000)) {
        let mut w = Writer::new(false);
        w.format(VEC3).format(IMU).subscribe(0, 1, "imu").subscribe(1, 2, "imu");
        w.bytes.extend_from_slice(&tail);
        exercise(&w.bytes);
    }
}

proptest! {
    #![proptest_config(config())]
    #[test]
    fn mutated_real_logs_never_panic(ms in proptest::collection::vec(mutation(), 1..5)) {
        let Some(real) = real() else {
            eprintln!("notice: ../shared/realdata/ulog absent; the real log is not fuzzed");
            return Ok(());
        };
        let mut bytes = real.to_vec();
        for m in &ms {
            apply(&mut bytes, m);
        }
        exercise(&bytes);
    }
}

/// The unmutated bases read cleanly, so the properties start from valid logs.
#[test]
fn the_bases_are_valid() {
    let log = Ulog::parse(synthetic(), "s.ulg").unwrap();
    assert_eq!(log.integrity().appended_sections, 1);
    assert_eq!(log.series("imu", 0, &[]).unwrap().time_us.len(), 41);
    if let Some(real) = real() {
        let log = Ulog::parse(real, "r.ulg").unwrap();
        assert!(log.topics().len() > 40);
    }
}
