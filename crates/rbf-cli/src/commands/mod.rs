//! The subcommands: flags (clap) and the glue that runs each one.

pub mod args;
pub mod cv;
pub mod fit;
pub mod predict;
