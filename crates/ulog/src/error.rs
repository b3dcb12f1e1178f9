//! What can go wrong reading a log or a series out of it. Every message is
//! one line naming the file (and the byte offset, topic, instance or field)
//! and, where there is one, what to do instead.

use thiserror::Error;

/// An error of the ULog reader.
#[derive(Debug, Error)]
pub enum UlogError {
    /// The file could not be read.
    #[error("{file}: cannot read: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// Shorter than the 16-byte file header.
    #[error(
        "{file}: {len} bytes, shorter than the 16-byte ULog header; give a .ulg file written by PX4's logger"
    )]
    TooShort { file: String, len: usize },
    /// The header's magic bytes are not ULog's.
    #[error(
        "{file}: not a PX4 ULog file (it does not start with the bytes 55 4c 6f 67 01 12 35, \"ULog\"); give a .ulg file written by PX4's logger"
    )]
    NotUlog { file: String },
    /// The flag-bits message is too short to hold its fields.
    #[error(
        "{file}: byte {offset}: the flag-bits message has {len} bytes; ULog's has 40 (compat flags, incompat flags, 3 appended-data offsets)"
    )]
    FlagBits {
        file: String,
        offset: usize,
        len: usize,
    },
    /// An incompatible flag this reader does not know is set.
    #[error(
        "{file}: incompatible flag byte {index} is {value:#04x}: the log uses a ULog feature this reader does not know; convert it with a current pyulog (ulog2csv) and read the CSV"
    )]
    Incompatible {
        file: String,
        index: usize,
        value: u8,
    },
    /// An appended-data offset points outside the file or backwards.
    #[error("{file}: appended-data offset {offset} in the flag bits {reason}; the file is damaged")]
    AppendedOffset {
        file: String,
        offset: u64,
        reason: String,
    },
    /// A format (`F`) message that does not parse.
    #[error("{file}: byte {offset}: format message: {reason}")]
    Format {
        file: String,
        offset: usize,
        reason: String,
    },
    /// A subscription (`A`) to a topic whose format is missing or broken.
    #[error("{file}: byte {offset}: subscription to '{topic}': {reason}")]
    Subscription {
        file: String,
        offset: usize,
        topic: String,
        reason: String,
    },
    /// No topic of that name has data.
    #[error("{file}: no topic '{topic}' with data (the log has: {available})")]
    NoTopic {
        file: String,
        topic: String,
        available: String,
    },
    /// The topic has data, but not for that multi-instance id.
    #[error("{file}: topic '{topic}' has no instance {instance} with data (it has: {available})")]
    NoInstance {
        file: String,
        topic: String,
        instance: u8,
        available: String,
    },
    /// The topic has no field of that (flattened) name.
    #[error("{file}: {topic}[{instance}] has no field '{field}' (its fields: {available})")]
    NoField {
        file: String,
        topic: String,
        instance: u8,
        field: String,
        available: String,
    },
    /// A time or interval field that is not an integer count of µs.
    #[error("{file}: {topic}[{instance}].{field} is {ty}: {role} must be an integer number of µs")]
    NotMicroseconds {
        file: String,
        topic: String,
        instance: u8,
        field: String,
        ty: String,
        role: String,
    },
    /// Time stamps out of order (or repeated) within one topic instance.
    #[error(
        "{file}: {topic}[{instance}] sample {index}: time {value} µs is not after the sample before ({previous} µs); the log's samples of this topic are out of order"
    )]
    NotIncreasing {
        file: String,
        topic: String,
        instance: u8,
        index: usize,
        previous: i128,
        value: i128,
    },
    /// A time stamp that is negative once its offset field is added.
    #[error(
        "{file}: {topic}[{instance}] sample {index}: time {value} µs (with {offset_field}) is negative"
    )]
    NegativeTime {
        file: String,
        topic: String,
        instance: u8,
        index: usize,
        offset_field: String,
        value: i128,
    },
    /// An integration interval that is not positive.
    #[error(
        "{file}: {topic}[{instance}] sample {index}: interval {field} = {value} µs; a rate needs a positive interval"
    )]
    Interval {
        file: String,
        topic: String,
        instance: u8,
        index: usize,
        field: String,
        value: f64,
    },
    /// A column the caller asked for that the `[ulog]` table does not map.
    #[error(
        "ulog.columns has no entry for column '{column}' (it maps: {available}); add `{column} = {{ topic = \"…\", field = \"…\" }}`"
    )]
    Unmapped { column: String, available: String },
    /// An error about one mapped column.
    #[error("ulog.columns.{column}: {source}")]
    Column {
        column: String,
        #[source]
        source: Box<UlogError>,
    },
    /// The join left fewer than two rows.
    #[error(
        "{file}: {rows} row(s) of {base} have a value of every column, a record needs two: {reason}"
    )]
    NothingJoined {
        file: String,
        base: String,
        rows: usize,
        reason: String,
    },
}

/// `names` joined by ", ", at most `most` of them, then how many more.
pub(crate) fn listing<S: AsRef<str>>(names: &[S], most: usize) -> String {
    let mut out: Vec<&str> = names.iter().take(most).map(AsRef::as_ref).collect();
    let more;
    if names.len() > most {
        more = format!("… and {} more", names.len() - most);
        out.push(&more);
    }
    if out.is_empty() {
        "nothing".to_string()
    } else {
        out.join(", ")
    }
}

/// At most 60 characters of `s`, control characters escaped, for a
/// one-line message quoting a file's text.
pub(crate) fn shorten(s: &str) -> String {
    let mut out: String = s.chars().take(60).flat_map(char::escape_debug).collect();
    if s.chars().nth(60).is_some() {
        out.push('…');
    }
    out
}
