//! Output files that never destroy an input. It is not a format writer:
//! callers bring the bytes (CSV, JSON, SVG, PNG).
//!
//! This crate is the one place where the workspace's tools put a file on disk:
//! every output is written to a temporary file in the target's directory,
//! flushed to the device and renamed into place, so a failed or interrupted
//! run leaves the previous file intact and no partial file behind. Before any
//! work, a tool asks [`refuse_inputs`] whether an output path is one of its
//! inputs (the same file after following links, or the same inode) and
//! [`check_writable`] whether the output's directory exists and takes files.
//!
//! It is not a file format: callers serialise; this crate only places bytes.
//!
//! ```
//! use std::io::Write;
//! let dir = std::env::temp_dir().join("outfile-doc");
//! std::fs::create_dir_all(&dir).unwrap();
//! let path = dir.join("model.json");
//! outfile::write_atomic(&path, |w| w.write_all(b"{}")).unwrap();
//! assert_eq!(std::fs::read(&path).unwrap(), b"{}");
//!
//! // A failed write leaves the previous content in place.
//! let failed: std::io::Result<()> = outfile::write_atomic(&path, |w| {
//!     w.write_all(b"{\"half")?;
//!     Err(std::io::Error::other("disk full"))
//! });
//! assert!(failed.is_err());
//! assert_eq!(std::fs::read(&path).unwrap(), b"{}");
//! ```

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A path as the user gave it, with the flag that named it (`--out`, `--data`).
#[derive(Debug, Clone, Copy)]
pub struct Named<'a> {
    /// The flag as the user types it, e.g. `--out`.
    pub flag: &'a str,
    /// The path given with that flag.
    pub path: &'a Path,
}

impl<'a> Named<'a> {
    /// A path named by `flag`.
    pub fn new(flag: &'a str, path: &'a Path) -> Self {
        Self { flag, path }
    }
}

/// Why an output path cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The output would overwrite an input.
    #[error(
        "{out_flag} {out} is the same file as {in_flag} {input}: writing it would destroy the input; give {out_flag} another path"
    )]
    SameAsInput {
        /// Flag of the output.
        out_flag: String,
        /// The output path (for a directory output, the file inside it).
        out: PathBuf,
        /// Flag of the input.
        in_flag: String,
        /// The input path.
        input: PathBuf,
    },
    /// The directory that would hold the output does not exist.
    #[error(
        "{flag} {path}: the directory {dir} does not exist; create it or give {flag} a path in an existing directory"
    )]
    NoDirectory {
        /// Flag of the output.
        flag: String,
        /// The output path.
        path: PathBuf,
        /// The missing directory.
        dir: PathBuf,
    },
    /// The directory exists but a file cannot be created in it.
    #[error(
        "{flag} {path}: cannot create a file in {dir} ({source}); give {flag} a path in a writable directory"
    )]
    NotWritable {
        /// Flag of the output.
        flag: String,
        /// The output path.
        path: PathBuf,
        /// The directory tried.
        dir: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
}

/// Writes a file atomically: `fill` writes into a temporary file in the same
/// directory, which is flushed, synced and renamed over `path` only if `fill`
/// succeeded. On any error the temporary file is removed and `path` is
/// untouched.
///
/// New files get the usual permissions (0666 less the process umask on Unix),
/// not the 0600 of a temporary file.
pub fn write_atomic<E, F>(path: impl AsRef<Path>, fill: F) -> Result<(), E>
where
    E: From<std::io::Error>,
    F: FnOnce(&mut BufWriter<&mut File>) -> Result<(), E>,
{
    write_atomic_or(path, E::from, fill)
}

/// As [`write_atomic`] for error types without `From<std::io::Error>`:
/// `io` turns an I/O failure of the temporary file or the rename into `E`.
pub fn write_atomic_or<E, F>(
    path: impl AsRef<Path>,
    io: impl Fn(std::io::Error) -> E,
    fill: F,
) -> Result<(), E>
where
    F: FnOnce(&mut BufWriter<&mut File>) -> Result<(), E>,
{
    let given = path.as_ref();
    // A link is followed, so the file it points to is replaced and the link
    // stays a link.
    let resolved = std::fs::canonicalize(given).ok();
    let path = resolved.as_deref().unwrap_or(given);
    if let Ok(meta) = std::fs::metadata(path)
        && !meta.is_file()
    {
        // A device or a pipe (/dev/null, /dev/stdout, a FIFO) is written in
        // place: renaming over it would replace the device with a file.
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(&io)?;
        let mut w = BufWriter::new(&mut f);
        fill(&mut w)?;
        return w.flush().map_err(&io);
    }
    let dir = parent_dir(path);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".part");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder.tempfile_in(&dir).map_err(&io)?;
    {
        let mut w = BufWriter::new(tmp.as_file_mut());
        fill(&mut w)?;
        w.flush().map_err(&io)?;
    }
    tmp.as_file().sync_all().map_err(&io)?;
    tmp.persist(path).map_err(|e| io(e.error))?;
    Ok(())
}

