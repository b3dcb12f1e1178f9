//! The reader on files built for each rule of the ULog specification:
//! nested types, arrays and padding; multi-instance topics; definitions and
//! data messages of every kind; appended data; dropouts, cut tails, damaged
//! and unknown messages; and the refusals, each naming what is wrong.

mod common;

use common::{IMU, IMU_FULL, IMU_MIN, VEC3, Writer, imu, two_imus};
use ulog::{FieldType, InfoValue, TimeSource, Ulog, UlogError};

fn parse(w: &Writer) -> Ulog {
    Ulog::parse(&w.bytes, "t.ulg").unwrap()
}

fn error(w: &Writer) -> String {
    Ulog::parse(&w.bytes, "t.ulg").unwrap_err().to_string()
}

#[test]
fn nested_types_and_arrays_flatten_as_pyulog_names_them_and_padding_is_left_out() {
    let log = parse(&two_imus(3));
    let fields = log.fields("imu", 0).unwrap();
    let names: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "timestamp",
            "gyro[0]",
            "gyro[1]",
            "gyro[2]",
            "rel",
            "acc.x",
            "acc.y",
            "acc.z"
        ]
    );
    let offsets: Vec<usize> = fields.iter().map(|f| f.offset).collect();
    assert_eq!(offsets, [0, 8, 12, 16, 20, 24, 28, 32]);
    assert_eq!(fields[0].ty, FieldType::UInt64);
    assert_eq!(fields[4].ty, FieldType::Int32);
    let s = log
        .series("imu", 0, &["gyro[1]", "acc.x", "acc.z"])
        .unwrap();
    assert_eq!(s.time_us, [1000, 5000, 9000]);
    assert_eq!(s.t_s(), [0.001, 0.005, 0.009]);
    assert_eq!(s.values[0], [0.0, 2.0, 4.0]);
    assert_eq!(s.values[1], [0.0, 0.5, 1.0]);
    assert_eq!(s.column("acc.z").unwrap(), [-9.8f32 as f64; 3]);
}

#[test]
fn multi_instance_topics_are_apart() {
    let log = parse(&two_imus(4));
    let t: Vec<(String, u8, usize)> = log
        .topics()
        .into_iter()
        .map(|t| (t.name, t.instance, t.samples))
        .collect();
    assert_eq!(t, [("imu".into(), 0, 4), ("imu".into(), 1, 4)]);
    let s = log.series("imu", 1, &["gyro[0]"]).unwrap();
    assert_eq!(s.time_us, [3000, 7000, 11000, 15000]);
    assert_eq!(s.values[0], [0.0, -1.0, -2.0, -3.0]);
    assert_eq!(log.topic_listing(), "imu[0,1]");
    let err = log.series("imu", 2, &["x"]).unwrap_err().to_string();
    assert_eq!(
        err,
        "t.ulg: topic 'imu' has no instance 2 with data (it has: 0, 1)"
    );
    let err = log.series("gyro", 0, &["x"]).unwrap_err().to_string();
    assert_eq!(
        err,
        "t.ulg: no topic 'gyro' with data (the log has: imu[0,1])"
    );
    let err = log.series("imu", 0, &["gyro[3]"]).unwrap_err().to_string();
    assert!(
        err.starts_with("t.ulg: imu[0] has no field 'gyro[3]' (its fields: timestamp, gyro[0],"),
        "{err}"
    );
    assert!(
        log.describe()
            .starts_with("imu[0]: 4 samples, 250.0 Hz; fields: timestamp, gyro[0]"),
        "{}",
        log.describe()
    );
}

#[test]
fn info_parameters_logged_strings_dropouts_and_syncs_are_kept() {
    let log = parse(&two_imus(4));
    assert_eq!(log.header().version, 1);
    assert_eq!(log.header().start_us, 1000);
    assert_eq!(log.info()["sys_name"], InfoValue::Text("PX4!".into()));
    assert_eq!(log.info()["ver_hw_id"], InfoValue::Integer(7));
    let perf = &log.multi_info()["perf"];
    assert_eq!(
        perf,
        &[vec![
            InfoValue::Text("one".into()),
            InfoValue::Text("two".into())
        ]]
    );
    assert_eq!(log.parameters()["IMU_GYRO_CUTOFF"], 30.0);
    assert_eq!(log.parameters()["SDLOG_MODE"], 1.0);
    let change = &log.parameter_changes()[0];
    assert_eq!(
        (change.name.as_str(), change.value, change.after_us),
        ("IMU_GYRO_CUTOFF", 40.0, 11000)
    );
    let logged: Vec<(&str, Option<u16>)> = log
        .logged_messages()
        .iter()
        .map(|m| (m.text.as_str(), m.tag))
        .collect();
    assert_eq!(logged, [("logging started", None), ("tagged", Some(3))]);
    let i = log.integrity();
    assert_eq!(i.dropouts.len(), 1);
    assert_eq!(
        (i.dropouts[0].after_us, i.dropouts[0].duration_ms),
        (11000, 25)
    );
    assert_eq!(i.syncs, 1);
    assert!(!i.is_clean());
    assert_eq!(
        i.summary(),
        "1 logger dropout(s), 25 ms in all, longest 25 ms"
    );
}

