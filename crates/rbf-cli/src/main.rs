//! `rbf`: fit, predict and cross-validate RBF networks on CSV data.
//!
//! Glue only: parse the flags, run the subcommand, and turn any failure into one line
//! on stderr with a non-zero exit (never a panic, never a usage screen for bad data).

mod commands;

use std::process::ExitCode;

use clap::Parser;
use cli_support::Style;

use commands::args::{Cli, Command};

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return cli_support::usage::exit(e, Style::TRIMMED),
    };
    if let Some(n) = cli.threads {
        // Before any params are built: they capture faer's global parallelism. The rayon
        // pool bounds what runs outside faer too (linfa's k-means, the library's loops).
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global();
        rbf::faer::set_global_parallelism(if n == 1 {
            rbf::Par::Seq
        } else {
            rbf::Par::rayon(n)
        });
    }
    let result = match cli.command {
        Command::Fit(a) => commands::fit::run(a),
        Command::Predict(a) => commands::predict::run(a),
        Command::Cv(a) => commands::cv::run(a),
    };
    cli_support::failure::exit(result, Style::TRIMMED)
}
