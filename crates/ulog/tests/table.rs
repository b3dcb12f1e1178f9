//! The `[ulog]` table as a unit file writes it: the keys, their defaults,
//! unknown keys refused, and the built-in triad mapping equal to the table
//! a user would write for it.

use ulog::{FieldSource, UlogTable};

#[derive(serde::Deserialize)]
#[allow(dead_code)]
struct UnitFileWithUlog {
    name: String,
    ulog: UlogTable,
}

#[test]
fn the_sensor_combined_default_is_the_table_a_user_would_write() {
    let text = r#"
name = "triad from sensor_combined"
[ulog]
base = "gx"
[ulog.columns]
gx = { topic = "sensor_combined", field = "gyro_rad[0]" }
gy = { topic = "sensor_combined", field = "gyro_rad[1]" }
gz = { topic = "sensor_combined", field = "gyro_rad[2]" }
ax = { topic = "sensor_combined", field = "accelerometer_m_s2[0]", time_offset = "accelerometer_timestamp_relative" }
ay = { topic = "sensor_combined", field = "accelerometer_m_s2[1]", time_offset = "accelerometer_timestamp_relative" }
az = { topic = "sensor_combined", field = "accelerometer_m_s2[2]", time_offset = "accelerometer_timestamp_relative" }
"#;
    let file: UnitFileWithUlog = toml::from_str(text).unwrap();
    assert_eq!(
        file.ulog,
        UlogTable::sensor_combined(["gx", "gy", "gz"], ["ax", "ay", "az"])
    );
}

#[test]
fn three_imus_from_sensor_gyro_and_sensor_accel_and_vehicle_imu() {
    let text = r#"
[columns.g0x]
topic = "sensor_gyro"
field = "x"
time = "timestamp_sample"
[columns.g1x]
topic = "sensor_gyro"
instance = 1
field = "x"
time = "timestamp_sample"
[columns.g2x]
topic = "vehicle_imu"
instance = 2
field = "delta_angle[0]"
time = "timestamp_sample"
interval = "delta_angle_dt"
[columns.temp]
topic = "sensor_gyro"
field = "temperature"
"#;
    let t: UlogTable = toml::from_str(text).unwrap();
    assert_eq!(t.base, None);
    assert_eq!(t.columns["g0x"].instance, 0);
    assert_eq!(t.columns["g1x"].instance, 1);
    assert_eq!(t.columns["g2x"].interval.as_deref(), Some("delta_angle_dt"));
    assert_eq!(
        t.columns["temp"],
        FieldSource::new("sensor_gyro", "temperature")
    );
    let back: UlogTable = toml::from_str(&toml::to_string(&t).unwrap()).unwrap();
    assert_eq!(back, t);
}

#[test]
fn unknown_keys_and_a_missing_field_are_refused_with_their_place() {
    let e = toml::from_str::<UlogTable>(
        "[columns]\ngx = { topic = \"sensor_gyro\", field = \"x\", instnace = 1 }\n",
    )
    .unwrap_err();
    assert!(e.to_string().contains("unknown field `instnace`, expected one of `topic`, `instance`, `field`, `time`, `time_offset`, `interval`"), "{e}");
    let e =
        toml::from_str::<UlogTable>("[columns]\ngx = { topic = \"sensor_gyro\" }\n").unwrap_err();
    assert!(e.to_string().contains("missing field `field`"), "{e}");
    let e = toml::from_str::<UlogTable>(
        "[columns]\ngx = { topic = \"sensor_gyro\", field = \"x\", instance = 256 }\n",
    )
    .unwrap_err();
    assert!(e.to_string().contains("256"), "{e}");
    let e = toml::from_str::<UlogTable>("bsae = \"gx\"\n[columns]\n").unwrap_err();
    assert!(e.to_string().contains("unknown field `bsae`"), "{e}");
}
