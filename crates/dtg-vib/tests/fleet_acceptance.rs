//! The acceptance lot of issue 38: 24 tetra units, each a 60-s tri-axial
//! random-vibration test with its own g_y on g2 drawn around 0.5 deg/h/g
//! (σ 0.05 between units), SN0005 at 1.0 and SN0016 at 0.05 (out of
//! family), SN0010's record without g3 (a broken channel). `fleet run` then
//! `fleet summary` names exactly those two and the failed one; a rerun
//! skips the 23 done units; the same lot as a Slurm job array on a
//! single-node Slurm gives the same summary (skipped with a notice without
//! slurm-wlm). Prints the time per unit that docs/campaign.md quotes.
//!
//! `cargo test --release -p dtg-vib --test fleet_acceptance -- --ignored --nocapture`
//! (about 2 minutes on 2 quiet cores; `fleet_lot.rs` is CI's short version).

mod fleet_common;

use dtg_vib::fleet::layout::read_json;
use dtg_vib::fleet::task::TaskRecord;
use fleet_common::{Slurm, dtg, ids, lot, plan, summary, text, verdicts};

#[test]
#[ignore = "the full acceptance lot: 24 units of 60 s, run here and as a Slurm array (minutes)"]
fn the_acceptance_lot_names_exactly_the_two_out_of_family_and_the_broken_one() {
    let tmp = tempfile::tempdir().unwrap();
    let lot = lot(
        &tmp.path().join("lot"),
        24,
        &[(4, 1.0), (15, 0.05)],
        &[9],
        60.0,
        "",
    );
    let m = lot.manifest.to_str().unwrap();
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();
    let start = std::time::Instant::now();
    let r = dtg(&["--quiet", "fleet", "run", "--manifest", m, "--out", o]);
    let wall = start.elapsed().as_secs_f64();
    assert_eq!(r.status.code(), Some(1), "{}", text(&r));
    println!("{}", String::from_utf8_lossy(&r.stdout));

    let s = summary(&out);
    assert_eq!(ids(&s, "out_of_family"), ["SN0005", "SN0016"], "{s:#}");
    assert_eq!(ids(&s, "failed"), ["SN0010"], "{s:#}");
    assert_eq!(ids(&s, "failing_spec"), ["SN0005"], "{s:#}");
    let g = s["groups"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["channel"] == "g2" && g["effect"] == "g_y")
        .unwrap();
    println!(
        "g2 g_y over {} units: median {:.4}, MAD {:.4}, robust σ {:.4} deg/h/g",
        g["members"].as_array().unwrap().len(),
        g["median"].as_f64().unwrap(),
        g["mad"].as_f64().unwrap(),
        g["robust_sigma"].as_f64().unwrap()
    );
    for o in s["out_of_family"].as_array().unwrap() {
        println!(
            "out of family: {} {} {} {:.4} z {:.1}",
            o["unit"],
            o["channel"],
            o["effect"],
            o["value"].as_f64().unwrap(),
            o["z"].as_f64().unwrap()
        );
    }
    // Each unit's interval covers its true coefficient in most units (95%).
    let covered = lot
        .units
        .iter()
        .filter(|u| u.broken.is_none())
        .filter(|u| {
            let m = &g["members"]
                .as_array()
                .unwrap()
                .iter()
                .find(|m| m["unit"] == u.id.as_str())
                .unwrap()["ci95"];
            m[0].as_f64().unwrap() <= u.value && u.value <= m[1].as_f64().unwrap()
        })
        .count();
    println!("intervals covering the true coefficient: {covered} of 23");
    assert!(covered >= 19, "{covered} of 23 intervals cover the truth");

    let costs: Vec<TaskRecord> = lot
        .units
        .iter()
        .filter(|u| u.broken.is_none())
        .map(|u| read_json(&out.join("units").join(&u.id).join("task.json")).unwrap())
        .collect();
    let mean =
        |f: &dyn Fn(&TaskRecord) -> f64| costs.iter().map(f).sum::<f64>() / costs.len() as f64;
    println!(
        "per unit: {:.2} s wall, {:.2} s CPU, peak {:.0} MiB (mean of 23 tasks); the lot: {:.1} s wall with {} jobs, {:.2} s a unit; load before the run {}",
        mean(&|t| t.cost.seconds),
        mean(&|t| t.cost.cpu_seconds.unwrap_or(f64::NAN)),
        mean(&|t| t.cost.max_rss_bytes.unwrap_or(0) as f64 / 1048576.0),
        wall,
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        wall / 24.0,
        std::fs::read_to_string("/proc/loadavg")
            .unwrap_or_default()
            .trim()
    );

    let r = dtg(&["--quiet", "fleet", "run", "--manifest", m, "--out", o]);
    assert!(
        String::from_utf8_lossy(&r.stdout).contains("0 done now, 23 already done, 1 failed"),
        "{}",
        text(&r)
    );

    let Some(slurm) = Slurm::start(&tmp.path().join("slurm")) else {
        return;
    };
    let out2 = tmp.path().join("out-slurm");
    let p = plan(m, &out2, "slurm", &[]);
    assert!(p.status.success(), "{}", text(&p));
    println!("{}", String::from_utf8_lossy(&p.stdout));
    let start = std::time::Instant::now();
    let r = slurm.run_array(&out2.join("plan/slurm-array.sh"));
    println!(
        "the Slurm array: {:.1} s wall",
        start.elapsed().as_secs_f64()
    );
    assert!(
        !r.status.success(),
        "the broken unit's element fails: {}",
        text(&r)
    );
    assert_eq!(
        verdicts(&summary(&out2)),
        verdicts(&s),
        "Slurm's summary differs"
    );
}
