//! The coefficient table of one DTG channel, with units in the field names.

use serde::{Deserialize, Serialize};

use super::term::DtgTerm;

/// The deterministic error coefficients of one DTG channel (IEEE Std 813
/// terms), each named with its unit. Missing fields in a file read as zero.
///
/// The same table serves as truth (what the simulator uses) and as ground
/// calibration (what the user compensates with; there `temp_deg_h_per_c` and
/// `rect_2n_deg_h_per_deg_s2` are always zero because ground calibration
/// does not cover them).
///
/// ```
/// use nav_sensors::dtg::{DtgCoefficients, DtgTerm};
/// let mut c = DtgCoefficients { bias_deg_h: 2.0, ..Default::default() };
/// c.set(DtgTerm::GgIS, 0.05);
/// assert_eq!(c.get(DtgTerm::GgIS), 0.05);
/// assert_eq!(c.gg_is_deg_h_g2, 0.05);
/// assert_eq!(c.get(DtgTerm::Bias), 2.0);
/// let back: DtgCoefficients = toml::from_str("bias_deg_h = 2.0\ngg_is_deg_h_g2 = 0.05\n").unwrap();
/// assert_eq!(back, c);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DtgCoefficients {
    /// `bias`, deg/h.
    pub bias_deg_h: f64,
    /// `scale_factor`, ppm.
    pub scale_factor_ppm: f64,
    /// Scale-factor nonlinearity: the scale-factor error grows by this many
    /// ppm per deg/s of |ω_I| (part of the `scale_factor` family, no own id).
    pub scale_factor_nonlinearity_ppm_per_deg_s: f64,
    /// `misalignment_O`, µrad (input axis rotated about S toward O).
    pub misalignment_o_urad: f64,
    /// `misalignment_S`, µrad (input axis rotated about O toward S).
    pub misalignment_s_urad: f64,
    /// `g_I`, deg/h/g.
    pub g_i_deg_h_g: f64,
    /// `g_O`, deg/h/g.
    pub g_o_deg_h_g: f64,
    /// `g_S`, deg/h/g.
    pub g_s_deg_h_g: f64,
    /// `gg_II`, deg/h/g².
    pub gg_ii_deg_h_g2: f64,
    /// `gg_OO`, deg/h/g².
    pub gg_oo_deg_h_g2: f64,
    /// `gg_SS`, deg/h/g².
    pub gg_ss_deg_h_g2: f64,
    /// `gg_IO`, deg/h/g².
    pub gg_io_deg_h_g2: f64,
    /// `gg_IS`, deg/h/g².
    pub gg_is_deg_h_g2: f64,
    /// `gg_OS`, deg/h/g².
    pub gg_os_deg_h_g2: f64,
    /// `ai_IO`, deg/h/(deg/s)².
    pub ai_io_deg_h_per_deg_s2: f64,
    /// `ai_IS`, deg/h/(deg/s)².
    pub ai_is_deg_h_per_deg_s2: f64,
    /// `ai_OS`, deg/h/(deg/s)².
    pub ai_os_deg_h_per_deg_s2: f64,
    /// `temp`, deg/h/°C about the scenario's reference temperature.
    pub temp_deg_h_per_c: f64,
    /// `rect_2n`, deg/h per (deg/s)² of mean-square angular rate about I in
    /// the band around twice the spin frequency.
    pub rect_2n_deg_h_per_deg_s2: f64,
}

