//! Asking a read log for what it has: its topics and their multi-instance
//! ids, a topic's fields, and the series of chosen fields with their time
//! stamps (µs, and s).

use crate::error::{UlogError, listing};
use crate::format::FlatField;
use crate::model::{TopicData, Ulog};

/// A topic instance that has samples.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TopicSummary {
    pub name: String,
    /// The multi-instance id (`sensor_gyro` 0, 1, 2 on a unit of three IMUs).
    pub instance: u8,
    pub samples: usize,
}

/// Where a series' time comes from: a field in µs, plus another field's
/// µs offset (`sensor_combined`'s accelerometer is at `timestamp +
/// accelerometer_timestamp_relative`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TimeSource<'a> {
    pub field: &'a str,
    pub offset: Option<&'a str>,
}

impl TimeSource<'static> {
    /// The `timestamp` field alone.
    pub const TIMESTAMP: TimeSource<'static> = TimeSource {
        field: "timestamp",
        offset: None,
    };
}

/// Fields of one topic instance, sample by sample, in file order.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub topic: String,
    pub instance: u8,
    /// Each sample's time, µs since boot.
    pub time_us: Vec<u64>,
    /// The fields' names, as asked.
    pub fields: Vec<String>,
    /// One vector per field, each as long as `time_us`.
    pub values: Vec<Vec<f64>>,
}

impl Series {
    /// Each sample's time in s since boot (µs × 1e-6).
    pub fn t_s(&self) -> Vec<f64> {
        self.time_us.iter().map(|&t| t as f64 * 1e-6).collect()
    }

    /// The values of a field, by name.
    pub fn column(&self, field: &str) -> Option<&[f64]> {
        let k = self.fields.iter().position(|f| f == field)?;
        Some(&self.values[k])
    }

    /// `topic[instance]`, for messages.
    pub fn label(&self) -> String {
        format!("{}[{}]", self.topic, self.instance)
    }
}

impl Ulog {
    /// The topic instances that have samples, by name then instance.
    pub fn topics(&self) -> Vec<TopicSummary> {
        let mut out: Vec<TopicSummary> = self
            .topics
            .iter()
            .filter(|t| t.count > 0)
            .map(|t| TopicSummary {
                name: t.name.clone(),
                instance: t.instance,
                samples: t.count,
            })
            .collect();
        out.sort_by(|a, b| (&a.name, a.instance).cmp(&(&b.name, b.instance)));
        out
    }

    /// The topics with data as `name[0,1,2]`, one entry per name.
    pub fn topic_listing(&self) -> String {
        let mut entries: Vec<String> = Vec::new();
        let mut last: Option<String> = None;
        for t in self.topics() {
            if last.as_deref() == Some(t.name.as_str()) {
                if let Some(e) = entries.last_mut() {
                    e.pop();
                    e.push_str(&format!(",{}]", t.instance));
                }
            } else {
                entries.push(format!("{}[{}]", t.name, t.instance));
                last = Some(t.name);
            }
        }
        listing(&entries, 200)
    }

    /// One line per topic instance: samples, mean rate and fields.
    pub fn describe(&self) -> String {
        let mut out = String::new();
        for t in self.topics() {
            let Ok(data) = self.topic(&t.name, t.instance) else {
                continue;
            };
            let fields = self.formats.flatten(&data.name, 41);
            let mut names: Vec<&str> = fields.iter().take(40).map(|f| f.name.as_str()).collect();
            if fields.len() > 40 {
                names.push("…");
            }
            let rate = self
                .series(&t.name, t.instance, &[])
                .ok()
                .and_then(|s| mean_rate_hz(&s.time_us))
                .map_or(String::new(), |r| format!(", {r:.1} Hz"));
            out.push_str(&format!(
                "{}[{}]: {} samples{rate}; fields: {}\n",
                t.name,
                t.instance,
                t.samples,
                names.join(", ")
            ));
        }
        out
    }

    /// The fields of a topic instance, flattened (`gyro_rad[0]`,
    /// `esc[5].esc_rpm`), with their types and offsets.
    pub fn fields(&self, topic: &str, instance: u8) -> Result<Vec<FlatField>, UlogError> {
        let data = self.topic(topic, instance)?;
        Ok(self.formats.flatten(&data.name, usize::MAX))
    }

