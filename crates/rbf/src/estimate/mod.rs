//! Parameter estimation: least squares by column-pivoted QR (optionally ridge-regularised)
//! and the all-points interpolation solve (Cholesky, or a saddle-point system with a
//! polynomial tail). Never the normal equations: they square the condition number.

mod condition;
mod error;
mod interpolate;
mod lstsq;
mod stream;

pub use error::SolveError;
pub use interpolate::{Interpolation, InterpolationOptions, interpolate};
pub use lstsq::{DEFAULT_MAX_CONDITION, LstsqOptions, Solution, lstsq};
pub use stream::StreamingLstsq;
