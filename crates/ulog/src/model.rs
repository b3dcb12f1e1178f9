//! What a log holds once read: its header, the samples of every topic
//! instance, info and parameters, logged strings, and what the reader met
//! that was not clean data (cut tail, dropouts, skipped messages).

use std::collections::BTreeMap;

use crate::format::{Formats, Layout};

/// A PX4 ULog file, read whole. Samples stay as the file's bytes until a
/// series is asked for ([`Ulog::series`]).
#[derive(Debug, Clone)]
pub struct Ulog {
    pub(crate) file: String,
    pub(crate) header: Header,
    pub(crate) formats: Formats,
    pub(crate) topics: Vec<TopicData>,
    pub(crate) info: BTreeMap<String, InfoValue>,
    pub(crate) multi_info: BTreeMap<String, Vec<Vec<InfoValue>>>,
    pub(crate) parameters: BTreeMap<String, f64>,
    pub(crate) parameter_changes: Vec<ParameterChange>,
    pub(crate) logged: Vec<LoggedMessage>,
    pub(crate) integrity: Integrity,
}

/// The file header and flag bits.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Header {
    /// ULog's file version byte (0 or 1 today).
    pub version: u8,
    /// The logger's start time, µs since boot.
    pub start_us: u64,
    pub compat_flags: [u8; 8],
    pub incompat_flags: [u8; 8],
    /// File offsets where appended data sections start (crash dumps
    /// written after the log), in the order read.
    pub appended_offsets: Vec<u64>,
}

/// The samples of one topic instance, as the file's bytes.
#[derive(Debug, Clone)]
pub(crate) struct TopicData {
    pub name: String,
    pub instance: u8,
    pub layout: Layout,
    /// Byte offset of a `uint64_t timestamp` field, if the format has one.
    pub timestamp_offset: Option<usize>,
    /// `count` samples of `layout.min_size` bytes each, in file order.
    pub bytes: Vec<u8>,
    pub count: usize,
}

/// The value of an info (`I`, `M`) message.
#[derive(Debug, Clone, PartialEq)]
pub enum InfoValue {
    /// `char[n]`: text (bytes that are not UTF-8 replaced).
    Text(String),
    /// An integer type.
    Integer(i128),
    /// `float` or `double`.
    Float(f64),
    /// Anything else (arrays of numbers, `bool`), as stored.
    Bytes(Vec<u8>),
}

/// A parameter changed during the log.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterChange {
    /// The latest data time stamp before the change, µs.
    pub after_us: u64,
    pub name: String,
    pub value: f64,
}

/// A string the firmware logged (`L`, or tagged `C`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoggedMessage {
    /// The log level, ASCII '0' (emergency) to '7' (debug).
    pub level: u8,
    pub tag: Option<u16>,
    pub timestamp_us: u64,
    pub text: String,
}

/// A dropout (`O`): the logger lost data for a while.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dropout {
    /// The latest data time stamp before it, µs.
    pub after_us: u64,
    pub duration_ms: u16,
}

/// What the reader met that was not clean data. None of it is an error:
/// PX4 logs are routinely cut by a power loss, and a damaged message is
/// skipped as pyulog skips it; the caller says what it means.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Integrity {
    /// The file ends inside a message (a power loss or a pulled card): that
    /// message is lost.
    pub truncated: bool,
    /// Appended data sections read (after a crash).
    pub appended_sections: usize,
    /// Messages cut by the start of an appended section (dropped).
    pub cut_messages: usize,
    /// Messages skipped as damaged: data of an id no subscription has, of a
    /// size its format cannot have, or a known message too short for its
    /// fields.
    pub corrupt_messages: usize,
    /// Messages of a type this reader does not know, skipped by their size.
    pub unknown_messages: usize,
    /// Bytes skipped looking for a sync marker after a damaged header.
    pub skipped_bytes: usize,
    /// Sync markers seen.
    pub syncs: usize,
    /// Subscriptions whose topic has no usable format: why, per topic.
    pub bad_subscriptions: Vec<String>,
    /// Dropouts, in order.
    pub dropouts: Vec<Dropout>,
}

impl Integrity {
    /// Nothing lost, skipped or damaged (appended sections and syncs are
    /// normal).
    pub fn is_clean(&self) -> bool {
        !self.truncated
            && self.cut_messages == 0
            && self.corrupt_messages == 0
            && self.unknown_messages == 0
            && self.skipped_bytes == 0
            && self.bad_subscriptions.is_empty()
            && self.dropouts.is_empty()
    }

    /// One line: "clean", or what was lost.
    pub fn summary(&self) -> String {
        let mut parts = Vec::new();
        if !self.dropouts.is_empty() {
            let total: u64 = self.dropouts.iter().map(|d| d.duration_ms as u64).sum();
            let longest = self
                .dropouts
                .iter()
                .map(|d| d.duration_ms)
                .max()
                .unwrap_or(0);
            parts.push(format!(
                "{} logger dropout(s), {total} ms in all, longest {longest} ms",
                self.dropouts.len()
            ));
        }
        if self.truncated {
            parts.push("the file ends inside a message (cut while logging)".into());
        }
        let counts = [
            (
                self.cut_messages,
                "message(s) cut by an appended section dropped",
            ),
            (self.corrupt_messages, "damaged message(s) skipped"),
            (self.unknown_messages, "message(s) of unknown type skipped"),
            (self.skipped_bytes, "byte(s) skipped to a sync marker"),
            (
                self.bad_subscriptions.len(),
                "subscription(s) without a usable format",
            ),
        ];
        for (n, what) in counts {
            if n > 0 {
                parts.push(format!("{n} {what}"));
            }
        }
        if parts.is_empty() {
            "clean".into()
        } else {
            parts.join("; ")
        }
    }
}

impl Ulog {
    /// The file name errors carry.
    pub fn file(&self) -> &str {
        &self.file
    }

    pub fn header(&self) -> &Header {
        &self.header
    }

    /// Info messages by key (`sys_name`, `ver_hw`, `ver_sw`, …).
    pub fn info(&self) -> &BTreeMap<String, InfoValue> {
        &self.info
    }

    /// Multi-info messages by key: each list one message with its
    /// continuations.
    pub fn multi_info(&self) -> &BTreeMap<String, Vec<Vec<InfoValue>>> {
        &self.multi_info
    }

    /// Parameters as the log started.
    pub fn parameters(&self) -> &BTreeMap<String, f64> {
        &self.parameters
    }

    /// Parameters changed during the log.
    pub fn parameter_changes(&self) -> &[ParameterChange] {
        &self.parameter_changes
    }

    /// Strings the firmware logged.
    pub fn logged_messages(&self) -> &[LoggedMessage] {
        &self.logged
    }

    /// What was lost or skipped.
    pub fn integrity(&self) -> &Integrity {
        &self.integrity
    }
}
