//! What writes the application's reports: the page of a model of any unit
//! on its records ([`compensation`]: the paper's figures among its
//! sections), the page of a diagnosis and that of an Allan analysis, drawn
//! with the [`plot`] crate. Each page is assembled from one writer per
//! section, in a file of its own.

mod allan;
mod common;
mod compensation;
mod diagnosis;
mod provenance;

pub use allan::write_allan_report;
pub use compensation::{
    DiagnosisExtra, Evaluated, FdiShown, NoiseFloor, PageNumbers, Parity, ReportExtras, ResidueRms,
    build_page, parity_on_samples,
};
pub use diagnosis::{ChannelWording, write_diagnosis_report, write_diagnosis_report_of};
pub use provenance::Provenance;

#[cfg(test)]
mod tests {
    #[test]
    fn short_drops_trailing_zeros() {
        assert_eq!(super::common::short(0.19), "0.19");
        assert_eq!(super::common::short(0.1), "0.1");
        assert_eq!(super::common::short(2.0), "2");
        assert_eq!(super::common::short(20.0), "20");
    }

    #[test]
    fn fmt_keeps_four_significant_digits() {
        assert_eq!(super::common::fmt(1.23456), "1.235");
        assert_eq!(super::common::fmt(123.456), "123.5");
        assert_eq!(super::common::fmt(0.0123456), "0.01235");
        assert_eq!(super::common::fmt(1.5e-7), "1.500e-7");
        assert_eq!(super::common::fmt(0.0), "0");
    }
}