    /// `fields` of `topic[instance]` with the `timestamp` field as time.
    pub fn series(&self, topic: &str, instance: u8, fields: &[&str]) -> Result<Series, UlogError> {
        self.series_timed(topic, instance, TimeSource::TIMESTAMP, fields)
    }

    /// `fields` of `topic[instance]` with the time `time` gives.
    pub fn series_timed(
        &self,
        topic: &str,
        instance: u8,
        time: TimeSource,
        fields: &[&str],
    ) -> Result<Series, UlogError> {
        let data = self.topic(topic, instance)?;
        let find = |name: &str| -> Result<FlatField, UlogError> {
            self.formats.field(&data.name, name).ok_or_else(|| {
                let flat = self.formats.flatten(&data.name, usize::MAX);
                let names: Vec<&str> = flat.iter().map(|f| f.name.as_str()).collect();
                UlogError::NoField {
                    file: self.file.clone(),
                    topic: topic.to_string(),
                    instance,
                    field: name.to_string(),
                    available: listing(&names, 60),
                }
            })
        };
        let micros = |name: &str, role: &str| -> Result<FlatField, UlogError> {
            let f = find(name)?;
            if f.ty.is_integer() {
                Ok(f)
            } else {
                Err(UlogError::NotMicroseconds {
                    file: self.file.clone(),
                    topic: topic.to_string(),
                    instance,
                    field: name.to_string(),
                    ty: f.ty.name().to_string(),
                    role: role.to_string(),
                })
            }
        };
        let time_field = micros(time.field, "a time stamp")?;
        let offset_field = time
            .offset
            .map(|o| micros(o, "a time offset"))
            .transpose()?;
        let wanted = fields
            .iter()
            .map(|f| find(f))
            .collect::<Result<Vec<_>, _>>()?;
        let samples = || data.bytes.chunks_exact(data.layout.min_size);
        let mut time_us = Vec::with_capacity(data.count);
        for (index, s) in samples().enumerate() {
            let mut t = integer(&time_field, s);
            if let Some(o) = &offset_field {
                t += integer(o, s);
            }
            time_us.push(u64::try_from(t).map_err(|_| UlogError::NegativeTime {
                file: self.file.clone(),
                topic: topic.to_string(),
                instance,
                index,
                offset_field: time.offset.unwrap_or(time.field).to_string(),
                value: t,
            })?);
        }
        let values = wanted
            .iter()
            .map(|f| {
                samples()
                    .map(|s| f.ty.decode(s, f.offset).unwrap_or(f64::NAN))
                    .collect()
            })
            .collect();
        Ok(Series {
            topic: topic.to_string(),
            instance,
            time_us,
            fields: fields.iter().map(|f| f.to_string()).collect(),
            values,
        })
    }

    /// The data of `topic[instance]`, or an error listing what there is.
    fn topic(&self, topic: &str, instance: u8) -> Result<&TopicData, UlogError> {
        let with_data = |t: &&TopicData| t.count > 0 && t.name == topic;
        if let Some(t) = self
            .topics
            .iter()
            .filter(with_data)
            .find(|t| t.instance == instance)
        {
            return Ok(t);
        }
        let mut instances: Vec<u8> = self
            .topics
            .iter()
            .filter(with_data)
            .map(|t| t.instance)
            .collect();
        if instances.is_empty() {
            return Err(UlogError::NoTopic {
                file: self.file.clone(),
                topic: topic.to_string(),
                available: self.topic_listing(),
            });
        }
        instances.sort_unstable();
        let names: Vec<String> = instances.iter().map(u8::to_string).collect();
        Err(UlogError::NoInstance {
            file: self.file.clone(),
            topic: topic.to_string(),
            instance,
            available: listing(&names, 256),
        })
    }
}

/// An integer field of a sample; the sample holds it (its layout's
/// `min_size` covers every flattened field).
fn integer(f: &FlatField, sample: &[u8]) -> i128 {
    f.ty.decode_integer(sample, f.offset).unwrap_or(0)
}

/// Samples per second over the whole series, if it spans any time.
fn mean_rate_hz(t: &[u64]) -> Option<f64> {
    let (first, last) = (*t.first()?, *t.last()?);
    (last > first).then(|| (t.len() - 1) as f64 / ((last - first) as f64 * 1e-6))
}
