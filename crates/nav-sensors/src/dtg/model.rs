//! The DTG channel model, forward (truth → output) and inverse (compensation).
//!
//! ```text
//! output = ω_I + Σ_k c_k · r_k(ω, f, T) + 1e-6 · SFNL · |ω_I / (deg/s)| · ω_I
//! ```
//!
//! with ω = (ω_I, ω_O, ω_S) in deg/h, f = (f_I, f_O, f_S) in g resolved into
//! the channel frame, r_k the regressor of term k ([`DtgTerm::regressor`]) and
//! c_k its coefficient. Noise (angle random walk, bias instability) is added
//! by the simulator, not here.

use super::coefficients::DtgCoefficients;
use super::input::DtgInput;
use super::term::DtgTerm;

impl DtgCoefficients {
    /// The forward model: the channel output in deg/h for what it senses.
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgCoefficients, DtgInput};
    /// use nav_sensors::geometry::Ios;
    /// let c = DtgCoefficients { bias_deg_h: 1.0, g_s_deg_h_g: 2.0, gg_is_deg_h_g2: 0.1, ..Default::default() };
    /// let x = DtgInput {
    ///     rate_deg_h: Ios { i: 10.0, ..Ios::default() },
    ///     specific_force_g: Ios { i: 3.0, o: 0.0, s: 1.0 },
    ///     ..DtgInput::default()
    /// };
    /// assert!((c.output_deg_h(&x) - (10.0 + 1.0 + 2.0 + 0.3)).abs() < 1e-12);
    /// ```
    #[inline]
    pub fn output_deg_h(&self, x: &DtgInput) -> f64 {
        let c = self.to_array();
        let r = DtgTerm::regressors(x);
        let drift: f64 = c.iter().zip(&r).map(|(c, r)| c * r).sum();
        let w_i = x.rate_deg_h.i;
        w_i + drift + self.nonlinearity_deg_h(w_i)
    }

    /// The error part of the output: `output − ω_I`, deg/h.
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgCoefficients, DtgInput};
    /// let c = DtgCoefficients { bias_deg_h: -0.7, ..Default::default() };
    /// assert_eq!(c.error_deg_h(&DtgInput::default()), -0.7);
    /// ```
    pub fn error_deg_h(&self, x: &DtgInput) -> f64 {
        self.output_deg_h(x) - x.rate_deg_h.i
    }

    /// The scale-factor nonlinearity's contribution for a rate ω_I, deg/h.
    ///
    /// ```
    /// let c = nav_sensors::dtg::DtgCoefficients { scale_factor_nonlinearity_ppm_per_deg_s: 10.0, ..Default::default() };
    /// // 10 ppm per deg/s at 100 deg/s: 1000 ppm of 360000 deg/h.
    /// assert!((c.nonlinearity_deg_h(360_000.0) - 360.0).abs() < 1e-9);
    /// ```
    #[inline]
    pub fn nonlinearity_deg_h(&self, w_i_deg_h: f64) -> f64 {
        1e-6 * self.scale_factor_nonlinearity_ppm_per_deg_s * (w_i_deg_h / 3600.0).abs() * w_i_deg_h
    }

    /// The inverse model (compensation): the rate about I, deg/h, that
    /// produces `measured_deg_h`, given the other inputs in `x` (its
    /// `rate_deg_h.i` is ignored; ω_O and ω_S enter through misalignment and
    /// anisoinertia, f and T through the drift terms).
    ///
    /// The model is affine in ω_I apart from the scale-factor nonlinearity,
    /// which is solved by Newton iteration (converges in 2–3 steps for any
    /// realistic coefficient).
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgCoefficients, DtgInput};
    /// use nav_sensors::geometry::Ios;
    /// let c = DtgCoefficients { bias_deg_h: 3.0, scale_factor_ppm: 200.0, gg_oo_deg_h_g2: 0.05, ..Default::default() };
    /// let mut x = DtgInput { specific_force_g: Ios { i: 0.0, o: 2.0, s: 1.0 }, ..DtgInput::default() };
    /// x.rate_deg_h.i = 15.0;
    /// let y = c.output_deg_h(&x);
    /// assert!((c.compensate_deg_h(y, &x) - 15.0).abs() < 1e-10);
    /// ```
    pub fn compensate_deg_h(&self, measured_deg_h: f64, x: &DtgInput) -> f64 {
        // Split the output into a + b·ω_I (+ nonlinearity) by evaluating the
        // drift at ω_I = 0 and ω_I = 1 deg/h.
        let mut x0 = *x;
        x0.rate_deg_h.i = 0.0;
        let c = self.to_array();
        let drift = |x: &DtgInput| -> f64 {
            DtgTerm::regressors(x)
                .iter()
                .zip(&c)
                .map(|(r, c)| r * c)
                .sum()
        };
        let a = drift(&x0);
        let mut x1 = x0;
        x1.rate_deg_h.i = 1.0;
        let b = 1.0 + drift(&x1) - a;
        let mut w = (measured_deg_h - a) / b;
        for _ in 0..4 {
            let f = a + b * w + self.nonlinearity_deg_h(w) - measured_deg_h;
            let df = b + 2e-6 * self.scale_factor_nonlinearity_ppm_per_deg_s * (w / 3600.0).abs();
            w -= f / df;
        }
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ios;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// Coefficients at the upper end of what a navigation DTG shows, random signs.
    fn random_coefficients(rng: &mut impl Rng) -> DtgCoefficients {
        let mut c = DtgCoefficients::default();
        let scale = |t: DtgTerm| match t {
            DtgTerm::Bias => 5.0,
            DtgTerm::ScaleFactor => 500.0,
            DtgTerm::MisalignmentO | DtgTerm::MisalignmentS => 1000.0,
            DtgTerm::GI | DtgTerm::GO | DtgTerm::GS => 3.0,
            DtgTerm::Temp => 0.1,
            _ => 0.2,
        };
        for t in DtgTerm::ALL {
            c.set(t, scale(t) * rng.gen_range(-1.0..1.0));
        }
        c.scale_factor_nonlinearity_ppm_per_deg_s = 5.0 * rng.gen_range(-1.0..1.0);
        c
    }

    #[test]
    fn forward_then_inverse_returns_the_true_rate() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        for _ in 0..2000 {
            let c = random_coefficients(&mut rng);
            let x = DtgInput {
                rate_deg_h: Ios {
                    i: rng.gen_range(-3.6e5..3.6e5), // ±100 deg/s
                    o: rng.gen_range(-3.6e5..3.6e5),
                    s: rng.gen_range(-3.6e5..3.6e5),
                },
                specific_force_g: Ios {
                    i: rng.gen_range(-10.0..10.0),
                    o: rng.gen_range(-10.0..10.0),
                    s: rng.gen_range(-10.0..10.0),
                },
                temperature_delta_c: rng.gen_range(-20.0..20.0),
                rate_2n_mean_square_deg2_s2: rng.gen_range(0.0..1.0),
                specific_force_cov_g2: std::array::from_fn(|_| rng.gen_range(0.0..2.0)),
            };
            let y = c.output_deg_h(&x);
            let back = c.compensate_deg_h(y, &x);
            let tol = 1e-9 * x.rate_deg_h.i.abs().max(1.0);
            assert!(
                (back - x.rate_deg_h.i).abs() < tol,
                "{back} vs {}",
                x.rate_deg_h.i
            );
        }
    }

    #[test]
    fn forward_is_the_sum_of_documented_terms() {
        // Hand-written IEEE Std 813 form for one case, independent of the term table.
        let c = DtgCoefficients {
            bias_deg_h: 1.0,
            scale_factor_ppm: 100.0,
            misalignment_o_urad: 50.0,
            misalignment_s_urad: -20.0,
            g_i_deg_h_g: 0.5,
            g_o_deg_h_g: -0.3,
            g_s_deg_h_g: 2.0,
            gg_ii_deg_h_g2: 0.01,
            gg_oo_deg_h_g2: 0.02,
            gg_ss_deg_h_g2: 0.03,
            gg_io_deg_h_g2: 0.04,
            gg_is_deg_h_g2: 0.05,
            gg_os_deg_h_g2: 0.06,
            ai_io_deg_h_per_deg_s2: 0.1,
            ai_is_deg_h_per_deg_s2: 0.2,
            ai_os_deg_h_per_deg_s2: 0.3,
            temp_deg_h_per_c: 0.02,
            rect_2n_deg_h_per_deg_s2: 4.0,
            scale_factor_nonlinearity_ppm_per_deg_s: 0.0,
        };
        let (wi, wo, ws) = (36000.0, -7200.0, 3600.0); // 10, −2, 1 deg/s
        let (fi, fo, fs) = (0.2, -0.5, 1.0);
        let x = DtgInput {
            rate_deg_h: Ios {
                i: wi,
                o: wo,
                s: ws,
            },
            specific_force_g: Ios {
                i: fi,
                o: fo,
                s: fs,
            },
            temperature_delta_c: 5.0,
            rate_2n_mean_square_deg2_s2: 0.25,
            specific_force_cov_g2: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
        };
        let expect = wi + 1.0 + 100e-6 * wi + 50e-6 * wo - 20e-6 * ws + 0.5 * fi - 0.3 * fo
            + 2.0 * fs
            + 0.01 * fi * fi
            + 0.02 * fo * fo
            + 0.03 * fs * fs
            + 0.04 * fi * fo
            + 0.05 * fi * fs
            + 0.06 * fo * fs
            // Within-interval covariances add to the anisoelastic products.
            + (0.01 * 0.1 + 0.02 * 0.2 + 0.03 * 0.3 + 0.04 * 0.4 + 0.05 * 0.5 + 0.06 * 0.6)
            + 0.1 * 10.0 * -2.0
            + 0.2 * 10.0 * 1.0
            + 0.3 * -2.0 * 1.0
            + 0.02 * 5.0
            + 4.0 * 0.25;
        assert!((c.output_deg_h(&x) - expect).abs() < 1e-9);
    }
}
