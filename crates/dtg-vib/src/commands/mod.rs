//! Each command's work as a library call, from its flags to its result:
//! the `dtg-vib` binary parses, calls these and prints; the Python
//! package (`python/`) calls the same functions, so both give one answer.
//!
//! | module | what |
//! |---|---|
//! | [`records`] | the unit, a model file, the plug-in and logs read with the unit, as every command resolves them |
//! | [`fit_args`] | the flags of a fit (`fit`, `explain`), resolved once into what the fit is told |
//! | [`thresholds`] | when the diagnosis suggests an effect (`diagnose`, `explain`) |
//! | [`parse`] | validators of numeric flags, each saying the valid range |
//! | [`simulate`], [`fit`], [`diagnose`], [`explain`], [`compensate`], [`residues`], [`allan`], [`report`] | the commands' work |
//! | [`fit_report`] | `fit --json` |

pub mod allan;
pub mod compensate;
pub mod diagnose;
pub mod explain;
pub mod fit;
pub mod fit_args;
pub mod fit_report;
pub mod parse;
pub mod records;
pub mod report;
pub mod residues;
pub mod simulate;
pub mod thresholds;
