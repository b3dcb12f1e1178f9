//! The unit file's rules, one test per refusal with its message, and the
//! built-in units against today's constants.

use super::*;
use crate::geometry::{ChannelFrame, Residue, measurement_matrix, parity_matrix};

/// A valid three-gyro, three-accelerometer file with `gyros` replacing the
/// gyro tables.
fn with_gyros(gyros: &str) -> String {
    format!(
        "name = \"test\"\n{gyros}\n\
         [[accel]]\nname = \"ax\"\ninput = [1.0, 0.0, 0.0]\n\
         [[accel]]\nname = \"ay\"\ninput = [0.0, 1.0, 0.0]\n\
         [[accel]]\nname = \"az\"\ninput = [0.0, 0.0, 1.0]\n"
    )
}

const RATE3: &str = "[[gyro]]\nname = \"a\"\nmodel = \"rate\"\ninput = [1.0, 0.0, 0.0]\n\
                     [[gyro]]\nname = \"b\"\nmodel = \"rate\"\ninput = [0.0, 1.0, 0.0]\n\
                     [[gyro]]\nname = \"c\"\nmodel = \"rate\"\ninput = [0.0, 0.0, 1.0]\n";

fn refuse(text: &str) -> String {
    Unit::from_toml(text, "u.toml").unwrap_err().to_string()
}

#[test]
fn every_builtin_parses_and_round_trips() {
    for name in Unit::BUILTIN_NAMES {
        let u = Unit::builtin(name).unwrap();
        assert_eq!(Unit::from_toml(&u.to_toml(), "copy").unwrap(), u, "{name}");
        // The embedded text is the repository's file (one source).
        let path = format!("{}/../../units/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        assert_eq!(
            std::fs::read_to_string(path).unwrap(),
            Unit::builtin_toml(name).unwrap()
        );
    }
}

