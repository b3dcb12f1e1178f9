//! `rbf`: fit, predict and cross-validate RBF networks on CSV data.
//!
//! Glue only: parse the flags, run the subcommand, and turn any failure into one line
//! on stderr with a non-zero exit (never a panic, never a usage screen for bad data).

mod commands;

use std::process::ExitCode;

use clap::Parser;
use clap::error::ErrorKind;

use commands::args::{Cli, Command};

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return clap_error(e),
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
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", one_line(&chain(&e)));
            ExitCode::FAILURE
        }
    }
}

/// Help and version print as usual; a flag error becomes one line (clap's own
/// message, without the usage block) and exit status 2.
fn clap_error(e: clap::Error) -> ExitCode {
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
        _ => {
            let text = e.render().to_string();
            let body: Vec<&str> = text
                .lines()
                .map(str::trim)
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
                .filter(|l| !l.is_empty())
                .collect();
            eprintln!("{} (see --help)", one_line(&body.join(" ")));
            ExitCode::from(2)
        }
    }
}

/// The error and its causes joined by ": ", skipping a cause whose text the message
/// already quotes (many errors print their source themselves).
fn chain(e: &anyhow::Error) -> String {
    let mut msg = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if msg.is_empty() {
            msg = text;
        } else if !msg.contains(&text) {
            msg = format!("{msg}: {text}");
        }
    }
    msg
}

fn one_line(s: &str) -> String {
    s.split('\n')
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}