/// [`write_atomic`] for bytes already in memory.
pub fn write_bytes(path: impl AsRef<Path>, bytes: impl AsRef<[u8]>) -> std::io::Result<()> {
    write_atomic(path, |w| w.write_all(bytes.as_ref()))
}

/// Refuses an output that is one of the inputs (same file after following
/// links, or the same device and inode). Inputs or outputs that do not exist
/// yet cannot be the same file and pass.
pub fn refuse_inputs(out: Named<'_>, inputs: &[Named<'_>]) -> Result<(), OutputError> {
    for input in inputs {
        if same_file::is_same_file(out.path, input.path).unwrap_or(false) {
            return Err(OutputError::SameAsInput {
                out_flag: out.flag.to_string(),
                out: out.path.to_path_buf(),
                in_flag: input.flag.to_string(),
                input: input.path.to_path_buf(),
            });
        }
    }
    Ok(())
}

/// As [`refuse_inputs`] for an output directory: none of the files the
/// command writes into `dir` (`files`, relative names) may be an input.
pub fn refuse_inputs_in_dir(
    dir: Named<'_>,
    files: &[&str],
    inputs: &[Named<'_>],
) -> Result<(), OutputError> {
    for f in files {
        let inside = dir.path.join(f);
        refuse_inputs(Named::new(dir.flag, &inside), inputs)?;
    }
    Ok(())
}

/// Checks, before any work, that a file can be created at `out`: its
/// directory exists and takes a new file. The probe file is removed.
pub fn check_writable(out: Named<'_>) -> Result<(), OutputError> {
    if let Ok(meta) = std::fs::metadata(out.path)
        && !meta.is_file()
        && !meta.is_dir()
    {
        // A device or pipe is written in place (see `write_atomic`).
        return std::fs::OpenOptions::new()
            .write(true)
            .open(out.path)
            .map(drop)
            .map_err(|source| OutputError::NotWritable {
                flag: out.flag.to_string(),
                path: out.path.to_path_buf(),
                dir: parent_dir(out.path),
                source,
            });
    }
    let dir = parent_dir(out.path);
    probe(out, &dir)
}

/// Checks, before any work, that the directory `out` can be created (if
/// missing) and filled: its nearest existing ancestor is a directory that
/// takes a new file.
pub fn check_dir_writable(out: Named<'_>) -> Result<(), OutputError> {
    let mut dir = out.path.to_path_buf();
    while !dir.exists() {
        match dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => dir = p.to_path_buf(),
            _ => {
                dir = PathBuf::from(".");
                break;
            }
        }
    }
    probe(out, &dir)
}

/// Everything a command checks before any work for one output file named by
/// `flag`: it is none of `inputs` (flag and path; `None` for an optional input
/// the user did not give) and its directory takes a new file.
///
/// ```
/// use std::path::Path;
/// let dir = std::env::temp_dir();
/// let data = dir.join("outfile-doc-guard.csv");
/// std::fs::write(&data, "t\n0\n").unwrap();
/// let e = outfile::guard_file("--out", &data, &[("--data", Some(&data)), ("--calib", None)]);
/// assert!(e.unwrap_err().to_string().contains("same file as --data"));
/// outfile::guard_file("--out", &dir.join("outfile-doc-model.json"), &[("--data", Some(&data))]).unwrap();
/// ```
pub fn guard_file(
    flag: &str,
    out: &Path,
    inputs: &[(&str, Option<&Path>)],
) -> Result<(), OutputError> {
    let out = Named::new(flag, out);
    refuse_inputs(out, &named(inputs))?;
    check_writable(out)
}

/// As [`guard_file`] for an output directory into which the command writes
/// `files` (names relative to it).
pub fn guard_dir(
    flag: &str,
    dir: &Path,
    files: &[&str],
    inputs: &[(&str, Option<&Path>)],
) -> Result<(), OutputError> {
    let dir = Named::new(flag, dir);
    refuse_inputs_in_dir(dir, files, &named(inputs))?;
    check_dir_writable(dir)
}

