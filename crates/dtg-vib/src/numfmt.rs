//! Numbers as the reports and the command line print them. Below both
//! `report` and `allan`, so that neither has to import the other for a
//! number format (it was `report::fmt`, which made allan ↔ report a cycle).

/// A number for a table: four significant digits, no exponent for everyday sizes.
pub fn fmt(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else if (1e-3..1e5).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

/// A number as a person writes it: at most four decimals, no trailing
/// zeros (0.19, 0.1, 2, 0.2): for settings and band edges, where "0.1000"
/// would claim a precision nobody set.
pub fn short(v: f64) -> String {
    let s = format!("{v:.4}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}
