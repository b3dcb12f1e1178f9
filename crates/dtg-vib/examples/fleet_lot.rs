//! Writes a simulated lot ([`dtg_vib::fleet::simulated`]) to try the
//! `dtg-vib fleet` commands on: tetra units in a tri-axial random test,
//! each with its own g_y sensitivity on g2 drawn around 0.5 deg/h/g
//! (unit-to-unit σ 0.05), hidden from its calibration.
//!
//! ```sh
//! cargo run --release -p dtg-vib --example fleet_lot -- --out lot --units 24 \
//!     --outlier 4=1.0 --outlier 15=0.05 --broken 9=g3
//! dtg-vib fleet run --manifest lot/lot.toml --out lot-out
//! dtg-vib fleet summary --out lot-out
//! ```

use clap::Parser;
use dtg_vib::fleet::simulated::{LotDesign, write};
use std::path::PathBuf;

/// The flags.
#[derive(Parser)]
struct Args {
    /// The folder to write the lot into (its manifest is lot.toml).
    #[arg(long)]
    out: PathBuf,
    /// How many units.
    #[arg(long, default_value_t = 24)]
    units: usize,
    /// A unit out of family, INDEX=VALUE (deg/h/g); repeatable.
    #[arg(long)]
    outlier: Vec<String>,
    /// A unit whose record lacks a column, INDEX=COLUMN; repeatable.
    #[arg(long)]
    broken: Vec<String>,
    /// Each test's length, s.
    #[arg(long, default_value_t = 60.0)]
    duration: f64,
    /// The seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The manifest's [options] and [spec] as TOML.
    #[arg(
        long,
        default_value = "[options]\nadd_effect = [\"g2=g_y\"]\n\n[spec]\ng_y = 0.9\n"
    )]
    tail: String,
}

fn pair(s: &str) -> Result<(usize, String), String> {
    let (i, v) = s
        .split_once('=')
        .ok_or(format!("'{s}': give INDEX=VALUE"))?;
    let i = i.trim().parse().map_err(|e| format!("'{s}': {e}"))?;
    Ok((i, v.trim().to_string()))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a = Args::parse();
    let outliers = a
        .outlier
        .iter()
        .map(|s| {
            let (i, v) = pair(s)?;
            Ok((i, v.parse::<f64>().map_err(|e| format!("'{s}': {e}"))?))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let broken = a
        .broken
        .iter()
        .map(|s| pair(s))
        .collect::<Result<Vec<_>, _>>()?;
    let lot = write(
        &LotDesign {
            unit: "tetra".into(),
            units: a.units,
            channel: "g2".into(),
            effect: "g_y".into(),
            lot_value: 0.5,
            spread: 0.05,
            outliers,
            broken,
            duration_s: a.duration,
            seed: a.seed,
            manifest_tail: a.tail,
        },
        &a.out,
    )?;
    for u in &lot.units {
        println!(
            "{}  g2 g_y {:.4} deg/h/g{}{}",
            u.id,
            u.value,
            if u.outlier { "  (out of family)" } else { "" },
            u.broken
                .as_ref()
                .map_or(String::new(), |c| format!("  (record without {c})"))
        );
    }
    println!("manifest: {}", lot.manifest.display());
    Ok(())
}
