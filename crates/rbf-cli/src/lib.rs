//! The reusable half of the `rbf` command line: generic data in CSV, no
//! gyros (the DTG application is `dtg-vib`), no numerics of its own (`rbf`).
//!
//! The binary (`src/main.rs`) only parses flags, reads files, calls the `rbf` library
//! and prints. What it needs beyond that lives here, one idea per module:
//!
//! | module | what |
//! |---|---|
//! | [`data`] | a `tabular::Table` → named columns as faer matrices; train/validation rows |
//! | [`settings`] | command-line choices (`--centres`, `--width`, …) → checked `rbf` params |
//! | [`saved`] | the model file: the library's model plus the column names it was fitted on |
//! | [`report`] | the `--json` objects of `fit`, `cv` and `predict` (typed, serialised by serde), and the human summaries |
//! | [`progress`] | the indicatif bar fed by the library's progress callback, and stage timings |
//! | [`hint`] | how to fix a failed fit, as a flag to change |
//! | [`train`] | the fit as `rbf fit` runs it (the `--width auto` search, the remedy on failure), for the binary and the Python binding |
//!
//! ```
//! use rbf_cli::{data, settings::{Centres, FitSettings, WidthArg}};
//!
//! let csv = "x,y,split\n0.0,0.0,train\n0.5,0.48,val\n1.0,0.84,train\n1.5,1.0,val\n2.0,0.91,train\n";
//! let table = tabular::Table::from_reader(csv.as_bytes(), "mem.csv")?;
//! let rows = data::split_by_column(&table, "split")?;
//! let inputs = data::input_columns(&table, "y", None, &["split"])?;
//! assert_eq!(inputs, vec!["x".to_string()]);
//! let x = data::numeric_matrix(&table, &inputs)?;
//! let y = data::numeric_matrix(&table, &["y".to_string()])?;
//!
//! let params = FitSettings {
//!     centres: Centres::Random,
//!     max_centres: Some(2),
//!     width: WidthArg::Fixed(1.0),
//!     ..FitSettings::default()
//! }
//! .params(rows.train.len(), inputs.len())?;
//! let (xt, yt) = (data::take_rows(x.as_ref(), &rows.train), data::take_rows(y.as_ref(), &rows.train));
//! let model = params.fit(xt.as_ref(), yt.as_ref())?;
//! assert_eq!(model.n_centres(), 2);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

pub mod data;
pub mod hint;
pub mod progress;
pub mod report;
pub mod saved;
pub mod settings;
pub mod train;
