//! `dtg-vib`: the command line. Parse the flags, run the subcommand (each in
//! its module under `cli/`: flags, glue and printing), and turn a failure
//! into one `error:` line on stderr with exit status 1 (2 for a flag clap
//! refuses); nothing else lives here.

mod cli;

use std::process::ExitCode;

use clap::Parser;
use cli::{Cli, Command};
use cli_support::Style;
use cli_support::progress::{Progress, visible};

fn main() -> ExitCode {
    cli_support::pipe::end_quietly_on_closed_pipe();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return cli_support::usage::exit(e, Style::VERBATIM),
    };
    // Errors as rbf prints them: a TOML error's excerpt lines trimmed, not
    // "…;   |; 2 | seed = ;   |        ^; …".
    cli_support::failure::exit(run(cli), Style::TRIMMED)
}

fn run(cli: Cli) -> anyhow::Result<()> {
    let progress = Progress::new(visible(cli.quiet));
    match cli.command {
        Command::Simulate(a) => cli::simulate::run(a, progress),
        Command::Fit(a) => cli::fit::run(*a, progress),
        Command::Compensate(a) => cli::compensate::run(a, progress),
        Command::Residues(a) => cli::residues::run(a, progress),
        Command::Report(a) => cli::report::run(a, progress),
        Command::Check(a) => cli::check::run(a, progress),
        Command::Diagnose(a) => cli::diagnose::run(a, progress),
        Command::Explain(a) => cli::explain::run(*a, progress),
        Command::Allan(a) => cli::allan::run(a, progress),
        Command::Export(a) => cli::export::run(a),
        Command::Demo(a) => cli::demo::run(a, progress),
        Command::Fleet(a) => cli::fleet::run(a, progress),
    }
}
