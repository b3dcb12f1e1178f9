//! What the fleet's tests share: the binary, a simulated lot of tetra
//! units, reading a summary, and a single-node Slurm started for the test
//! (`scripts/slurm-single-node.sh`), or a notice where there is none.

#![allow(dead_code)]

use dtg_vib::fleet::simulated::{LotDesign, SimulatedLot, write};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_dtg-vib")
}

/// `dtg-vib ARGS`.
pub fn dtg(args: &[&str]) -> Output {
    Command::new(bin())
        .args(args)
        .output()
        .expect("dtg-vib runs")
}

pub fn text(o: &Output) -> String {
    format!(
        "status {}\nstdout:\n{}\nstderr:\n{}",
        o.status,
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// A lot of `units` tetra units, each with its own g_y on g2 drawn around
/// 0.5 deg/h/g (σ 0.05 between units), `outliers` put far from it,
/// `broken` without g3 in their record; tests of `duration_s`; g_y on g2
/// fitted on every unit; |g_y| ≤ 0.9 deg/h/g by the spec.
pub fn lot(
    dir: &Path,
    units: usize,
    outliers: &[(usize, f64)],
    broken: &[usize],
    duration_s: f64,
    options: &str,
) -> SimulatedLot {
    lot_seeded(dir, units, outliers, broken, duration_s, options, 7)
}

/// [`lot`] with its own seed.
pub fn lot_seeded(
    dir: &Path,
    units: usize,
    outliers: &[(usize, f64)],
    broken: &[usize],
    duration_s: f64,
    options: &str,
    seed: u64,
) -> SimulatedLot {
    write(
        &LotDesign {
            unit: "tetra".into(),
            units,
            channel: "g2".into(),
            effect: "g_y".into(),
            lot_value: 0.5,
            spread: 0.05,
            outliers: outliers.to_vec(),
            broken: broken.iter().map(|&k| (k, "g3".to_string())).collect(),
            duration_s,
            seed,
            manifest_tail: format!(
                "[options]\nadd_effect = [\"g2=g_y\"]\n{options}\n[spec]\ng_y = 0.9\n"
            ),
        },
        dir,
    )
    .expect("the lot simulates")
}

/// `dtg-vib --quiet fleet plan --manifest MANIFEST --out OUT --engine ENGINE EXTRA…`.
pub fn plan(manifest: &str, out: &Path, engine: &str, extra: &[&str]) -> Output {
    let o = out.to_str().unwrap();
    let mut args = vec![
        "--quiet",
        "fleet",
        "plan",
        "--manifest",
        manifest,
        "--out",
        o,
        "--engine",
        engine,
    ];
    args.extend_from_slice(extra);
    dtg(&args)
}

/// `fleet summary --json` of `out`.
pub fn summary(out: &Path) -> Value {
    let o = dtg(&["fleet", "summary", "--out", out.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", text(&o));
    serde_json::from_slice(&o.stdout).expect("summary JSON")
}

/// The sorted unit ids of a summary list.
pub fn ids(s: &Value, key: &str) -> Vec<String> {
    let mut v: Vec<String> = s[key]
        .as_array()
        .unwrap_or_else(|| panic!("{key} is a list"))
        .iter()
        .map(|x| x["unit"].as_str().unwrap().to_string())
        .collect();
    v.sort();
    v.dedup();
    v
}

/// The summary with what depends on where and when it ran left out: the
/// verdicts and every coefficient, to compare two runs of one lot.
pub fn verdicts(s: &Value) -> Value {
    serde_json::json!({
        "out_of_family": s["out_of_family"],
        "failing_spec": s["failing_spec"],
        "failed": s["failed"],
        "groups": s["groups"],
        "not_run": s["not_run"],
    })
}

/// A free TCP port on the loopback.
fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

/// A single-node Slurm, stopped when dropped.
pub struct Slurm {
    dir: PathBuf,
    pub conf: PathBuf,
}

impl Slurm {
    /// Starts one in `dir`, or, where slurm-wlm is not installed, says so
    /// (a notice) and gives `None`.
    pub fn start(dir: &Path) -> Option<Self> {
        let script =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/slurm-single-node.sh");
        let (a, b) = (free_port(), free_port());
        let o = Command::new("bash")
            .arg(&script)
            .arg("start")
            .arg(dir)
            .arg(a.to_string())
            .arg(b.to_string())
            .output()
            .expect("bash runs");
        // Exit 2: slurm-wlm is not installed, the one case skipped. Installed
        // but not starting is a failure, so CI cannot pass without running it.
        assert!(
            o.status.success() || o.status.code() == Some(2),
            "slurm-wlm is installed but the single-node Slurm did not start: {}",
            text(&o)
        );
        if !o.status.success() {
            eprintln!(
                "notice: no single-node Slurm here, the Slurm run is skipped ({}): .ci/install-slurm.sh installs Debian's slurm-wlm",
                String::from_utf8_lossy(&o.stderr).trim()
            );
            return None;
        }
        Some(Self {
            dir: dir.to_path_buf(),
            conf: dir.join("slurm.conf"),
        })
    }

    /// `sbatch --wait SCRIPT`: its output (it fails when an element failed).
    pub fn run_array(&self, script: &Path) -> Output {
        Command::new("sbatch")
            .arg("--wait")
            .arg(script)
            .env("SLURM_CONF", &self.conf)
            .output()
            .expect("sbatch runs")
    }
}

impl Drop for Slurm {
    fn drop(&mut self) {
        let script =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/slurm-single-node.sh");
        let _ = Command::new("bash")
            .arg(script)
            .arg("stop")
            .arg(&self.dir)
            .output();
    }
}
