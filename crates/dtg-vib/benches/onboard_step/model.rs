//! The step bench's models as onboard tables, built by hand with seeded
//! random numbers (a step's cost does not depend on their values): in the
//! layout written now and, with the same numbers, in the layout 5b6a72d
//! wrote (2 for the paper's six channels, 3 for any other unit), so that
//! scripts/onboard-pairs.sh can time the same model on both sides.

use dtg_onboard::{FIXED_HEADER_WORDS, FLAG_CALIBRATION, LAYOUT_2, LAYOUT_3, MAGIC, VERSION, kind};
use dtg_vib::signal::LowPass;
use nav_sensors::unit::{GyroModel, Unit};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256Plus;

/// Centres per channel, window samples.
pub const K: usize = 100;
pub const L: usize = 50;

/// One bench model.
pub struct Spec {
    /// Bench name.
    pub name: &'static str,
    /// The unit: its gyros (DTG or rate), accelerometers and geometry.
    pub unit: Unit,
    /// The network input (`dtg_onboard::input`); the statistics input has
    /// the 0.1-Hz prediction smoother.
    pub input: u32,
    /// Window signals (accelerometer codes) and each channel's (a mask of
    /// them; layout 3 and 2 take every signal for every channel).
    pub signals: Vec<u32>,
    pub masks: Vec<u32>,
    /// Every channel with the first's centres and widths (its own weights).
    pub shared: bool,
}

/// The paper's unit on `input`: six DTG channels on ax, ay, az.
pub fn paper(name: &'static str, input: u32, shared: bool) -> Spec {
    Spec {
        name,
        unit: Unit::paper(),
        input,
        signals: vec![0, 1, 2],
        masks: vec![7; 6],
        shared,
    }
}

/// The flight unit of three IMUs (tests/fixtures/onboard/three-imus.toml:
/// nine rate gyros, nine accelerometers) on the statistics input: with
/// `own_imu`, each gyro's network on its own IMU's three accelerometers;
/// else every network on the first IMU's (one list of window signals,
/// what the loop fits today and layout 3 holds).
pub fn three_imus(name: &'static str, own_imu: bool) -> Spec {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/onboard/three-imus.toml"
    );
    let unit = Unit::resolve(path).expect("the bench's unit file");
    let (signals, masks) = if own_imu {
        (
            (0..9).collect(),
            (0..9).map(|g| 7 << (3 * (g / 3))).collect(),
        )
    } else {
        (vec![0, 1, 2], vec![7; 9])
    };
    Spec {
        name,
        unit,
        input: dtg_onboard::input::STATISTICS,
        signals,
        masks,
        shared: false,
    }
}

/// The header words of `spec` in layout `version`.
fn words(spec: &Spec, version: u32, n_sections: usize) -> Vec<u32> {
    let (n, n_a) = (spec.unit.gyros().len(), spec.unit.accels().len());
    let stats = spec.input == dtg_onboard::input::STATISTICS;
    let mut w: Vec<u32> = vec![
        u32::from_le_bytes(MAGIC),
        version,
        0,
        FLAG_CALIBRATION
            | if triad(&spec.unit) {
                dtg_onboard::FLAG_ACCEL_TRIAD
            } else {
                0
            },
        0,
        n_sections as u32,
        0,
        L as u32,
        spec.signals.len() as u32,
    ];
    if version != LAYOUT_2 {
        w.extend([n as u32, n_a as u32]);
        debug_assert_eq!(w.len(), FIXED_HEADER_WORDS);
    }
    w.extend(std::iter::repeat_n(2u32, n));
    w.extend(std::iter::repeat_n(K as u32, n));
    if version != LAYOUT_2 {
        w.extend(spec.unit.gyros().iter().map(|g| match g.model {
            GyroModel::Dtg { .. } => dtg_onboard::gyro::DTG,
            GyroModel::Rate => dtg_onboard::gyro::RATE,
        }));
    }
    if version == VERSION {
        w.extend(&spec.masks);
    }
    w.extend(&spec.signals);
    for _ in 0..n {
        w.extend([kind::LINEAR_G, 0, kind::QUADRATIC_G, 0]);
    }
    w.extend([spec.input, u32::from(stats)]);
    if w.len() % 2 == 1 {
        w.push(0);
    }
    w[2] = w.len() as u32;
    w
}

/// Whether the unit's accelerometers are its x, y, z (their triad
/// calibration then applies).
fn triad(unit: &Unit) -> bool {
    unit.accels().len() == 3
}

