//! Python's keyword arguments arrive as the command's flags
//! (`rbf_dtg.loop._flags`) and are parsed by the command's own flag
//! definitions, so the defaults, ranges and refusals are the command's.

use clap::Parser;
use dtg_vib::commands::explain::ExplainArgs;
use dtg_vib::commands::fit_args::FitArgs;
use dtg_vib::commands::thresholds::Thresholds;
use pyo3::PyErr;

use crate::error::Error;

/// `dtg-vib fit`'s flags.
#[derive(Parser)]
#[command(name = "fit", allow_negative_numbers = true)]
pub struct FitFlags {
    #[command(flatten)]
    pub fit: FitArgs,
}

/// `dtg-vib explain`'s flags.
#[derive(Parser)]
#[command(name = "explain", allow_negative_numbers = true)]
pub struct ExplainFlags {
    #[command(flatten)]
    pub explain: ExplainArgs,
}

/// `dtg-vib diagnose`'s thresholds.
#[derive(Parser)]
#[command(name = "diagnose")]
pub struct DiagnoseFlags {
    #[command(flatten)]
    pub thresholds: Thresholds,
}

/// The flags parsed, or clap's refusal as the command's one line (without
/// `error: ` and the pointer to `--help`).
pub fn parse<T: Parser>(argv: Vec<String>) -> Result<T, PyErr> {
    T::try_parse_from(argv).map_err(|e| {
        let line = cli_support::usage::line(&e, cli_support::Style::VERBATIM);
        let line = line.strip_prefix("error: ").unwrap_or(&line);
        Error::new_err(
            line.strip_suffix(" (see --help)")
                .unwrap_or(line)
                .to_string(),
        )
    })
}
