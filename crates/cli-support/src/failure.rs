//! A failed run told in one line: `error: ` then what, where (the libraries'
//! errors carry file:line:column or the flag) and how to fix it; exit status 1.

use std::process::ExitCode;

use crate::Style;

/// The error and its causes joined by ": ", skipping a cause whose text the
/// message already quotes (many errors print their source themselves), on one
/// line as `style` says.
///
/// ```
/// use cli_support::{Style, failure::message};
///
/// let io = std::io::Error::other("no space left");
/// let e = anyhow::Error::new(io).context("m.json: no space left");
/// assert_eq!(message(&e, Style::TRIMMED), "m.json: no space left");
///
/// let e = anyhow::anyhow!("parse error\n  | a =\n").context("bad.toml");
/// assert_eq!(message(&e, Style::TRIMMED), "bad.toml: parse error; | a =");
/// assert_eq!(message(&e, Style::VERBATIM), "bad.toml: parse error;   | a =; ");
/// ```
pub fn message(e: &anyhow::Error, style: Style) -> String {
    let mut msg = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if msg.is_empty() {
            msg = text;
        } else if !msg.contains(&text) {
            msg = format!("{msg}: {text}");
        }
    }
    if style.trim_lines {
        msg.split('\n')
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ")
    } else {
        msg.replace('\n', "; ")
    }
}

/// The exit of a run: success, or its error as one `error:` line on stderr
/// and exit status 1.
///
/// ```
/// use cli_support::{Style, failure::exit};
/// assert_eq!(exit(Ok(()), Style::TRIMMED), std::process::ExitCode::SUCCESS);
/// assert_eq!(exit(Err(anyhow::anyhow!("no")), Style::TRIMMED), std::process::ExitCode::FAILURE);
/// ```
pub fn exit(result: anyhow::Result<()>, style: Style) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", message(&e, style));
            ExitCode::FAILURE
        }
    }
}
