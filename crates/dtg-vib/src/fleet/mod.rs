//! A lot of units: every unit's campaign run as an independent, idempotent
//! task that any batch engine can run, and the lot summarised.
//!
//! [`manifest`] (the lot: unit, `explain` options, limits, entries) →
//! [`task`] (one unit: its `explain`, its page, into `DIR/units/ID/`
//! whole, [`layout`]; its cost, [`measure`]) → run by [`run`] (this
//! machine, N at a time) or by an engine from a [`plan`] (Slurm job
//! array, Kubernetes Indexed Job) → [`summary`] (per channel and effect:
//! median, MAD, out of family by [`family`]; failing the spec; failed)
//! and its [`page`]. [`simulated`] writes a lot to try it on.

pub mod family;
pub mod layout;
pub mod manifest;
pub mod measure;
pub mod page;
pub mod plan;
pub mod run;
pub mod simulated;
pub mod summary;
pub mod task;