#[test]
fn a_sample_with_or_without_its_trailing_padding_is_read_and_other_sizes_are_skipped() {
    let mut w = Writer::new(false);
    w.format(VEC3).format(IMU).subscribe(0, 1, "imu");
    let mut padded = imu(10, [1.0; 3], 0, [0.0; 3]);
    padded.extend_from_slice(&[0xAA; 3]);
    assert_eq!(padded.len(), IMU_FULL);
    w.data(1, &padded);
    w.data(1, &imu(20, [2.0; 3], 0, [0.0; 3]));
    w.data(1, &imu(30, [3.0; 3], 0, [0.0; 3])[..IMU_MIN - 1]);
    w.data(1, &[imu(40, [4.0; 3], 0, [0.0; 3]), vec![0; 4]].concat());
    w.data(9, &imu(50, [5.0; 3], 0, [0.0; 3]));
    let log = parse(&w);
    let s = log.series("imu", 0, &["gyro[0]"]).unwrap();
    assert_eq!(s.time_us, [10, 20]);
    assert_eq!(s.values[0], [1.0, 2.0]);
    assert_eq!(log.integrity().corrupt_messages, 3);
}

#[test]
fn appended_sections_are_read_and_a_message_cut_by_one_is_dropped() {
    let mut w = Writer::new(true);
    w.format(VEC3).format(IMU).subscribe(0, 1, "imu");
    w.data(1, &imu(10, [1.0; 3], 0, [0.0; 3]));
    // A crash: the logger stopped inside a message, then wrote the rest of
    // its buffer after it (the appended section).
    let whole = w.len();
    w.data(1, &imu(20, [2.0; 3], 0, [0.0; 3]));
    w.bytes.truncate(whole + 10);
    let appended = w.len() as u64;
    w.data(1, &imu(30, [3.0; 3], 0, [0.0; 3])).dropout(5);
    let second = w.len() as u64;
    w.data(1, &imu(40, [4.0; 3], 0, [0.0; 3]));
    w.set_appended_offset(0, appended)
        .set_appended_offset(1, second);
    let log = parse(&w);
    assert_eq!(log.header().appended_offsets, [appended, second]);
    let s = log.series("imu", 0, &["gyro[0]"]).unwrap();
    assert_eq!(s.time_us, [10, 30, 40]);
    assert_eq!(s.values[0], [1.0, 3.0, 4.0]);
    let i = log.integrity();
    assert_eq!(
        (i.appended_sections, i.cut_messages, i.truncated),
        (2, 1, false)
    );
    assert_eq!(i.dropouts[0].after_us, 30);
    // Appended offsets are read only with the data-appended flag, as pyulog.
    w.bytes[16 + 3 + 8] = 0;
    let log = parse(&w);
    assert_eq!(log.integrity().appended_sections, 0);
    assert!(log.integrity().corrupt_messages + log.integrity().skipped_bytes > 0);
}

#[test]
fn a_file_cut_inside_a_message_keeps_what_came_before() {
    let mut w = two_imus(6);
    let n = w.len();
    w.bytes.truncate(n - 5);
    let log = parse(&w);
    assert!(log.integrity().truncated);
    assert!(
        log.integrity()
            .summary()
            .contains("the file ends inside a message")
    );
    assert_eq!(log.series("imu", 0, &[]).unwrap().time_us.len(), 6);
    assert_eq!(log.series("imu", 1, &[]).unwrap().time_us.len(), 5);
}