fn named<'a>(inputs: &[(&'a str, Option<&'a Path>)]) -> Vec<Named<'a>> {
    inputs
        .iter()
        .filter_map(|&(flag, path)| path.map(|p| Named::new(flag, p)))
        .collect()
}

fn probe(out: Named<'_>, dir: &Path) -> Result<(), OutputError> {
    if !dir.is_dir() {
        return Err(OutputError::NoDirectory {
            flag: out.flag.to_string(),
            path: out.path.to_path_buf(),
            dir: dir.to_path_buf(),
        });
    }
    tempfile::Builder::new()
        .prefix(".write-probe.")
        .tempfile_in(dir)
        .map(drop)
        .map_err(|source| OutputError::NotWritable {
            flag: out.flag.to_string(),
            path: out.path.to_path_buf(),
            dir: dir.to_path_buf(),
            source,
        })
}

fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("outfile-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".part"))
            .collect()
    }

    #[test]
    fn failed_write_keeps_old_file_and_leaves_no_part_file() {
        let d = scratch("fail");
        let p = d.join("a.csv");
        write_bytes(&p, b"good").unwrap();
        let r: std::io::Result<()> = write_atomic(&p, |w| {
            w.write_all(&[b'x'; 100_000])?;
            Err(std::io::Error::other("killed"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&p).unwrap(), b"good");
        assert!(leftovers(&d).is_empty(), "{:?}", leftovers(&d));
    }

    #[cfg(unix)]
    #[test]
    fn devices_are_written_in_place_not_replaced() {
        use std::os::unix::fs::FileTypeExt;
        write_bytes("/dev/null", b"discarded").unwrap();
        let meta = std::fs::metadata("/dev/null").unwrap();
        assert!(meta.file_type().is_char_device());
    }

    #[cfg(unix)]
    #[test]
    fn a_link_stays_a_link() {
        let d = scratch("symlink");
        let real = d.join("real.json");
        std::fs::write(&real, b"old").unwrap();
        let link = d.join("link.json");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_bytes(&link, b"new").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
    }

    #[test]
    fn replaces_existing_file() {
        let d = scratch("replace");
        let p = d.join("m.json");
        write_bytes(&p, b"old").unwrap();
        write_bytes(&p, b"new").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"new");
    }

    #[test]
    fn same_file_is_refused_through_a_different_spelling() {
        let d = scratch("same");
        let p = d.join("r.csv");
        std::fs::write(&p, b"t\n").unwrap();
        let other = d.join(".").join("r.csv");
        let e =
            refuse_inputs(Named::new("--out", &other), &[Named::new("--data", &p)]).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("--out") && msg.contains("--data"), "{msg}");
        // A different, not yet existing file passes.
        refuse_inputs(
            Named::new("--out", &d.join("new.csv")),
            &[Named::new("--data", &p)],
        )
        .unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn hard_link_is_the_same_file() {
        let d = scratch("link");
        let p = d.join("r.csv");
        std::fs::write(&p, b"t\n").unwrap();
        let l = d.join("link.csv");
        std::fs::hard_link(&p, &l).unwrap();
        assert!(refuse_inputs(Named::new("--out", &l), &[Named::new("--data", &p)]).is_err());
    }

    #[test]
    fn directory_output_refuses_an_input_inside() {
        let d = scratch("dir");
        let s = d.join("scenario.toml");
        std::fs::write(&s, b"x").unwrap();
        let e = refuse_inputs_in_dir(
            Named::new("--out", &d),
            &["record.csv", "scenario.toml"],
            &[Named::new("--scenario", &s)],
        )
        .unwrap_err();
        assert!(e.to_string().contains("--scenario"));
    }

    #[test]
    fn missing_directory_is_named() {
        let d = scratch("missing");
        let p = d.join("no").join("such").join("m.json");
        let e = check_writable(Named::new("--out", &p)).unwrap_err();
        assert!(matches!(e, OutputError::NoDirectory { .. }), "{e}");
        // A directory output may be created below an existing one.
        check_dir_writable(Named::new("--out", &d.join("no").join("such"))).unwrap();
        // But not below a file.
        let f = d.join("file");
        std::fs::write(&f, b"").unwrap();
        assert!(check_dir_writable(Named::new("--out", &f.join("sub"))).is_err());
    }
}
