//! Memory a fit will need, checked before the allocation instead of
//! aborting in the allocator.

/// Bytes of memory available to this process now: `MemAvailable` of
/// `/proc/meminfo` on Linux; `None` where it cannot be read (no check is
/// then made).
pub fn available_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    text.lines()
        .find_map(|l| l.strip_prefix("MemAvailable:"))
        .and_then(|rest| rest.trim().strip_suffix("kB"))
        .and_then(|kb| kb.trim().parse::<u64>().ok())
        .map(|kb| kb * 1024)
}

/// The share of the available memory one matrix may take: the rest is for
/// the copies and work arrays around it and for everything else running.
const SHARE: f64 = 0.5;

/// Checks that an `n × m` f64 matrix fits in `available` bytes (half of
/// them, see `SHARE`); the error gives the largest `m` that would fit.
///
/// ```
/// let e = rbf::memory::check_matrix(1_000_000, 1_000_000, Some(16 << 30), "candidate kernel matrix").unwrap_err();
/// assert_eq!(e.max_columns, 1073);
/// assert!(rbf::memory::check_matrix(2500, 2500, Some(16 << 30), "candidate kernel matrix").is_ok());
/// ```
pub fn check_matrix(
    n: usize,
    m: usize,
    available: Option<u64>,
    what: &'static str,
) -> Result<(), MemoryError> {
    check_entries(n, m, 8, available, what)
}

/// [`check_matrix`] for a matrix of `entry_bytes` bytes an entry (4 for the f32 copy
/// of OLS candidates).
///
/// ```
/// let e = rbf::memory::check_entries(1_000_000, 1_000_000, 4, Some(16 << 30), "f32 candidate copy").unwrap_err();
/// assert_eq!(e.max_columns, 2147);
/// ```
pub fn check_entries(
    n: usize,
    m: usize,
    entry_bytes: usize,
    available: Option<u64>,
    what: &'static str,
) -> Result<(), MemoryError> {
    let Some(available) = available else {
        return Ok(());
    };
    let per = entry_bytes as f64;
    let bytes = (n as f64) * (m as f64) * per;
    let budget = available as f64 * SHARE;
    if bytes <= budget {
        return Ok(());
    }
    Err(MemoryError {
        what,
        rows: n,
        columns: m,
        bytes,
        available: available as f64,
        max_columns: (budget / (per * n.max(1) as f64)).floor() as usize,
        entry_bytes,
    })
}

/// A matrix that would not fit in memory.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "the {what} would take {:.1} GiB ({rows} rows × {columns} columns × {entry_bytes} bytes) but {:.1} GiB of memory are available; at most {max_columns} columns fit in half of it",
    bytes / GIB,
    available / GIB
)]
pub struct MemoryError {
    /// Which matrix.
    pub what: &'static str,
    /// Its rows.
    pub rows: usize,
    /// Its columns.
    pub columns: usize,
    /// Bytes it needs.
    pub bytes: f64,
    /// Bytes available.
    pub available: f64,
    /// The most columns that fit the budget.
    pub max_columns: usize,
    /// Bytes an entry.
    pub entry_bytes: usize,
}

const GIB: f64 = (1u64 << 30) as f64;
