//! A model of any unit, the paper's included, as equations with units,
//! for review (`dtg-vib export --lang text`).

use crate::unit_sensor::UnitModel;
use nav_sensors::calibration::GyroCoefficients;
use nav_sensors::dtg::DtgTerm;
use nav_sensors::rate::RateTerm;
use std::fmt::Write;
use sysid::operating::OperatingPoints;

/// The model written out: the unit, pre-processing, calibration, filter
/// coefficients, and per channel the effect terms with their coefficients
/// and the RBF sum with its centres, width and weights. Works on
/// zero-phase and causal models.
pub fn equations(model: &UnitModel) -> String {
    let m = model.inner();
    equations_with(
        &format!(
            "# dtg-vib compensation model of the unit '{}'",
            model.unit().name()
        ),
        m.dt_s(),
        (m.preprocess(), &model.unit().gyro_names()),
        &|w| calibration_text(w, model),
        &|w| {
            for c in m.channels() {
                channel_text(w, c);
            }
        },
        m.operating_points(),
    )
}

/// The equations of any model: its title line, output period and
/// pre-processing (of channels `names`), what `calibration` and `channels`
/// write, and the training range of `points`.
fn equations_with(
    title: &str,
    dt_s: f64,
    (pre, names): (&sysid::Preprocess, &[&str]),
    calibration: &dyn Fn(&mut String),
    channels: &dyn Fn(&mut String),
    points: Option<&OperatingPoints>,
) -> String {
    let mut s = String::new();
    let w = &mut s;
    let _ = writeln!(w, "{title}");
    let _ = writeln!(w, "output period: {} s ({} Hz)", dt_s, 1.0 / dt_s);
    let _ = writeln!(
        w,
        "mode: {}",
        if pre.causal {
            "causal (past and present samples only; runs on-line)"
        } else {
            "zero-phase (forward-backward low-pass; needs the whole record)"
        }
    );
    calibration(w);
    let _ = writeln!(
        w,
        "\n## Low-pass of the effect terms (and of the fit targets)"
    );
    filter_text(w, &pre.filter, pre.causal, dt_s);
    let _ = writeln!(w, "\n## Low-pass of the windowed signals");
    filter_text(w, &pre.input_filter, pre.causal, dt_s);
    // One window for every channel, or one per group of channels that read
    // their own signals (each gyro its own IMU's accelerometers).
    let groups = pre.window.groups(names.len().max(1));
    for (members, win) in &groups {
        let of = match groups.len() {
            1 => String::new(),
            _ => format!(
                " of {}",
                members
                    .iter()
                    .map(|&k| names[k])
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        window_text(w, pre.input, win, &of);
    }
    if let Some(sm) = pre.smoother {
        let _ = writeln!(
            w,
            "\n## Prediction smoother (the network part Σ wₖ·exp(…) only)"
        );
        let spec = sysid::FilterSpec {
            order: sysid::smoother::SMOOTHER_ORDER,
            cutoff_hz: sm.cutoff_hz,
        };
        filter_text(w, &Some(spec), pre.causal, dt_s);
    }
    channels(w);
    range_text(w, points);
    s
}

/// The window `win` (of the channels `of` names) as the network reads it.
fn window_text(w: &mut String, input: sysid::ModelInput, win: &sysid::WindowSpec, of: &str) {
    match input {
        sysid::ModelInput::Raw => {
            let _ = writeln!(
                w,
                "\n## Window{of}\nx = the last {} samples (oldest first) of {}, g (or the column's unit); {} inputs",
                win.length(),
                win.signals().join(", then "),
                win.dim()
            );
        }
        sysid::ModelInput::Statistics => {
            let _ = writeln!(
                w,
                "\n## Window{of}\nx = for each of {} in turn: the current sample, the mean and the rms about the mean of its last {} samples (running sums s1 += v − v_old, s2 += v² − v_old²; mean = s1/L, rms = √max(s2/L − mean², 0)), g (or the column's unit); {} inputs",
                win.signals().join(", "),
                win.length(),
                input.dim(win)
            );
        }
    }
}

/// The training range and the fade of the network part beyond it
/// (sysid::operating::fade); nothing for a model without one.
fn range_text(w: &mut String, points: Option<&OperatingPoints>) {
    let Some(r) = points.and_then(|o| o.range.as_ref()) else {
        return;
    };
    let _ = writeln!(
        w,
        "\n## Training range and fade\nper axis, over the last {} samples (calibrated, not filtered): the window mean and level (rms about the mean) the training windows spanned, g",
        r.window
    );
    for (k, sig) in r.signals.iter().enumerate() {
        let _ = writeln!(
            w,
            "  {sig}: mean {:e} to {:e}, level {:e} to {:e}",
            r.mean_min[k], r.mean_max[k], r.level_min[k], r.level_max[k]
        );
    }
    if let Some(s) = &r.shape {
        let _ = writeln!(
            w,
            "per axis, the vibration shape ρ = √(Σ(vᵢ − vᵢ₋₁)² / (2(L − 1)) / level²) the training windows above {} g of level spanned; its excess beyond them counts in d over {}, times min(1, max(0, level / {} g − 1))",
            r.scale, s.scale, r.scale
        );
        for (k, sig) in r.signals.iter().enumerate() {
            let _ = writeln!(w, "  {sig}: shape {:e} to {:e}", s.min[k], s.max[k]);
        }
        let _ = writeln!(
            w,
            "toward a lower w₀ the one-pole's time constant is {} s (0: at once)",
            r.fade
                .fall_time_constant_s
                .unwrap_or(r.fade.time_constant_s)
        );
    }
    let _ = writeln!(
        w,
        "d = √Σ(excess beyond each interval / {} g)²; w₀ = 1 for d ≤ {:e}, smoothstep to 0 at d = {:e}; w = one-pole of w₀ (gain α), τ = {} s\nheld h_c from the network at rest {}; at w = 1 error_c uses rbf_c and h_c ← h_c + α·(rbf_c − h_c), below it h_c stays and error_c uses h_c + w·(rbf_c − h_c) in place of the RBF sum",
        r.scale,
        r.tolerance,
        r.tolerance + r.fade.width,
        r.fade.time_constant_s,
        r.network_mean
            .iter()
            .map(|m| format!("{m:e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
}

/// The unit's columns, units and gyros, and its ground calibration as the
/// inverse models the preparation applies.
fn calibration_text(w: &mut String, model: &UnitModel) {
    let unit = model.unit();
    let _ = writeln!(
        w,
        "\n## Unit\nlog columns: time {} (s × {}); gyros {} ({}, times {} to deg/h); accelerometers {} ({}, times {} to g)",
        unit.columns().time,
        unit.columns().time_scale,
        unit.gyro_names().join(", "),
        unit.units().rate,
        unit.units().rate.to_deg_h(),
        unit.accel_names().join(", "),
        unit.units().specific_force,
        unit.units().specific_force.to_g(),
    );
    for g in unit.gyros() {
        let axes = match g.dtg_axes() {
            Some(a) => format!(
                "dtg, I = {:?}, O = {:?}, S = {:?}",
                a.input.as_slice(),
                a.output.as_slice(),
                a.spin.as_slice()
            ),
            None => format!("rate, input axis {:?}", g.input.as_slice()),
        };
        let _ = writeln!(w, "  {}: {axes}", g.name);
    }
    let _ = writeln!(w, "\n## Ground calibration");
    let Some(cal) = model.inner().sensor().calibration.as_ref() else {
        let _ = writeln!(w, "none: the raw outputs are used as they are");
        return;
    };
    let _ = writeln!(
        w,
        "accelerometers, when they are the unit's x, y, z axes (else as given): static inverse of output/g = (1 + K1·1e-6)(K0 + a_i + K2·a_i² + K3·a_i³ + δo·a_p − δp·a_o + Kip·a_i·a_p + Kio·a_i·a_o), each coefficient ·1e-6; the specific force is their least-squares resolution in the unit frame"
    );
    for (name, c) in &cal.accels {
        accel_text(w, name, c);
    }
    let _ = writeln!(
        w,
        "gyros (a rate gyro: (output − Σ coefficient·term at zero rate)/(1 + scale factor·1e-6); a DTG: inverse of output = ω_I + Σ coefficient·term, Newton on the scale-factor nonlinearity, the rate from the least-squares rate of all gyros, two passes; g² terms with the {} within-interval covariance):",
        if model.inner().preprocess().causal {
            "centred (samples n − 3 … n + 3, so 3 periods late on line)"
        } else {
            "centred (samples n − 3 … n + 3)"
        }
    );
    for (name, c) in &cal.gyros {
        let terms: Vec<String> = match c {
            GyroCoefficients::Rate(r) => RateTerm::ALL
                .iter()
                .zip(r.to_array())
                .filter(|(_, v)| *v != 0.0)
                .map(|(t, v)| format!("{} = {v} {}", t.id(), t.unit()))
                .collect(),
            GyroCoefficients::Dtg(d) => DtgTerm::ALL
                .iter()
                .zip(d.to_array())
                .filter(|(_, v)| *v != 0.0)
                .map(|(t, v)| format!("{} = {v} {}", t.id(), t.unit()))
                .chain(std::iter::once(format!(
                    "nonlinearity = {} ppm/(deg/s)",
                    d.scale_factor_nonlinearity_ppm_per_deg_s
                )))
                .collect(),
        };
        let _ = writeln!(w, "  {name} ({}): {}", c.model(), terms.join(", "));
    }
}

/// One accelerometer's calibration, with units.
fn accel_text(w: &mut String, name: &str, c: &nav_sensors::accel::AccelCoefficients) {
    let [k0, k1, k2, k3, d_o, d_p, kip, kio] = crate::onboard::accel_floats(c);
    let _ = writeln!(
        w,
        "  {name}: K0 = {k0} µg, K1 = {k1} ppm, K2 = {k2} µg/g², K3 = {k3} µg/g³, δo = {d_o} µrad, δp = {d_p} µrad, Kip = {kip} µg/g², Kio = {kio} µg/g²"
    );
}

/// One low-pass as its sections' difference equations.
fn filter_text(w: &mut String, f: &Option<sysid::FilterSpec>, causal: bool, dt_s: f64) {
    match f {
        None => {
            let _ = writeln!(w, "none");
        }
        Some(f) => {
            let _ = writeln!(
                w,
                "Butterworth, order {}, −3 dB at {} Hz, {}",
                f.order,
                f.cutoff_hz,
                if causal {
                    "one forward pass started in the steady state of the first sample"
                } else {
                    "forward and backward (zero phase)"
                }
            );
            if let Ok(lp) = crate::signal::LowPass::butterworth(f.order, f.cutoff_hz, 1.0 / dt_s) {
                let _ = writeln!(
                    w,
                    "  each section: y[n] = b0·x[n] + b1·x[n−1] + b2·x[n−2] − a1·y[n−1] − a2·y[n−2], in order"
                );
                for (i, sec) in lp.sections().iter().enumerate() {
                    let _ = writeln!(
                        w,
                        "  section {i}: b0 = {:e}, b1 = {:e}, b2 = {:e}, a1 = {:e}, a2 = {:e}",
                        sec.b[0], sec.b[1], sec.b[2], sec.a[0], sec.a[1]
                    );
                }
            }
        }
    }
}

/// One channel's equation: its effects with their coefficients and the
/// RBF sum with every centre, width and weight.
fn channel_text<C: std::fmt::Display + Clone, E: sysid::Effect>(
    w: &mut String,
    c: &sysid::ChannelModel<C, E>,
) {
    let ch = c.channel();
    let rbf = c.rbf();
    let _ = writeln!(w, "\n## Channel {ch}");
    let mut eq = format!("error_{ch} [deg/h] = {:e}", c.bias());
    for (e, th) in c.effects().iter().zip(c.effect_coefficients()) {
        let _ = write!(eq, " + ({th:e} {})·LP[{}]", e.unit(), e.id());
    }
    let _ = write!(
        eq,
        " + Σ_k w_k·exp(−‖x − c_k‖²/β_k²), {} centres",
        rbf.n_centres()
    );
    let _ = writeln!(w, "{eq}");
    let _ = writeln!(w, "compensated_{ch} [deg/h] = calibrated_{ch} − error_{ch}");
    for e in c.effects() {
        let _ = writeln!(w, "  {}: {}", e.id(), e.description());
    }
    let centres = rbf.centres();
    for k in 0..rbf.n_centres() {
        let row: Vec<String> = (0..centres.ncols())
            .map(|d| format!("{:e}", centres[(k, d)]))
            .collect();
        let _ = writeln!(
            w,
            "  k = {k}: w = {:e} deg/h, β = {:e} g, c = [{}] g",
            rbf.weights()[(k, 0)],
            rbf.widths().get(k),
            row.join(", ")
        );
    }
}