#[test]
fn paper_unit_is_todays_geometry_bit_for_bit() {
    let u = Unit::paper();
    assert!(u.has_paper_geometry());
    assert_eq!(u.file_format(), super::FileFormat::Paper);
    let bits = |a: &Vector3<f64>, b: &Vector3<f64>| {
        a.iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    };
    for (g, c) in u.gyros().iter().zip(Channel::ALL) {
        let f = ChannelFrame::of(c);
        let a = g.dtg_axes().unwrap();
        assert!(bits(&a.input, &f.input), "{c} input");
        assert!(bits(&a.output, &f.other), "{c} output");
        assert!(bits(&a.spin, &f.spin), "{c} spin");
    }
    let h = measurement_matrix();
    assert!(
        u.measurement_matrix()
            .iter()
            .zip(h.iter())
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
}

/// units/paper.toml names eq. 6's residues with `Residue::coefficients`'
/// weights to the last bit (a weight the file leaves out is zero, which
/// eq. 6 gives as ±0).
#[test]
fn the_paper_files_residues_are_eq_6_bit_for_bit() {
    let u = Unit::paper();
    assert_eq!(u.residue_names(), ["K0", "K1", "K2", "K3", "K4", "K5"]);
    for (named, r) in u.named_residues().iter().zip(Residue::ALL) {
        assert_eq!(named.name, r.name());
        for (w, c) in named.weights.iter().zip(r.coefficients()) {
            assert!(
                w.to_bits() == c.to_bits() || (*w == 0.0 && c == 0.0),
                "{r}: {w} against {c}"
            );
        }
    }
    let c = u.geometry().residue_coefficients();
    assert_eq!(c.shape(), (6, 6));
    // The residues of a sample are eq. 6's to rounding (the sums run in
    // another order than eq. 5's differences).
    let mut rng = <rand_xoshiro::Xoshiro256PlusPlus as rand::SeedableRng>::seed_from_u64(33);
    for _ in 0..1000 {
        let m: [f64; 6] = std::array::from_fn(|_| rand::Rng::gen_range(&mut rng, -500.0..500.0));
        for (a, b) in u.residues(&m).iter().zip(crate::geometry::residues(&m)) {
            assert!((a - b).abs() <= 1e-15 * 500.0 * 4.0, "{a} against {b}");
        }
    }
}

/// The least-squares operator is H's pseudo-inverse for every unit: for
/// the paper's, eq. 4's constant `(HᵀH)⁻¹Hᵀ` to rounding. The largest
/// relative difference (entry by entry against the largest entry) is
/// printed for the record; it is a few ε.
#[test]
fn the_paper_least_squares_operator_is_eq_4s_to_rounding() {
    let u = Unit::paper();
    let p = u.geometry().least_squares_operator();
    let today = crate::geometry::least_squares_operator();
    let scale = today.amax();
    let worst = (0..3)
        .flat_map(|i| (0..6).map(move |j| (i, j)))
        .map(|(i, j)| (p[(i, j)] - today[(i, j)]).abs() / scale)
        .fold(0.0, f64::max);
    println!("largest relative difference of the SVD operator from eq. 4's: {worst:e}");
    assert!(worst <= 8.0 * f64::EPSILON, "{worst:e}");
}

/// One parity basis for every unit: the paper's V is the QR basis, not the
/// Gram–Schmidt rows of `geometry::parity_matrix`, and the two span the
/// same space (equal projectors VᵀV to rounding), so every statistic that
/// does not depend on the basis is unchanged (FDI: `fdi` tests).
#[test]
fn the_paper_parity_basis_spans_eq_6s_space() {
    let u = Unit::paper();
    let v = u.parity_matrix();
    let gs = parity_matrix();
    let gs = nalgebra::DMatrix::from_fn(3, 6, |i, j| gs[(i, j)]);
    let projector = v.transpose() * v;
    let today = gs.transpose() * &gs;
    assert!((projector - today).amax() < 1e-15);
}

#[test]
fn builtin_layouts_are_as_documented() {
    let tetra = Unit::builtin("tetra").unwrap();
    let hth = tetra.measurement_matrix().transpose() * tetra.measurement_matrix();
    assert!((hth - nalgebra::DMatrix::identity(3, 3) * (4.0 / 3.0)).norm() < 1e-14);
    for (k, g) in tetra.gyros().iter().enumerate() {
        // 54.7356° from z, azimuth 90°·k from x.
        assert!((g.input.z.acos().to_degrees() - 54.7356).abs() < 1e-4);
        let az = g.input.y.atan2(g.input.x).to_degrees().rem_euclid(360.0);
        assert!((az - 90.0 * k as f64).abs() < 1e-9, "{az}");
    }
    let dual = Unit::builtin("dual-triad").unwrap();
    let rot = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 10f64.to_radians());
    for k in 0..3 {
        let first = dual.gyros()[k].input;
        assert!((rot * first - dual.gyros()[k + 3].input).norm() < 1e-15);
    }
    let triad = Unit::builtin("triad").unwrap();
    assert_eq!(triad.units().rate, RateUnit::DegPerSecond);
    assert_eq!(
        triad.units().specific_force,
        SpecificForceUnit::MetresPerSecond2
    );
}

#[test]
fn geometry_of_every_unit_is_orthonormal_and_annihilates_h() {
    for name in Unit::BUILTIN_NAMES {
        let u = Unit::builtin(name).unwrap();
        let n = u.gyros().len();
        let v = u.parity_matrix();
        assert_eq!(v.shape(), (n - 3, n), "{name}");
        assert!((v * u.measurement_matrix()).norm() < 1e-12, "{name}");
        assert!((v * v.transpose() - nalgebra::DMatrix::identity(n - 3, n - 3)).norm() < 1e-12);
        let w = Vector3::new(120.0, -35.0, 7.5);
        let m: Vec<f64> = u.gyros().iter().map(|g| g.input.dot(&w)).collect();
        assert!((u.least_squares_rate(&m) - w).norm() < 1e-10, "{name}");
        assert!(u.residues(&m).iter().all(|r| r.abs() < 1e-10), "{name}");
    }
}

#[test]
fn a_zero_axis_is_refused() {
    let text = with_gyros(&RATE3.replace("[0.0, 1.0, 0.0]", "[0.0, 0.0, 0.0]"));
    assert_eq!(
        refuse(&text),
        "u.toml: gyro[1].input (b): the axis is zero; give a direction such as [0.0, 0.0, 1.0]"
    );
    let text = with_gyros(RATE3);
    let at = text.rfind("[0.0, 0.0, 1.0]").unwrap();
    let text = format!("{}[0.0, 0.0, 0.0]\n", &text[..at]);
    assert!(
        refuse(&text).starts_with("u.toml: accel[2].input (az): the axis is zero"),
        "{}",
        refuse(&text)
    );
}

