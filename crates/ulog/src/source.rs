//! Where each column of a unit comes from in a ULog file: the `[ulog]`
//! table a unit file may carry (docs/formats.md), and the default for a
//! triad, PX4's `sensor_combined`. Data, read by [`crate::join`].

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// The `[ulog]` table of a unit file.
///
/// ```
/// let table: ulog::UlogTable = toml::from_str(r#"
///     base = "gx"
///     [columns]
///     gx = { topic = "sensor_gyro", field = "x", time = "timestamp_sample" }
///     ax = { topic = "sensor_accel", instance = 0, field = "x", time = "timestamp_sample" }
///     temp = { topic = "sensor_gyro", field = "temperature" }
/// "#).unwrap();
/// assert_eq!(table.columns["gx"].instance, 0);
/// assert_eq!(table.columns["temp"].time, "timestamp");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UlogTable {
    /// The column whose topic instance's time stamps become the record's
    /// time; the other topics are interpolated onto them. Default: the
    /// unit's first gyro (the caller resolves it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base: Option<String>,
    /// Every column of the unit (gyros, accelerometers, temperature) by its
    /// name in the unit file, and where it comes from.
    pub columns: BTreeMap<String, FieldSource>,
}

/// One column's source: a field of a topic instance.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldSource {
    /// The uORB topic (`sensor_combined`, `sensor_gyro`, `vehicle_imu`).
    pub topic: String,
    /// Its multi-instance id (0 when the topic has one instance).
    #[serde(default)]
    pub instance: u8,
    /// The field, flattened as pyulog names it (`x`, `gyro_rad[0]`,
    /// `delta_angle[2]`).
    pub field: String,
    /// The field holding each sample's time in µs (`timestamp`, or
    /// `timestamp_sample`: when the sensor sampled rather than when the
    /// driver published).
    #[serde(default = "default_time")]
    pub time: String,
    /// A field added to `time`, in µs (`sensor_combined`'s
    /// `accelerometer_timestamp_relative`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_offset: Option<String>,
    /// A field holding the integration interval in µs: the value is divided
    /// by it (`vehicle_imu`'s `delta_angle[k]` in rad over `delta_angle_dt`
    /// gives rad/s; `delta_velocity[k]` over `delta_velocity_dt`, m/s²).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interval: Option<String>,
}

fn default_time() -> String {
    "timestamp".into()
}

impl FieldSource {
    /// `field` of `topic` instance 0, timed by `timestamp`.
    pub fn new(topic: &str, field: &str) -> Self {
        Self {
            topic: topic.into(),
            instance: 0,
            field: field.into(),
            time: default_time(),
            time_offset: None,
            interval: None,
        }
    }

    /// The same field at another multi-instance id.
    pub fn instance(mut self, instance: u8) -> Self {
        self.instance = instance;
        self
    }

    /// `topic[instance]` and how it is timed: the samples of one stream
    /// share their rows.
    pub(crate) fn stream(&self) -> (&str, u8, &str, Option<&str>) {
        (
            &self.topic,
            self.instance,
            &self.time,
            self.time_offset.as_deref(),
        )
    }
}

impl UlogTable {
    /// A triad from PX4's `sensor_combined`: `gyros[k]` ← `gyro_rad[k]`
    /// (rad/s), `accels[k]` ← `accelerometer_m_s2[k]` (m/s²) at
    /// `timestamp + accelerometer_timestamp_relative`; the gyro's
    /// `timestamp` is the record's time.
    pub fn sensor_combined(gyros: [&str; 3], accels: [&str; 3]) -> Self {
        let mut columns = BTreeMap::new();
        for (k, g) in gyros.iter().enumerate() {
            columns.insert(
                g.to_string(),
                FieldSource::new("sensor_combined", &format!("gyro_rad[{k}]")),
            );
        }
        for (k, a) in accels.iter().enumerate() {
            let mut s = FieldSource::new("sensor_combined", &format!("accelerometer_m_s2[{k}]"));
            s.time_offset = Some("accelerometer_timestamp_relative".into());
            columns.insert(a.to_string(), s);
        }
        Self {
            base: Some(gyros[0].to_string()),
            columns,
        }
    }
}