#[test]
fn unknown_messages_are_skipped_and_a_damaged_header_resyncs_at_the_next_sync_marker() {
    let mut w = Writer::new(false);
    w.format(VEC3).format(IMU).subscribe(0, 1, "imu");
    w.data(1, &imu(10, [1.0; 3], 0, [0.0; 3]));
    w.msg(b'Z', b"a future message type");
    w.data(1, &imu(20, [2.0; 3], 0, [0.0; 3]));
    w.bytes.extend_from_slice(&[0, 0, 0, 7, 7]); // a header of type 0: damage
    w.data(1, &imu(30, [3.0; 3], 0, [0.0; 3])); // lost: no sync before it
    w.sync();
    w.data(1, &imu(40, [4.0; 3], 0, [0.0; 3]));
    let log = parse(&w);
    assert_eq!(log.series("imu", 0, &[]).unwrap().time_us, [10, 20, 40]);
    let i = log.integrity();
    assert_eq!(i.unknown_messages, 1);
    assert_eq!(i.syncs, 1);
    assert_eq!(i.skipped_bytes, 5 + 3 + 2 + IMU_MIN + 3);
}

#[test]
fn removed_and_resubscribed_topics_continue_one_series() {
    let mut w = Writer::new(false);
    w.format(VEC3).format(IMU).subscribe(0, 1, "imu");
    w.data(1, &imu(10, [1.0; 3], 0, [0.0; 3]));
    w.remove(1);
    w.data(1, &imu(20, [2.0; 3], 0, [0.0; 3]));
    w.subscribe(0, 5, "imu");
    w.data(5, &imu(30, [3.0; 3], 0, [0.0; 3]));
    let log = parse(&w);
    assert_eq!(log.series("imu", 0, &[]).unwrap().time_us, [10, 30]);
    assert_eq!(log.integrity().corrupt_messages, 1);
}

#[test]
fn a_subscription_without_a_usable_format_is_counted_and_its_topic_absent() {
    let mut w = Writer::new(false);
    w.format("loop:uint64_t timestamp;loop inner;")
        .format("half:uint64_t timestamp;nothing x;");
    w.format("pad:uint8_t[4] _padding0;")
        .format(VEC3)
        .format(IMU);
    w.subscribe(0, 1, "loop")
        .subscribe(0, 2, "half")
        .subscribe(0, 3, "pad")
        .subscribe(0, 4, "none");
    w.subscribe(0, 5, "imu")
        .data(5, &imu(10, [1.0; 3], 0, [0.0; 3]))
        .data(1, &[0; 16]);
    let log = parse(&w);
    let bad = &log.integrity().bad_subscriptions;
    assert_eq!(bad.len(), 4, "{bad:?}");
    assert!(
        bad[0].ends_with("'loop': format 'loop' contains itself"),
        "{bad:?}"
    );
    assert!(
        bad[1].ends_with("'half': no format 'nothing' is defined"),
        "{bad:?}"
    );
    assert!(
        bad[2].ends_with("'pad': its format has no fields but padding"),
        "{bad:?}"
    );
    assert!(
        bad[3].ends_with("'none': no format 'none' is defined"),
        "{bad:?}"
    );
    assert_eq!(log.integrity().corrupt_messages, 1);
    assert!(log.series("loop", 0, &[]).is_err());
    assert_eq!(log.series("imu", 0, &[]).unwrap().time_us, [10]);
}