#[test]
fn a_non_finite_axis_is_refused() {
    let text = with_gyros(&RATE3.replace("[1.0, 0.0, 0.0]", "[nan, 0.0, 1.0]"));
    assert_eq!(
        refuse(&text),
        "u.toml: gyro[0].input (a): the axis is not finite; give a direction such as [0.0, 0.0, 1.0]"
    );
    let text = with_gyros(&RATE3.replace("[0.0, 0.0, 1.0]", "[0.0, inf, 1.0]"));
    assert!(refuse(&text).contains("gyro[2].input (c): the axis is not finite"));
}

#[test]
fn axes_are_normalised_even_when_huge() {
    let text = with_gyros(&RATE3.replace("[1.0, 0.0, 0.0]", "[1e308, 1e308, 0.0]"));
    let u = Unit::from_toml(&text, "u.toml").unwrap();
    assert!((u.gyros()[0].input.norm() - 1.0).abs() < 1e-15);
}

fn dtg(name: &str, input: &str, spin: &str, output: &str) -> String {
    format!(
        "[[gyro]]\nname = \"{name}\"\nmodel = \"dtg\"\ninput = {input}\nspin = {spin}\noutput = {output}\n"
    )
}

#[test]
fn dtg_axes_must_be_perpendicular() {
    let good = dtg("d", "[0.0, 0.0, 1.0]", "[1.0, 0.0, 0.0]", "[0.0, 1.0, 0.0]");
    assert!(Unit::from_toml(&with_gyros(&format!("{RATE3}{good}")), "u.toml").is_ok());
    let bad = dtg(
        "d",
        "[0.0, 0.0, 1.0]",
        "[1.0, 0.0, 0.01]",
        "[0.0, 1.0, 0.0]",
    );
    let msg = refuse(&with_gyros(&format!("{RATE3}{bad}")));
    assert!(
        msg.starts_with("u.toml: gyro[3] (d): input and spin are not perpendicular (cosine 9.9995"),
        "{msg}"
    );
    assert!(msg.ends_with("tolerance 1e-6 after normalising)"), "{msg}");
    let bad = dtg("d", "[0.0, 0.0, 1.0]", "[1.0, 0.0, 0.0]", "[1.0, 1.0, 0.0]");
    assert!(
        refuse(&with_gyros(&format!("{RATE3}{bad}")))
            .contains("spin and output are not perpendicular")
    );
    // Within 1e-6 after normalising: accepted.
    let near = dtg(
        "d",
        "[0.0, 0.0, 1.0]",
        "[1.0, 0.0, 5e-7]",
        "[0.0, 1.0, 0.0]",
    );
    assert!(Unit::from_toml(&with_gyros(&format!("{RATE3}{near}")), "u.toml").is_ok());
}

#[test]
fn dtg_needs_spin_and_output_and_rate_has_none() {
    let text = with_gyros(&format!(
        "{RATE3}[[gyro]]\nname = \"d\"\nmodel = \"dtg\"\ninput = [0.0, 0.0, 1.0]\noutput = [1.0, 0.0, 0.0]\n"
    ));
    assert_eq!(
        refuse(&text),
        "u.toml: gyro[3].spin (d) is missing: a \"dtg\" gyro needs input, spin and output axes"
    );
    let text = with_gyros(&RATE3.replace(
        "name = \"c\"\nmodel = \"rate\"\ninput = [0.0, 0.0, 1.0]\n",
        "name = \"c\"\nmodel = \"rate\"\ninput = [0.0, 0.0, 1.0]\noutput = [1.0, 0.0, 0.0]\n",
    ));
    assert_eq!(
        refuse(&text),
        "u.toml: gyro[2].output (c): only a \"dtg\" gyro has spin and output axes; remove it or set model = \"dtg\""
    );
}