impl DtgCoefficients {
    /// The coefficient of one term, in [`DtgTerm::unit`].
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgCoefficients, DtgTerm};
    /// let c = DtgCoefficients { g_o_deg_h_g: -0.4, ..Default::default() };
    /// assert_eq!(c.get(DtgTerm::GO), -0.4);
    /// ```
    pub fn get(&self, term: DtgTerm) -> f64 {
        *self.field(term)
    }

    /// Sets the coefficient of one term.
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgCoefficients, DtgTerm};
    /// let mut c = DtgCoefficients::default();
    /// c.set(DtgTerm::AiIS, 0.02);
    /// assert_eq!(c.ai_is_deg_h_per_deg_s2, 0.02);
    /// ```
    pub fn set(&mut self, term: DtgTerm, value: f64) {
        *self.field_mut(term) = value;
    }

    /// All eighteen coefficients in [`DtgTerm::ALL`] order.
    ///
    /// ```
    /// let c = nav_sensors::dtg::DtgCoefficients { g_s_deg_h_g: 1.5, ..Default::default() };
    /// assert_eq!(c.to_array()[nav_sensors::dtg::DtgTerm::GS.index()], 1.5);
    /// ```
    pub fn to_array(&self) -> [f64; 18] {
        DtgTerm::ALL.map(|t| self.get(t))
    }

    /// A copy with the given terms set to zero.
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgCoefficients, DtgTerm};
    /// let c = DtgCoefficients { temp_deg_h_per_c: 0.1, bias_deg_h: 1.0, ..Default::default() };
    /// let z = c.without(&[DtgTerm::Temp]);
    /// assert_eq!((z.temp_deg_h_per_c, z.bias_deg_h), (0.0, 1.0));
    /// ```
    pub fn without(&self, terms: &[DtgTerm]) -> Self {
        let mut c = *self;
        for &t in terms {
            c.set(t, 0.0);
        }
        c
    }

    fn field(&self, term: DtgTerm) -> &f64 {
        match term {
            DtgTerm::Bias => &self.bias_deg_h,
            DtgTerm::ScaleFactor => &self.scale_factor_ppm,
            DtgTerm::MisalignmentO => &self.misalignment_o_urad,
            DtgTerm::MisalignmentS => &self.misalignment_s_urad,
            DtgTerm::GI => &self.g_i_deg_h_g,
            DtgTerm::GO => &self.g_o_deg_h_g,
            DtgTerm::GS => &self.g_s_deg_h_g,
            DtgTerm::GgII => &self.gg_ii_deg_h_g2,
            DtgTerm::GgOO => &self.gg_oo_deg_h_g2,
            DtgTerm::GgSS => &self.gg_ss_deg_h_g2,
            DtgTerm::GgIO => &self.gg_io_deg_h_g2,
            DtgTerm::GgIS => &self.gg_is_deg_h_g2,
            DtgTerm::GgOS => &self.gg_os_deg_h_g2,
            DtgTerm::AiIO => &self.ai_io_deg_h_per_deg_s2,
            DtgTerm::AiIS => &self.ai_is_deg_h_per_deg_s2,
            DtgTerm::AiOS => &self.ai_os_deg_h_per_deg_s2,
            DtgTerm::Temp => &self.temp_deg_h_per_c,
            DtgTerm::Rect2N => &self.rect_2n_deg_h_per_deg_s2,
        }
    }

    fn field_mut(&mut self, term: DtgTerm) -> &mut f64 {
        match term {
            DtgTerm::Bias => &mut self.bias_deg_h,
            DtgTerm::ScaleFactor => &mut self.scale_factor_ppm,
            DtgTerm::MisalignmentO => &mut self.misalignment_o_urad,
            DtgTerm::MisalignmentS => &mut self.misalignment_s_urad,
            DtgTerm::GI => &mut self.g_i_deg_h_g,
            DtgTerm::GO => &mut self.g_o_deg_h_g,
            DtgTerm::GS => &mut self.g_s_deg_h_g,
            DtgTerm::GgII => &mut self.gg_ii_deg_h_g2,
            DtgTerm::GgOO => &mut self.gg_oo_deg_h_g2,
            DtgTerm::GgSS => &mut self.gg_ss_deg_h_g2,
            DtgTerm::GgIO => &mut self.gg_io_deg_h_g2,
            DtgTerm::GgIS => &mut self.gg_is_deg_h_g2,
            DtgTerm::GgOS => &mut self.gg_os_deg_h_g2,
            DtgTerm::AiIO => &mut self.ai_io_deg_h_per_deg_s2,
            DtgTerm::AiIS => &mut self.ai_is_deg_h_per_deg_s2,
            DtgTerm::AiOS => &mut self.ai_os_deg_h_per_deg_s2,
            DtgTerm::Temp => &mut self.temp_deg_h_per_c,
            DtgTerm::Rect2N => &mut self.rect_2n_deg_h_per_deg_s2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn get_and_set_address_distinct_fields() {
        let mut c = DtgCoefficients::default();
        for (k, t) in DtgTerm::ALL.into_iter().enumerate() {
            c.set(t, k as f64 + 1.0);
        }
        for (k, t) in DtgTerm::ALL.into_iter().enumerate() {
            assert_eq!(c.get(t), k as f64 + 1.0, "{t}");
        }
        let json = serde_json::to_string(&c).unwrap();
        assert_eq!(serde_json::from_str::<DtgCoefficients>(&json).unwrap(), c);
    }

    #[test]
    fn unknown_fields_are_rejected() {
        assert!(toml::from_str::<DtgCoefficients>("bias = 1.0").is_err());
    }
}
