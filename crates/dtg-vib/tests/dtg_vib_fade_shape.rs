//! Issue 35 §3: the fade sees novelty, not only level. A model fitted on
//! the campaign's z run (NAVMAT random vibration, 20–2000 Hz) is checked on
//! the same run with its vibration's power moved to 2–12 Hz at the same
//! level (0.33 g rms on az at 0 dB, as the z run's): every window's mean
//! and level lie inside what the model saw, only the spectrum differs. The
//! network maps az's level to the drift the shaker's spectrum gave at it,
//! so as fitted it adds 3–14× the record's own variation; faded, the
//! spread after must stay ≤ 1.02× the rms before on every channel (the
//! issue's bound). Fixed seeds (the z run's, 7 for the other); a fit with
//! the default flags takes seconds.

use serde_json::Value;
use std::path::{Path, PathBuf};

mod workspace_cli;
use workspace_cli::{bin, ok};

/// The z run's scenario with its random drive's PSD moved to 2–12 Hz
/// (0.015 g²/Hz: the same 0.33 g rms on az at 0 dB) and seed 7.
fn low_frequency_scenario(dir: &Path) -> PathBuf {
    let z = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/z-axis.toml"),
    )
    .unwrap();
    let mut replaced = 0;
    let text: String = z
        .lines()
        .map(|l| {
            if l.starts_with("psd = ") {
                replaced += 1;
                "psd = [[2.0, 0.015], [12.0, 0.015]]".to_string()
            } else if l.starts_with("seed = ") {
                replaced += 1;
                "seed = 7".to_string()
            } else if l.starts_with("name = ") {
                replaced += 1;
                "name = \"z-axis-2-12-hz\"".to_string()
            } else {
                l.to_string()
            }
        })
        .map(|l| l + "\n")
        .collect();
    assert_eq!(replaced, 3, "the z run's scenario changed: adapt this test");
    let path = dir.join("z-axis-2-12-hz.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

#[test]
fn a_z_model_fades_on_a_vibration_of_another_spectrum_at_the_same_level() {
    let d = std::env::temp_dir().join(format!("dtg-vib-fade-shape-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    ok(bin()
        .args(["simulate", "--builtin", "z-axis", "--out"])
        .arg(d.join("z")));
    ok(bin()
        .arg("simulate")
        .arg("--scenario")
        .arg(low_frequency_scenario(&d))
        .arg("--out")
        .arg(d.join("lf")));
    let model = d.join("z.json");
    ok(bin()
        .arg("fit")
        .arg("--data")
        .arg(d.join("z/record.csv"))
        .arg("--calib")
        .arg(d.join("z/calibration.json"))
        .arg("--out")
        .arg(&model));
    let check = |run: &str| -> Value {
        let out = ok(bin()
            .args(["check", "--json", "--model"])
            .arg(&model)
            .arg("--data")
            .arg(d.join(run).join("record.csv")));
        serde_json::from_str(&out).unwrap()
    };
    let c = check("lf");
    // Mean and level alone: 93% of the windows inside (main at b56274f:
    // outside_range_fraction 0.068, weight 0.998, spread after / rms before
    // 3.69–14.4 faded); with the shape 95% outside.
    let worst_unfaded = c["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|ch| f(ch, "spread_after_unfaded") / f(ch, "rms_before"))
        .fold(0.0, f64::max);
    assert!(
        worst_unfaded > 2.0,
        "the scenario must be one where the network extrapolates: {worst_unfaded}"
    );
    assert!(f(&c, "outside_range_fraction") > 0.9, "{c}");
    let lacks = c["lacks"].to_string();
    assert!(lacks.contains("another spectrum"), "{lacks}");
    for ch in c["channels"].as_array().unwrap() {
        let ratio = f(ch, "spread_after") / f(ch, "rms_before");
        assert!(
            ratio <= 1.02,
            "{}: spread after / rms before {ratio}",
            ch["channel"]
        );
    }
    // Its own record stays compensated: weight 1, the fitted model.
    let own = check("z");
    assert_eq!(f(&own, "fade_weight_mean"), 1.0);
    for ch in own["channels"].as_array().unwrap() {
        assert_eq!(ch["spread_after"], ch["spread_after_unfaded"]);
        assert!(f(ch, "spread_after") / f(ch, "rms_before") < 0.4, "{ch}");
    }
    std::fs::remove_dir_all(&d).ok();
}
