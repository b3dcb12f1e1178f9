//! sysid: the identification loop, for any sensor that plugs into it.
//!
//! A model of each output channel of a sensor is a bias, named physical
//! effects linear in their coefficients (with units and intervals) and a
//! radial-basis-function network over windows of chosen input signals. The
//! loop fits such models over records with cross-validation, estimates the
//! effects' coefficients by cross-fitting with HAC errors, diagnoses what a
//! model misses (candidate effects ranked on its out-of-sample residual,
//! collinear groups and the experiment that splits them, residual tests,
//! where in time, frequency and operating range it fails), adds what the
//! diagnosis names and fits again, and checks a model on a record it was not
//! fitted on.
//!
//! It knows no sensor: a [`Sensor`] plug-in says which columns are
//! outputs and what they should read, how a raw record is calibrated, which
//! effects could be missing and how to compute their regressors, and which
//! experiment separates look-alike effects. The gyro plug-in lives in
//! `dtg-vib`; `examples/pressure_transducer.rs` is another.
//!
//! Data flow one way:
//!
//! ```text
//! Signals (t + named columns) ─ Sensor::calibrate, ::targets ─▶ Prepared (the window's signals,
//!     chosen from the records unless the recipe names them; filters, windows, regressors)
//!   ─▶ split ─▶ fit (recipe: effects + settings) ─▶ Model (stores its recipe)
//!   ─▶ predictions ─▶ diagnose (reads the model's and its mirror's predictions; states a
//!       suggestion's coefficient with fit's cross-fitted estimator, as the refit will store it)
//!   ─▶ explain (fits the models the diagnosis reads: the mirror, a longer window; adds the
//!       suggestions, fits again)
//! ```
//!
//! The diagnosis fits no channel model: the models it reads (the model,
//! its mirror, a longer window) are fitted by the loop layer
//! ([`explain`]). It calls the fit layer for one estimate only, a
//! suggestion's coefficient by the fit's own cross-fitted partialling
//! (`fit::cross_fitted_theta`, in `diagnose/estimate.rs`: that estimator
//! fits its nuisance networks), so that the diagnosis and the refit state
//! the same number and interval.
//!
//! ```
//! use sysid::example::{Line, line_record};
//! let rec = line_record(3000, 2.0, 1);
//! let mut options = sysid::FitOptions::new(1);
//! options.recipe.preprocess = Line::preprocess();
//! options.recipe.settings.max_centres = 5;
//! let e = sysid::explain::explain(&Line, &[("r".into(), &rec)], &options, &Default::default(), 3, &|_| {})?;
//! let slope = &e.model.channel(0).coefficients().unwrap()[0];
//! assert!(slope.covers(2.0));
//! # Ok::<(), sysid::SysidError>(())
//! ```

pub mod check;
pub mod diagnose;
mod error;
pub mod example;
pub mod explain;
pub mod fit;
pub mod inference;
pub mod input;
mod model;
pub mod operating;
mod prepared;
mod preprocess;
mod recipe;
pub mod residuals;
mod sensor;
mod signals;
pub mod smoother;
pub mod split;
pub mod window;

pub use error::SysidError;
pub use fit::{FitStage, RecordScore, fit, fit_prepared, fit_records};
pub use input::ModelInput;
pub use model::{
    ChannelModel, ChannelModelOf, ChannelScores, Faded, INTERVAL_TOLERANCE, Model, ModelParts,
    score,
};
pub use prepared::{Prepared, choose_window_signals, signal, window_candidates};
pub use preprocess::{FilterSpec, Preprocess};
pub use recipe::{CentreMethod, FitOptions, FitSettings, Recipe};
pub use sensor::{
    Candidacy, Effect, Named, OperatingStats, Response, Sensor, SensorError, Separation, Wording,
};
pub use signals::{Signals, SignalsError};
pub use smoother::Smoother;
pub use window::{WindowError, WindowSignals, WindowSpec, Windows};
