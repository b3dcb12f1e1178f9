//! The ground calibration a user would have: the truth plus seeded
//! calibration errors, with the hidden effects and the terms ground
//! calibration never covers set to zero.

use std::collections::BTreeMap;

use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

use super::scenario::Scenario;
use crate::accel::AccelCoefficients;
use crate::calibration::Calibration;
use crate::dtg::DtgTerm;
use crate::geometry::{Axis, Channel};

/// Draws the calibration for a scenario. Two normal draws are taken for
/// every coefficient whether used or not, so the errors of one term do not
/// depend on the others' settings.
pub(crate) fn ground_calibration(s: &Scenario, rng: &mut impl Rng) -> Calibration {
    let e = &s.calibration_error;
    let mut normal = || -> (f64, f64) { (StandardNormal.sample(rng), StandardNormal.sample(rng)) };
    let mut gyros = BTreeMap::new();
    for c in Channel::ALL {
        let truth = s.gyro(c);
        let mut cal = truth;
        for t in DtgTerm::ALL {
            let (n1, n2) = normal();
            let v = if t.is_calibrated() {
                truth.get(t) * (1.0 + e.relative * n1) + e.absolute_for(t) * n2
            } else {
                0.0
            };
            cal.set(t, v);
        }
        let (n1, _) = normal();
        cal.scale_factor_nonlinearity_ppm_per_deg_s *= 1.0 + e.relative * n1;
        for h in s.hidden.iter().filter(|h| h.channel == c) {
            cal.set(h.term, 0.0);
        }
        gyros.insert(c, cal);
    }
    let mut accels = BTreeMap::new();
    for a in Axis::ALL {
        let t = s.accel(a);
        let mut draw = |value: f64, absolute: f64| {
            let (n1, n2) = normal();
            value * (1.0 + e.relative * n1) + absolute * n2
        };
        let cal = AccelCoefficients {
            bias_ug: draw(t.bias_ug, e.accel_bias_ug),
            scale_factor_ppm: draw(t.scale_factor_ppm, e.accel_scale_factor_ppm),
            k2_ug_per_g2: draw(t.k2_ug_per_g2, e.accel_k2_ug_per_g2),
            k3_ug_per_g3: draw(t.k3_ug_per_g3, 0.0),
            misalignment_o_urad: draw(t.misalignment_o_urad, e.accel_misalignment_urad),
            misalignment_p_urad: draw(t.misalignment_p_urad, e.accel_misalignment_urad),
            kip_ug_per_g2: draw(t.kip_ug_per_g2, 0.0),
            kio_ug_per_g2: draw(t.kio_ug_per_g2, 0.0),
        };
        accels.insert(a, cal);
    }
    Calibration {
        format_version: Calibration::FORMAT_VERSION,
        gyros,
        accels,
    }
}
