//! The single-axis rate-gyro error model (MEMS and other Coriolis vibratory
//! gyros, IEEE Std 1431; fiber-optic gyros, IEEE Std 952), next to the DTG's
//! ([`crate::dtg`]): term table with stable ids, coefficients, forward model
//! and inverse (compensation).
//!
//! Both standards write the model as `S₀·ΔN/Δt = (I + E + D)(1 + 10⁻⁶·ε_K)⁻¹`:
//! I the inertial input (the rate about the input axis), E the
//! environmental sensitivities (temperature), D the drift (bias and the
//! acceleration-sensitive drift). A rate gyro has no rotor, so its
//! acceleration sensitivity is written in the unit frame (x, y, z), not in
//! spin and output axes: the linear g-sensitivity `g_x`, `g_y`, `g_z`
//! (deg/h/g, what MEMS data sheets quote per axis) and the vibration
//! rectification `gg_xx` … `gg_yz` (deg/h/g², the g² terms data sheets
//! quote as "vibration rectification error"). As for the DTG, a g² term's
//! output over an interval is the interval mean of the product, which the
//! product of the accelerometers' interval means misses by the
//! within-interval covariance ([`RateInput::with_covariance`], from
//! [`crate::dtg::within_interval_covariance`]).

mod coefficients;
mod input;
mod model;
mod term;

pub use coefficients::RateCoefficients;
pub use input::RateInput;
pub use term::RateTerm;