#[test]
fn duplicate_names_are_refused() {
    let text = with_gyros(&RATE3.replace("name = \"c\"", "name = \"a\""));
    assert_eq!(
        refuse(&text),
        "u.toml: gyro[2].name = \"a\" is already gyro[0]'s name; every column has one role"
    );
    let text = with_gyros(&RATE3.replace("name = \"c\"", "name = \"ax\""));
    // The gyro claims "ax" first; the accelerometer is the duplicate.
    assert_eq!(
        refuse(&text),
        "u.toml: accel[0].name = \"ax\" is already gyro[2]'s name; every column has one role"
    );
    let text = with_gyros(RATE3).replace(
        "name = \"test\"\n",
        "name = \"test\"\n[columns]\ntemperature = \"b\"\n",
    );
    assert_eq!(
        refuse(&text),
        "u.toml: gyro[1].name = \"b\" is already columns.temperature's name; every column has one role"
    );
    let text = with_gyros(&RATE3.replace("name = \"b\"", "name = \"t\""));
    assert!(refuse(&text).contains("is already columns.time's name"));
}

#[test]
fn empty_names_are_refused() {
    let text = with_gyros(&RATE3.replace("name = \"b\"", "name = \" \""));
    assert_eq!(
        refuse(&text),
        "u.toml: gyro[1].name is empty; give the record's column name"
    );
}

#[test]
fn too_few_or_coplanar_sensors_are_refused() {
    let two = RATE3
        .split("[[gyro]]")
        .take(3)
        .collect::<Vec<_>>()
        .join("[[gyro]]");
    assert_eq!(
        refuse(&with_gyros(&two)),
        "u.toml: [[gyro]]: 2 gyros whose input axes span 2 dimension(s); a unit needs at least three spanning all three"
    );
    // Four gyros in one plane: enough of them, not enough dimensions.
    let flat = "[[gyro]]\nname = \"a\"\nmodel = \"rate\"\ninput = [1.0, 0.0, 0.0]\n\
                [[gyro]]\nname = \"b\"\nmodel = \"rate\"\ninput = [0.0, 1.0, 0.0]\n\
                [[gyro]]\nname = \"c\"\nmodel = \"rate\"\ninput = [1.0, 1.0, 0.0]\n\
                [[gyro]]\nname = \"d\"\nmodel = \"rate\"\ninput = [1.0, -1.0, 0.0]\n";
    assert!(
        refuse(&with_gyros(flat))
            .starts_with("u.toml: [[gyro]]: 4 gyros whose input axes span 2 dimension(s)")
    );
    let no_accel = format!("name = \"x\"\n{RATE3}");
    assert_eq!(
        refuse(&no_accel),
        "u.toml: [[accel]]: 0 accelerometers whose input axes span 0 dimension(s); a unit needs at least three spanning all three"
    );
}

#[test]
fn unknown_keys_and_values_are_refused_on_one_line_with_the_place() {
    let text = with_gyros(&RATE3.replace(
        "model = \"rate\"\ninput = [0.0, 1.0",
        "model = \"rate\"\ninputs = [0.0, 1.0",
    ));
    let msg = refuse(&text);
    assert!(
        msg.starts_with("u.toml:9:1: unknown field `inputs`"),
        "{msg}"
    );
    assert!(!msg.contains('\n'));
    let text = with_gyros(&RATE3.replacen("model = \"rate\"", "model = \"fog\"", 1));
    let msg = refuse(&text);
    assert!(
        msg.starts_with("u.toml:4:9: unknown variant `fog`, expected `rate` or `dtg`"),
        "{msg}"
    );
    let text = with_gyros(RATE3).replace(
        "name = \"test\"\n",
        "name = \"test\"\n[units]\nrate = \"rpm\"\n",
    );
    assert!(
        refuse(&text).contains("unknown variant `rpm`"),
        "{}",
        refuse(&text)
    );
    let text = with_gyros(RATE3).replace("name = \"test\"\n", "");
    assert!(
        refuse(&text).contains("missing field `name`"),
        "{}",
        refuse(&text)
    );
}

#[test]
fn time_scale_must_be_positive() {
    let text = with_gyros(RATE3).replace(
        "name = \"test\"\n",
        "name = \"test\"\n[columns]\ntime_scale = 0.0\n",
    );
    assert_eq!(
        refuse(&text),
        "u.toml: columns.time_scale = 0: must be positive and finite (1 for seconds, 1e-6 for microseconds)"
    );
}

#[test]
fn resolve_takes_a_builtin_or_a_file() {
    assert!(matches!(Unit::resolve("tetra"), Ok(u) if u.gyros().len() == 4));
    let err = Unit::resolve("missing-unit.toml").unwrap_err();
    assert!(matches!(err, UnitError::Io { .. }), "{err}");
    assert!(err.to_string().starts_with("missing-unit.toml: "));
}

