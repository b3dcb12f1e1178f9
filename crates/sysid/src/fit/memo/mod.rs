//! What a fit remembers within a process: channel fits ([`channel_fits`])
//! and cross-fitted effect estimates ([`estimates`]), each keyed by
//! digests ([`digest`]) of everything it is a function of, so a fit or
//! estimate asked again with the same inputs is the one computed before,
//! bit for bit.

pub(super) mod channel_fits;
pub mod digest;
pub(super) mod estimates;