#[test]
fn a_time_offset_field_is_added_and_a_time_must_be_whole_microseconds() {
    let mut w = Writer::new(false);
    w.format(VEC3).format(IMU).subscribe(0, 1, "imu");
    w.data(1, &imu(100, [0.0; 3], -40, [0.0; 3]));
    w.data(1, &imu(200, [0.0; 3], 7, [0.0; 3]));
    let log = parse(&w);
    let time = TimeSource {
        field: "timestamp",
        offset: Some("rel"),
    };
    assert_eq!(
        log.series_timed("imu", 0, time, &[]).unwrap().time_us,
        [60, 207]
    );
    let err = log
        .series_timed(
            "imu",
            0,
            TimeSource {
                field: "acc.x",
                offset: None,
            },
            &[],
        )
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "t.ulg: imu[0].acc.x is float: a time stamp must be an integer number of µs"
    );
    w.data(1, &imu(10, [0.0; 3], -40, [0.0; 3]));
    let err = parse(&w).series_timed("imu", 0, time, &[]).unwrap_err();
    assert!(
        matches!(
            err,
            UlogError::NegativeTime {
                index: 2,
                value: -30,
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn a_log_without_flag_bits_is_read() {
    let mut w = Writer::without_flags();
    w.format(VEC3)
        .format(IMU)
        .subscribe(0, 1, "imu")
        .data(1, &imu(10, [1.0; 3], 0, [0.0; 3]));
    let log = parse(&w);
    assert_eq!(log.header().incompat_flags, [0; 8]);
    assert_eq!(log.series("imu", 0, &[]).unwrap().time_us, [10]);
    assert!(log.integrity().is_clean());
}

#[test]
fn refusals_name_the_file_and_what_is_wrong() {
    assert_eq!(
        Ulog::parse(b"ULog", "t.ulg").unwrap_err().to_string(),
        "t.ulg: 4 bytes, shorter than the 16-byte ULog header; give a .ulg file written by PX4's logger"
    );
    let mut csv = b"t,gx,gy,gz,ax,ay,az\n0,".to_vec();
    csv.resize(40, b'0');
    assert!(
        Ulog::parse(&csv, "t.ulg")
            .unwrap_err()
            .to_string()
            .starts_with("t.ulg: not a PX4 ULog file")
    );
    let mut w = Writer::new(false);
    w.bytes[16 + 3 + 8 + 2] = 4;
    assert_eq!(
        error(&w),
        "t.ulg: incompatible flag byte 2 is 0x04: the log uses a ULog feature this reader does not know; \
         convert it with a current pyulog (ulog2csv) and read the CSV"
    );
    let mut w = Writer::new(false);
    w.bytes[16] = 20;
    w.bytes.truncate(16 + 3 + 20);
    assert!(
        error(&w).starts_with("t.ulg: byte 16: the flag-bits message has 20 bytes"),
        "{}",
        error(&w)
    );
    let mut w = Writer::new(true);
    w.set_appended_offset(0, 1 << 40);
    assert_eq!(
        error(&w),
        "t.ulg: appended-data offset 1099511627776 in the flag bits is past the end of the file (59 bytes); the file is damaged"
    );
    let mut w = Writer::new(true);
    w.format(VEC3)
        .set_appended_offset(0, 70)
        .set_appended_offset(1, 65);
    assert!(
        error(&w).contains("offset 65 in the flag bits is before the section it follows (byte 70)"),
        "{}",
        error(&w)
    );
    for (text, why) in [
        (
            "imu;uint64_t timestamp;",
            "'imu;uint64_t timestamp;' has no ':' after the name",
        ),
        (":uint64_t timestamp;", "has an empty name"),
        ("imu:uint64_t;", "imu: field 'uint64_t': not 'type name'"),
        (
            "imu:float[0] x;",
            "imu: field 'float[0] x': the array size is not an integer from 1 to 65533",
        ),
        (
            "imu:float[70000] x;",
            "the array size is not an integer from 1 to 65533",
        ),
        ("imu:float[3 x;", "the array size is not"),
        (
            "imu:float acc.x;",
            "imu: field 'float acc.x': the name is not an identifier (letters, digits and _)",
        ),
        (
            "imu:float\ny;",
            "imu: field 'float\\ny': an empty type, or control characters",
        ),
        (
            "i\tmu:float y;",
            "'i\\tmu:float y;' has an empty name or one with control characters",
        ),
    ] {
        let mut w = Writer::new(false);
        w.format(text);
        let e = error(&w);
        assert!(e.starts_with("t.ulg: byte 59: format message: "), "{e}");
        assert!(e.contains(why), "{text}: {e}");
    }
    let missing = std::env::temp_dir().join("ulog-test-no-such-file.ulg");
    let e = Ulog::read(&missing).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}: cannot read: ", missing.display())),
        "{e}"
    );
}

/// A schema built to be expensive (3000 topics, each a 60 000-field nested
/// type, at two instances each, 300 with data) is read and listed without expanding
/// every field: a regression guard against a hang on a hostile file.
#[test]
fn a_costly_schema_is_read_and_listed_without_expanding_every_field() {
    let mut w = Writer::new(false);
    w.format("big:uint8_t[60000] y;");
    for k in 0..3000 {
        w.format(&format!("t{k}:uint64_t timestamp;big b;"));
    }
    for k in 0..3000u16 {
        w.subscribe((k % 200) as u8, k, &format!("t{k}"));
        w.subscribe((k % 200) as u8 + 1, k, &format!("t{k}"));
    }
    for k in 0..300u16 {
        let mut sample = (k as u64).to_le_bytes().to_vec();
        sample.resize(8 + 60000, 1);
        w.data(k, &sample);
    }
    let log = parse(&w);
    assert_eq!(log.topics().len(), 300);
    let listing = log.describe();
    assert_eq!(listing.lines().count(), 300);
    assert!(
        listing.lines().all(|l| l.ends_with("b.y[38], …")),
        "{}",
        &listing[..200]
    );
    assert_eq!(log.fields("t7", 8).unwrap().len(), 60001);
}
