//! Prints the error budget of a scenario: per channel the noise floor and
//! what the vibration leaves after compensation, per residue the rms before
//! and after ground-calibration compensation, and the hidden effects.
//!
//! ```sh
//! cargo run --release -p nav-sensors --example budget -- [paper_z_random|triaxial_clean|triaxial_hidden|FILE.toml] [OUT_DIR]
//! ```

use std::time::Instant;

use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, UnitSimulation, UnitTruth, simulate_unit};
use nav_sensors::unit::Unit;

use stats::{rms, std_dev};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "paper_z_random".into());
    let scenario = match Scenario::builtin(&arg) {
        Some(s) => s,
        None => Scenario::load(&arg)?,
    };
    let start = Instant::now();
    let paper = Unit::paper();
    let sim = simulate_unit(&paper, &scenario)?;
    println!(
        "{}: simulated {} s in {:.3} s",
        scenario.name,
        scenario.duration_s,
        start.elapsed().as_secs_f64()
    );
    if let Some(dir) = std::env::args().nth(2) {
        sim.write_dir(&dir)?;
        println!("wrote {dir}");
    }
    print_channels(&sim.truth);
    let compensated = sim.calibration.compensate(&paper, &sim.record)?;
    print_residues(&sim, &compensated);
    let az = sim.record.accel_named("az").expect("the paper's az");
    for w in [50usize, 250] {
        window_proxy(&sim, &variance_feature(az, w), w);
    }
    for w in [50usize, 250] {
        blocked_split_proxy(&paper, &compensated, &variance_feature(az, w), w);
    }
    for h in &sim.truth.hidden {
        println!(
            "\nhidden {}/{} = {} {}: {:.3} deg/h rms visible, {:.2}x the floor",
            h.channel, h.term, h.coefficient, h.unit, h.rms_deg_h, h.ratio_to_noise_floor
        );
    }
    Ok(())
}

/// Per channel the error budget of the truth.
fn print_channels(t: &UnitTruth) {
    println!(
        "\n{:<4} {:>7} {:>7} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>8}  collinear",
        "ch",
        "floor",
        "lvlonly",
        "noise",
        "motion",
        "unmod",
        "expect",
        "predict",
        "calerr",
        "after"
    );
    for ct in &t.channels {
        let pairs: Vec<String> = ct
            .collinear
            .iter()
            .map(|p| format!("{}~{}", p.a, p.b))
            .collect();
        println!(
            "{:<4} {:>7.3} {:>7.3} {:>7.3} {:>7.3} {:>8.3} {:>8.3} {:>8.3} {:>8.4} {:>8.3}  {}",
            ct.channel,
            ct.noise_floor_deg_h,
            ct.level_only_noise_floor_deg_h,
            ct.noise_rms_deg_h,
            ct.motion_rms_deg_h,
            ct.unmodelled_rms_deg_h,
            ct.rectification_expected_rms_deg_h,
            ct.predictable_rms_deg_h,
            ct.calibration_error_rms_deg_h,
            ct.after_true_compensation_rms_deg_h,
            pairs.join(" ")
        );
    }
}

/// Per residue the raw, calibrated and true-compensation levels against its floor.
fn print_residues(sim: &UnitSimulation, compensated: &Record) {
    let t = &sim.truth;
    let raw = sim.record.unit_residues(&sim.unit);
    let comp = compensated.unit_residues(&sim.unit);
    println!(
        "\n{:<3} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "K", "raw std", "cal rms", "cal std", "true rms", "floor", "rms/floor"
    );
    for (k, r) in sim.unit.residue_names().iter().enumerate() {
        let floor = t.residue_noise_floor_deg_h[r];
        println!(
            "{:<3} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>9.2}",
            r,
            std_dev(&raw[k]),
            rms(&comp[k]),
            std_dev(&comp[k]),
            t.residue_after_true_compensation_rms_deg_h[r],
            floor,
            rms(&comp[k]) / floor
        );
    }
}

/// The variance of `az` over the last `w` samples, sample by sample.
fn variance_feature(az: &[f64], w: usize) -> Vec<f64> {
    (0..az.len())
        .map(|i| {
            let lo = i.saturating_sub(w - 1);
            let m = az[lo..=i].iter().sum::<f64>() / (i - lo + 1) as f64;
            az[lo..=i].iter().map(|a| (a - m) * (a - m)).sum::<f64>() / (i - lo + 1) as f64
        })
        .collect()
}

/// The least-squares line `y ≈ my + b·(f − mf)` of `y` on `feat`: (mf, my, b).
fn line(feat: &[f64], y: &[f64]) -> (f64, f64, f64) {
    let m = feat.len() as f64;
    let (mf, my) = (feat.iter().sum::<f64>() / m, y.iter().sum::<f64>() / m);
    let b = feat
        .iter()
        .zip(y)
        .map(|(f, y)| (f - mf) * (y - my))
        .sum::<f64>()
        / feat.iter().map(|f| (f - mf) * (f - mf)).sum::<f64>();
    (mf, my, b)
}

/// A proxy of what a windowed model can do: fit each channel's
/// unmodelled + noise series by a + b·var(az) over the last `w` samples.
fn window_proxy(sim: &UnitSimulation, feat: &[f64], w: usize) {
    let n = feat.len();
    println!("\nwindow proxy (a + b*var(az over {w} samples)):");
    for c in sim.unit.gyro_names() {
        let y: Vec<f64> = (0..n)
            .map(|i| {
                sim.components.get(&format!("{c}_unmodelled")).unwrap()[i]
                    + sim.components.get(&format!("{c}_noise")).unwrap()[i]
            })
            .collect();
        let (mf, my, b) = line(feat, &y);
        let res: Vec<f64> = feat
            .iter()
            .zip(&y)
            .map(|(f, y)| y - my - b * (f - mf))
            .collect();
        println!(
            "  {c}: rms before {:.3}, after {:.3}, factor {:.2}",
            rms(&y),
            rms(&res),
            rms(&y) / rms(&res)
        );
    }
}

/// The same proxy on the paper's procedure: fit on the first 70% of the
/// ground-calibration-compensated record (blocked split), predict the
/// last 30%, and compare the residues' rms there before and after.
fn blocked_split_proxy(paper: &Unit, compensated: &Record, feat: &[f64], w: usize) {
    let n = feat.len();
    let split = n * 7 / 10;
    let corrected: Vec<Vec<f64>> = (0..compensated.gyro_names().len())
        .map(|k| {
            let y = compensated.gyro_at(k);
            let (mf, my, b) = line(&feat[..split], &y[..split]);
            (0..n).map(|i| y[i] - my - b * (feat[i] - mf)).collect()
        })
        .collect();
    let before = compensated.unit_residues(paper);
    let after = compensated.with_gyro_series(corrected).unit_residues(paper);
    let factors: Vec<String> = paper
        .residue_names()
        .iter()
        .enumerate()
        .map(|(k, r)| {
            format!(
                "{} {:.2}",
                r,
                rms(&before[k][split..]) / rms(&after[k][split..])
            )
        })
        .collect();
    println!(
        "blocked-split proxy, window {w}: residue rms reduction on validation: {}",
        factors.join(", ")
    );
}
