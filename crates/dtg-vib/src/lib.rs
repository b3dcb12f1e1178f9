//! DTG vibration-error identification and compensation with RBF networks.

pub mod report;
