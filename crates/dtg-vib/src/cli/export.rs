//! `dtg-vib export`: a causal model as C99 sources and onboard tables, or
//! any model as equations (on stdout, or into `DIR/equations.txt`).

use anyhow::Result;
use clap::Args;
use std::path::{Path, PathBuf};

use dtg_vib::commands::records::open_model;

/// The flags of `export`.
#[derive(Args)]
pub struct ExportArgs {
    /// Model file from `fit --causal` (any model for --lang text).
    #[arg(long)]
    model: PathBuf,
    /// c: dtg_model.h, dtg_model.c, main.c and model.dtgo into --out; text:
    /// equations on stdout, or into equations.txt with --out.
    #[arg(long)]
    lang: String,
    /// Output directory (--lang c; --lang text writes equations.txt there).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Tables and arithmetic of the C: f64 (equal to `compensate`) or f32.
    #[arg(long, default_value = "f64")]
    precision: String,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); not needed (a model stores its unit), and
    /// refused when it is not the model's.
    #[arg(long)]
    unit: Option<String>,
}

/// The file `--lang text --out DIR` writes into DIR.
const EQUATIONS_FILE: &str = "equations.txt";

/// Writes the C sources and tables, or the equations, of a model of any
/// unit (a paper model file is the paper unit's model).
pub fn run(a: ExportArgs) -> Result<()> {
    let m = open_model(&a.model, a.unit.as_deref())?;
    match a.lang.as_str() {
        "text" => write_text(&dtg_vib::export::equations(&m), &a.model, a.out.as_deref()),
        "c" => {
            let Some(out) = &a.out else {
                anyhow::bail!("--lang c writes files: give the directory with --out DIR");
            };
            let precision: dtg_vib::export::Precision = a.precision.parse()?;
            let tables = dtg_vib::export::tables(&m)?;
            let c = dtg_vib::export::c_sources(&m, precision)?;
            write_c(&c, &tables, &a.model, out)
        }
        other => anyhow::bail!("--lang {other}: use c (C99 sources) or text (equations)"),
    }
}

/// `equations` on stdout, or into `out/equations.txt`.
fn write_text(equations: &str, model_path: &Path, out: Option<&Path>) -> Result<()> {
    let Some(out) = out else {
        print!("{equations}");
        return Ok(());
    };
    outfile::guard_dir(
        "--out",
        out,
        &[EQUATIONS_FILE],
        &[("--model", Some(model_path))],
    )?;
    write_files(out, [(EQUATIONS_FILE, equations.as_bytes())])?;
    let path = out.join(EQUATIONS_FILE);
    println!("wrote {}", path.display());
    Ok(())
}

/// Writes C sources and tables into `out` and says what they hold.
fn write_c(
    c: &dtg_vib::export::CSources,
    tables: &dtg_vib::export::Tables,
    model_path: &Path,
    out: &Path,
) -> Result<()> {
    let files = ["dtg_model.h", "dtg_model.c", "main.c", "model.dtgo"];
    outfile::guard_dir("--out", out, &files, &[("--model", Some(model_path))])?;
    let sources = c.files().map(|(name, text)| (name, text.as_bytes()));
    write_files(
        out,
        sources
            .into_iter()
            .chain([("model.dtgo", &tables.bytes[..])]),
    )?;
    let m = dtg_onboard::Model::parse(&tables.bytes).map_err(|e| anyhow::anyhow!("{e}"))?;
    println!(
        "wrote {}: dtg_model.h, dtg_model.c, main.c (cc -O2 -std=c99 *.c -lm), model.dtgo ({} bytes of tables, {} f64 of state, {} flops and {} exponentials per step; extra columns: {})",
        out.display(),
        m.size_bytes(),
        m.state_len(),
        m.flops_per_step(),
        m.exps_per_step(),
        if tables.extra.is_empty() {
            "none".to_string()
        } else {
            tables.extra.join(", ")
        }
    );
    Ok(())
}

/// Writes each (name, bytes) into `out`, made if missing; each file atomically.
fn write_files<'a>(out: &Path, files: impl IntoIterator<Item = (&'a str, &'a [u8])>) -> Result<()> {
    std::fs::create_dir_all(out).map_err(|e| anyhow::anyhow!("--out {}: {e}", out.display()))?;
    for (name, bytes) in files {
        let path = out.join(name);
        outfile::write_bytes(&path, bytes)
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    }
    Ok(())
}
