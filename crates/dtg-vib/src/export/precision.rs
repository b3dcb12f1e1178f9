//! The arithmetic and table precision of the exported C.

/// Arithmetic and table precision of the exported C.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// `double` tables and arithmetic: equal to the desktop tool.
    F64,
    /// `float` tables and arithmetic: half the table size; the difference
    /// from the desktop tool is measured in docs/dtg-vib.md.
    F32,
}

impl std::str::FromStr for Precision {
    type Err = crate::error::DtgVibError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "f64" => Ok(Precision::F64),
            "f32" => Ok(Precision::F32),
            other => Err(sysid::SysidError::InvalidOption {
                name: "precision",
                value: other.to_string(),
                reason: "use f64 or f32",
            }
            .into()),
        }
    }
}
