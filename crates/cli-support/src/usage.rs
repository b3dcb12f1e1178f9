//! A command-line usage error on one line, like every other error: clap's
//! message and any tip, without the usage block (`--help` has it), and exit
//! status 2. Help and version requests print as clap prints them.

use std::process::ExitCode;

use clap::error::ErrorKind;

use crate::Style;

/// clap's message as one line ending in "(see --help)".
///
/// ```
/// use clap::Parser;
/// use cli_support::{Style, usage::line};
///
/// #[derive(Parser, Debug)]
/// struct Cli {
///     #[arg(long)]
///     model: String,
/// }
/// let e = Cli::try_parse_from(["x", "--modle", "m"]).unwrap_err();
/// assert_eq!(
///     line(&e, Style::VERBATIM),
///     "error: unexpected argument '--modle' found; tip: a similar argument exists: '--model' (see --help)"
/// );
/// assert_eq!(
///     line(&e, Style::TRIMMED),
///     "error: unexpected argument '--modle' found tip: a similar argument exists: '--model' (see --help)"
/// );
/// ```
pub fn line(e: &clap::Error, style: Style) -> String {
    let text = e.render().to_string();
    let parts = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"));
    let mut line = String::new();
    for part in parts {
        if !line.is_empty() {
            line.push_str(if style.usage_semicolons && !line.ends_with(':') {
                "; "
            } else {
                " "
            });
        }
        line.push_str(part);
    }
    format!("{line} (see --help)")
}

/// Ends a run whose flags clap refused: help and version print (exit 0), any
/// other error is one line on stderr and exit status 2.
///
/// ```no_run
/// use clap::Parser;
/// #[derive(Parser)]
/// struct Cli {}
/// fn main() -> std::process::ExitCode {
///     let _cli = match Cli::try_parse() {
///         Ok(cli) => cli,
///         Err(e) => return cli_support::usage::exit(e, cli_support::Style::TRIMMED),
///     };
///     std::process::ExitCode::SUCCESS
/// }
/// ```
pub fn exit(e: clap::Error, style: Style) -> ExitCode {
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
        _ => {
            eprintln!("{}", line(&e, style));
            ExitCode::from(2)
        }
    }
}
