//! A reader of PX4 ULog files (`.ulg`), the format PX4's logger writes
//! (<https://docs.px4.io/main/en/dev_log/ulog_file_format.html>): the
//! header and flag bits, the definitions (formats with nested types and
//! arrays, info, multi-info, parameters), the data (subscriptions with
//! multi-instance ids, data, logged strings, dropouts, syncs) and appended
//! data sections, read as pyulog reads them.
//!
//! It never panics on a damaged or hostile file: a broken header or schema
//! is a typed [`UlogError`]; a cut tail, a dropout or a damaged message in
//! the data is skipped and counted in [`Integrity`], as pyulog skips it.
//!
//! - [`Ulog::read`] / [`Ulog::parse`]: a file or bytes;
//! - [`Ulog::topics`], [`Ulog::fields`], [`Ulog::describe`]: what a log has;
//! - [`Ulog::series`]: for a topic, a multi-instance id and a list of
//!   fields, the time stamps (µs, and s via [`Series::t_s`]) and each
//!   field as f64;
//! - [`UlogTable`]: a unit file's `[ulog]` table (which topic, instance and
//!   field fills each column), [`UlogTable::sensor_combined`] the default
//!   for a triad, and [`UlogTable::join`] the columns on one time base.
//!
//! ```
//! # fn main() -> Result<(), ulog::UlogError> {
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/realdata/ulog/sample_log_small.ulg");
//! if std::path::Path::new(path).exists() {
//!     let log = ulog::Ulog::read(path)?;
//!     let gyro = log.series("sensor_gyro", 1, &["x", "y", "z"])?;
//!     assert_eq!(gyro.values.len(), 3);
//!     assert_eq!(gyro.values[0].len(), gyro.time_us.len());
//!     let triad = ulog::UlogTable::sensor_combined(["gx", "gy", "gz"], ["ax", "ay", "az"]);
//!     let rec = triad.join(&log, &["gx", "gy", "gz", "ax", "ay", "az"], 3.0)?;
//!     assert_eq!(rec.t_s[0], 0.0);
//! }
//! # Ok(()) }
//! ```

mod bytes;
mod error;
mod format;
mod join;
mod messages;
mod model;
mod query;
mod read;
mod source;

pub use error::UlogError;
pub use format::{FieldType, FlatField};
pub use join::{Joined, StreamReport};
pub use model::{Dropout, Header, InfoValue, Integrity, LoggedMessage, ParameterChange, Ulog};
pub use query::{Series, TimeSource, TopicSummary};
pub use source::{FieldSource, UlogTable};
