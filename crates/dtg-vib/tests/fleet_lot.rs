//! A lot end to end, lean enough for CI (24 tetra units, 20-s tests): two
//! units out of family and one with a broken channel; `fleet run` then
//! `fleet summary` names exactly those, a rerun skips the done units, a
//! task of the broken unit fails with its reason, and the same lot as a
//! Slurm job array on a single-node Slurm started here gives the same
//! summary (skipped with a notice where slurm-wlm is not installed). The
//! same lot with 60-s tests is `fleet_acceptance.rs` (ignored: minutes).

mod fleet_common;

use fleet_common::{Slurm, dtg, ids, lot, plan, summary, text, verdicts};
use std::path::Path;

const OUTLIERS: [(usize, f64); 2] = [(4, 1.0), (15, 0.05)];
const BROKEN: usize = 9;

#[test]
fn a_lot_run_here_and_as_a_slurm_array_names_the_two_out_of_family_and_the_failed_one() {
    let tmp = tempfile::tempdir().unwrap();
    let lot = lot(&tmp.path().join("lot"), 24, &OUTLIERS, &[BROKEN], 20.0, "");
    let m = lot.manifest.to_str().unwrap();
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();

    let r = dtg(&[
        "--quiet",
        "fleet",
        "run",
        "--manifest",
        m,
        "--out",
        o,
        "--jobs",
        "2",
    ]);
    // A failed unit makes the run exit 1, after every unit ran.
    assert_eq!(r.status.code(), Some(1), "{}", text(&r));
    let said = String::from_utf8_lossy(&r.stdout);
    assert!(
        said.contains("23 done now, 0 already done, 1 failed"),
        "{said}"
    );
    assert!(said.contains("SN0010 failed: "), "{said}");
    assert!(
        said.contains("a unit done now: ") && said.contains("on average over 23"),
        "{said}"
    );

    let s = summary(&out);
    let expected_out: Vec<String> = OUTLIERS
        .iter()
        .map(|(k, _)| format!("SN{:04}", k + 1))
        .collect();
    assert_eq!(ids(&s, "out_of_family"), expected_out, "{s:#}");
    assert_eq!(ids(&s, "failed"), ["SN0010"], "{s:#}");
    let reason = s["failed"][0]["reason"].as_str().unwrap();
    assert!(
        reason.contains("g3"),
        "the reason names the missing column: {reason}"
    );
    // |1.0| is beyond the spec's 0.9; nothing else is.
    assert_eq!(ids(&s, "failing_spec"), ["SN0005"], "{s:#}");
    assert_eq!(s["failing_spec"][0]["limit_key"], "g_y");
    assert_eq!(s["units"].as_array().unwrap().len(), 24);
    for o in s["out_of_family"].as_array().unwrap() {
        assert_eq!(
            (o["channel"].as_str(), o["effect"].as_str()),
            (Some("g2"), Some("g_y"))
        );
        assert!(o["z"].as_f64().unwrap().abs() > 5.0);
    }
    let index = std::fs::read_to_string(out.join("index.html")).unwrap();
    for k in (0..24).filter(|&k| k != BROKEN) {
        assert!(
            index.contains(&format!("units/SN{:04}/report/index.html", k + 1)),
            "unit {k} linked"
        );
        assert!(
            out.join(format!("units/SN{:04}/report/index.html", k + 1))
                .exists()
        );
    }

    // A rerun skips the done units and runs the failed one again.
    let r = dtg(&["--quiet", "fleet", "run", "--manifest", m, "--out", o]);
    let said = String::from_utf8_lossy(&r.stdout);
    assert!(
        said.contains("0 done now, 23 already done, 1 failed"),
        "{}",
        text(&r)
    );
    let t = dtg(&["fleet", "task", "--manifest", m, "--index", "0", "--out", o]);
    assert!(
        String::from_utf8_lossy(&t.stdout).contains("SN0001: already done"),
        "{}",
        text(&t)
    );
    let t = dtg(&["fleet", "task", "--manifest", m, "--index", "9", "--out", o]);
    assert_eq!(t.status.code(), Some(1), "{}", text(&t));
    let err = String::from_utf8_lossy(&t.stderr);
    assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
    assert!(
        err.contains("SN0010 failed") && err.contains("failed.json"),
        "{err}"
    );
    assert_eq!(verdicts(&summary(&out)), verdicts(&s));

    slurm_gives_the_same(tmp.path(), m, &s);
}

/// The same lot as a Slurm job array into another folder: the same summary.
fn slurm_gives_the_same(tmp: &Path, manifest: &str, here: &serde_json::Value) {
    let Some(slurm) = Slurm::start(&tmp.join("slurm")) else {
        return;
    };
    let out = tmp.join("out-slurm");
    let p = plan(manifest, &out, "slurm", &[]);
    assert!(p.status.success(), "{}", text(&p));
    let script = out.join("plan/slurm-array.sh");
    let body = std::fs::read_to_string(&script).unwrap();
    assert!(body.contains("#SBATCH --array=0-23"), "{body}");
    assert!(body.contains("--index \"$SLURM_ARRAY_TASK_ID\""), "{body}");
    let r = slurm.run_array(&script);
    // The broken unit's element fails, so sbatch --wait says so.
    assert!(!r.status.success(), "{}", text(&r));
    let s = summary(&out);
    assert_eq!(
        verdicts(&s),
        verdicts(here),
        "Slurm's summary differs from the local run's"
    );
    let log = std::fs::read_to_string(out.join("logs/task-9.log")).unwrap();
    assert!(log.contains("SN0010 failed"), "{log}");
}