#[test]
fn a_stored_unit_is_validated_when_read_back() {
    let json = serde_json::to_string(&Unit::builtin("triad").unwrap()).unwrap();
    let bad = json.replace("[1.0,0.0,0.0]", "[0.0,0.0,0.0]");
    let err = serde_json::from_str::<Unit>(&bad).unwrap_err().to_string();
    assert!(
        err.contains("<stored unit>: gyro[0].input (gx): the axis is zero"),
        "{err}"
    );
}

/// A tetra with its one residue named, as `units/tetra.toml` could.
fn tetra_with(residues: &str) -> String {
    format!("{}\n{residues}", Unit::builtin_toml("tetra").unwrap())
}

#[test]
fn a_unit_may_name_its_residues() {
    let text = tetra_with(
        "[[residue]]\nname = \"sum\"\nweights = { g1 = 1.0, g2 = -1.0, g3 = 1.0, g4 = -1.0 }\n",
    );
    let u = Unit::from_toml(&text, "u.toml").unwrap();
    assert_eq!(u.residue_names(), ["sum"]);
    assert_eq!(u.residues(&[1.0, 2.0, 4.0, 8.0]), [1.0 - 2.0 + 4.0 - 8.0]);
    // The parity vector stays the orthonormal one.
    let plain = Unit::builtin("tetra").unwrap();
    assert_eq!(
        u.parity_vector(&[1.0, 2.0, 4.0, 8.0]),
        plain.residues(&[1.0, 2.0, 4.0, 8.0])
    );
    // Written back, read back.
    assert!(u.to_toml().contains("[[residue]]"));
    assert_eq!(Unit::from_toml(&u.to_toml(), "copy").unwrap(), u);
    let json = serde_json::to_string(&u).unwrap();
    assert_eq!(serde_json::from_str::<Unit>(&json).unwrap(), u);
    // A unit without residues writes no residue key (files written before
    // read the same).
    assert!(!plain.to_toml().contains("residue"));
}

#[test]
fn named_residues_are_checked() {
    let one = |w: &str| tetra_with(&format!("[[residue]]\nname = \"r\"\nweights = {{ {w} }}\n"));
    assert_eq!(
        refuse(&one("g1 = 1.0, g5 = 1.0")),
        "u.toml: residue[0].weights.g5: no such gyro (the unit's gyros: g1, g2, g3, g4)"
    );
    assert_eq!(
        refuse(&one("g1 = nan")),
        "u.toml: residue[0].weights.g1 = NaN: a weight must be finite"
    );
    assert_eq!(
        refuse(&one("g1 = 1.0, g2 = 1.0")),
        "u.toml: residue[0] (r): its weights do not cancel the rate (Σ weight·input axis = [8.16496580927726e-1, 8.16496580927726e-1, 1.1547005383792517e0] against Σ|weight| = 2; tolerance 1e-6 of it): a parity residue is a combination of the gyros that no rate enters"
    );
    assert!(refuse(&one("")).contains("its weights do not cancel the rate"));
    // Weights to 7 digits cancel within the tolerance.
    let paper = Unit::builtin_toml("paper")
        .unwrap()
        .replace("1.4142135623730951", "1.414214");
    assert!(Unit::from_toml(&paper, "p.toml").is_ok());
    // Named residues must span the parity space.
    let dual = Unit::builtin_toml("dual-triad").unwrap().to_string()
        + "[[residue]]\nname = \"z\"\nweights = { gz = 1.0, gz2 = -1.0 }\n";
    assert_eq!(
        refuse(&dual),
        "u.toml: [[residue]]: the named residues span 1 of the unit's 3 parity dimension(s); name residues spanning all of them, or none (then they are P0, P1, …)"
    );
    // A residue's name is a column of residue files: unique among them all.
    let dup = tetra_with(
        "[[residue]]\nname = \"g2\"\nweights = { g1 = 1.0, g2 = -1.0, g3 = 1.0, g4 = -1.0 }\n",
    );
    assert_eq!(
        refuse(&dup),
        "u.toml: residue[0].name = \"g2\" is already gyro[1]'s name; every column has one role"
    );
}