/// The geometry and the calibration's numbers of `spec`.
fn geometry(spec: &Spec, version: u32, rng: &mut Xoshiro256Plus) -> Vec<f64> {
    let unit = &spec.unit;
    let (n, n_a) = (unit.gyros().len(), unit.accels().len());
    let mut f = vec![0.02];
    if version != LAYOUT_2 {
        f.extend([1.0, 1.0]);
    }
    for g in unit.gyros() {
        let (o, s) = g.dtg_axes().map_or(
            (nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros()),
            |a| (a.output, a.spin),
        );
        for v in [g.input, o, s] {
            f.extend([v.x, v.y, v.z]);
        }
    }
    let ls = unit.geometry().least_squares_operator();
    for i in 0..3 {
        f.extend((0..n).map(|j| ls[(i, j)]));
    }
    if version != LAYOUT_2 {
        for i in 0..3 {
            f.extend((0..n_a).map(|k| {
                let mut e = vec![0.0; n_a];
                e[k] = 1.0;
                unit.specific_force(&e)[i]
            }));
        }
    }
    for g in unit.gyros() {
        if g.dtg_axes().is_some() {
            // 18 DTG terms (temp and rect_2n zero) and the nonlinearity.
            f.extend((0..16).map(|_| rng.gen_range(-0.5..0.5)));
            f.extend([0.0, 0.0, 0.3]);
        } else {
            // Bias, scale factor (ppm), 3 g and 6 g² terms, temp.
            f.extend((0..11).map(|_| rng.gen_range(-0.5..0.5)));
            f.push(0.0);
        }
    }
    if triad(unit) {
        for _ in 0..3 {
            f.extend((0..8).map(|_| rng.gen_range(-50.0..50.0)));
        }
    }
    f
}

/// The tables of `spec` in layout `version` ([`LAYOUT_2`] for the paper's
/// unit, [`LAYOUT_3`] for another, [`VERSION`]): the same numbers in each.
pub fn tables(spec: &Spec, version: u32) -> Vec<u8> {
    assert!(
        version == VERSION
            || version == LAYOUT_3
            || spec.unit.file_format() == nav_sensors::unit::FileFormat::Paper
    );
    let stats = spec.input == dtg_onboard::input::STATISTICS;
    let smoother = LowPass::butterworth(2, 0.1, 50.0).expect("a low-pass");
    let lp = LowPass::butterworth(4, 5.0, 50.0).expect("a low-pass");
    let mut rng = Xoshiro256Plus::seed_from_u64(13);
    let words = words(spec, version, lp.sections().len());
    let mut f = geometry(spec, version, &mut rng);
    for (s, z) in lp.sections().iter().zip(lp.steady_state()) {
        f.extend([s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], z[0], z[1]]);
    }
    if stats {
        for (s, z) in smoother.sections().iter().zip(smoother.steady_state()) {
            f.extend([s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], z[0], z[1]]);
        }
    }
    networks(spec, &mut rng, &mut f);
    let mut bytes = Vec::new();
    for w in &words {
        bytes.extend(w.to_le_bytes());
    }
    for v in &f {
        bytes.extend(v.to_le_bytes());
    }
    bytes
}

/// Each channel's bias, two effects (g along its input axis, g² along its
/// input and spin axes, or input twice), widths, weights and centres.
fn networks(spec: &Spec, rng: &mut Xoshiro256Plus, f: &mut Vec<f64>) {
    let stats = spec.input == dtg_onboard::input::STATISTICS;
    let mut first: Option<(Vec<f64>, Vec<f64>)> = None;
    for (g, mask) in spec.unit.gyros().iter().zip(&spec.masks) {
        let i = g.input;
        let s = g.dtg_axes().map_or(i, |a| a.spin);
        f.push(rng.gen_range(-5.0..5.0)); // bias
        f.extend([0.8, -0.1]); // the two effects' coefficients
        f.extend([i.x, i.y, i.z, i.x, i.y, i.z, s.x, s.y, s.z]);
        let widths: Vec<f64> = (0..K).map(|_| rng.gen_range(2.0..6.0)).collect();
        let weights: Vec<f64> = (0..K).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let mut centres = Vec::new();
        for _ in 0..K {
            for (sig, code) in spec.signals.iter().enumerate() {
                if mask & (1 << sig) == 0 {
                    continue;
                }
                let one_g = if code % 3 == 2 { 1.0 } else { 0.0 };
                if stats {
                    // Current sample, window mean, window rms.
                    centres.extend([
                        one_g + rng.gen_range(-0.5..0.5),
                        one_g + rng.gen_range(-0.05..0.05),
                        rng.gen_range(0.0..0.3),
                    ]);
                } else {
                    centres.extend((0..L).map(|_| one_g + rng.gen_range(-0.5..0.5)));
                }
            }
        }
        let (widths, centres) = match (&first, spec.shared) {
            (Some((w, c)), true) => (w.clone(), c.clone()),
            _ => (widths, centres),
        };
        first.get_or_insert((widths.clone(), centres.clone()));
        f.extend(widths);
        f.extend(weights);
        f.extend(centres);
    }
}
