//! `dtg-vib export`: a causal model as C99 sources and onboard tables, or
//! any model as equations.

use anyhow::Result;
use clap::Args;
use dtg_vib::model::CompensationModel;
use std::path::PathBuf;

/// The flags of `export`.
#[derive(Args)]
pub struct ExportArgs {
    /// Model file from `fit --causal` (any model for --lang text).
    #[arg(long)]
    model: PathBuf,
    /// c: dtg_model.h, dtg_model.c, main.c and model.dtgo into --out; text: equations on stdout.
    #[arg(long)]
    lang: String,
    /// Output directory (--lang c).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Tables and arithmetic of the C: f64 (equal to `compensate`) or f32.
    #[arg(long, default_value = "f64")]
    precision: String,
}

/// Writes the C sources and tables, or prints the equations.
pub fn run(a: ExportArgs) -> Result<()> {
    let ExportArgs {
        model,
        lang,
        out,
        precision,
    } = a;
    export(&model, &lang, out.as_deref(), &precision)
}

/// `dtg-vib export`: the model as C99 sources and onboard tables, or as equations.
fn export(
    model_path: &std::path::Path,
    lang: &str,
    out: Option<&std::path::Path>,
    precision: &str,
) -> anyhow::Result<()> {
    let model = CompensationModel::load(model_path)?;
    match lang {
        "text" => {
            print!("{}", dtg_vib::export::equations(&model));
            Ok(())
        }
        "c" => {
            let Some(out) = out else {
                anyhow::bail!("--lang c writes files: give the directory with --out DIR");
            };
            let precision: dtg_vib::export::Precision = precision.parse()?;
            let files = ["dtg_model.h", "dtg_model.c", "main.c", "model.dtgo"];
            outfile::guard_dir("--out", out, &files, &[("--model", Some(model_path))])?;
            let c = dtg_vib::export::c_sources(&model, precision)?;
            let tables = dtg_vib::export::tables(&model)?;
            std::fs::create_dir_all(out)
                .map_err(|e| anyhow::anyhow!("--out {}: {e}", out.display()))?;
            for (name, text) in c.files() {
                outfile::write_bytes(out.join(name), text)
                    .map_err(|e| anyhow::anyhow!("{}: {e}", out.join(name).display()))?;
            }
            let bin = out.join("model.dtgo");
            outfile::write_bytes(&bin, &tables.bytes)
                .map_err(|e| anyhow::anyhow!("{}: {e}", bin.display()))?;
            let m = dtg_onboard::Model::parse(&tables.bytes).map_err(|e| anyhow::anyhow!("{e}"))?;
            println!(
                "wrote {}: dtg_model.h, dtg_model.c, main.c (cc -O2 -std=c99 *.c -lm), model.dtgo ({} bytes of tables, {} f64 of state, {} flops per step; extra columns: {})",
                out.display(),
                m.size_bytes(),
                m.state_len(),
                m.flops_per_step(),
                if tables.extra.is_empty() {
                    "none".to_string()
                } else {
                    tables.extra.join(", ")
                }
            );
            Ok(())
        }
        other => anyhow::bail!("--lang {other}: use c (C99 sources) or text (equations)"),
    }
}
