//! `fleet plan`: a Kubernetes Indexed Job that validates against the
//! batch/v1 Job schema of Kubernetes v1.33 (tests/fixtures/kubernetes/, no
//! cluster needed), a Slurm job-array script, both with the requests of a
//! measured task (task 0, run by the plan itself when no unit is done).

mod fleet_common;

use dtg_vib::fleet::layout::read_json;
use dtg_vib::fleet::plan::{Requests, yaml};
use dtg_vib::fleet::task::TaskRecord;
use fleet_common::{dtg, lot, plan, text};
use serde_json::{Value, json};

fn job_schema() -> jsonschema::Validator {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/kubernetes/job-batch-v1.33.json"
    );
    let schema: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    jsonschema::validator_for(&schema).expect("the Job schema compiles")
}

fn errors(v: &jsonschema::Validator, job: &Value) -> Vec<String> {
    v.iter_errors(job)
        .map(|e| format!("{}: {e}", e.instance_path()))
        .collect()
}

#[test]
fn the_kubernetes_plan_is_an_indexed_job_the_schema_takes_with_a_measured_tasks_requests() {
    let tmp = tempfile::tempdir().unwrap();
    let lot = lot(&tmp.path().join("lot"), 3, &[], &[], 20.0, "");
    let out = tmp.path().join("out");
    let p = plan(
        lot.manifest.to_str().unwrap(),
        &out,
        "kubernetes",
        &[
            "--image",
            "registry.example/dtg-vib:1",
            "--claim",
            "lot-2026-48",
        ],
    );
    assert!(p.status.success(), "{}", text(&p));
    let said = String::from_utf8_lossy(&p.stdout);
    assert!(said.contains("measured: SN0001"), "{said}");
    let task: TaskRecord = read_json(&out.join("units/SN0001/task.json")).unwrap();
    let r = Requests::of(&task.cost);

    let text = std::fs::read_to_string(out.join("plan/job.yaml")).unwrap();
    let job: Value = serde_norway::from_str(&text).expect("job.yaml is YAML");
    let schema = job_schema();
    assert_eq!(errors(&schema, &job), Vec::<String>::new(), "{text}");
    let spec = &job["spec"];
    assert_eq!(spec["completionMode"], "Indexed");
    assert_eq!(spec["completions"], 3);
    let c = &spec["template"]["spec"]["containers"][0];
    assert_eq!(c["image"], "registry.example/dtg-vib:1");
    let args: Vec<&str> = c["args"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    let at = args.iter().position(|a| *a == "--index").unwrap();
    assert_eq!(args[at + 1], "$(JOB_COMPLETION_INDEX)");
    assert_eq!(&args[..3], ["--quiet", "fleet", "task"]);
    assert_eq!(
        c["resources"]["requests"]["memory"],
        format!("{}Mi", r.memory_mib)
    );
    assert_eq!(c["resources"]["requests"]["cpu"], r.cpus.to_string());
    assert!(r.memory_mib >= 128 && r.memory_mib.is_multiple_of(64));
    let rss_mib = task.cost.max_rss_bytes.unwrap() as f64 / 1048576.0;
    assert!(
        r.memory_mib as f64 >= 1.5 * rss_mib,
        "{r:?} for {rss_mib} MiB"
    );
    assert_eq!(
        spec["template"]["spec"]["volumes"][0]["persistentVolumeClaim"]["claimName"],
        "lot-2026-48"
    );
    assert!(
        text.contains("fleet summary --out"),
        "the summary command: {text}"
    );

    // The check can fail: a misspelt field and a wrong mode are refused.
    let mut bad = job.clone();
    bad["spec"]["completionsMode"] = json!("Indexed");
    assert!(!errors(&schema, &bad).is_empty());
    let mut bad = job.clone();
    bad["spec"]["template"]["spec"]["containers"][0]["resources"]["requests"] = json!(["1"]);
    assert!(!errors(&schema, &bad).is_empty());
}

#[test]
fn the_slurm_plan_is_a_job_array_with_the_measured_requests() {
    let tmp = tempfile::tempdir().unwrap();
    let lot = lot(&tmp.path().join("lot"), 3, &[], &[], 20.0, "");
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();
    let m = lot.manifest.to_str().unwrap();
    let t = dtg(&[
        "--quiet",
        "fleet",
        "task",
        "--manifest",
        m,
        "--index",
        "1",
        "--out",
        o,
    ]);
    assert!(t.status.success(), "{}", text(&t));
    let p = plan(m, &out, "slurm", &[]);
    assert!(p.status.success(), "{}", text(&p));
    // A done unit is measured: no task is run for the plan.
    assert!(!out.join("units/SN0001").exists());
    let task: TaskRecord = read_json(&out.join("units/SN0002/task.json")).unwrap();
    let r = Requests::of(&task.cost);
    let s = std::fs::read_to_string(out.join("plan/slurm-array.sh")).unwrap();
    for line in [
        "#SBATCH --array=0-2".to_string(),
        format!("#SBATCH --cpus-per-task={}", r.cpus),
        format!("#SBATCH --mem={}M", r.memory_mib),
        format!("#SBATCH --time={}", r.minutes),
        format!("#SBATCH --output={}/logs/task-%a.log", o),
    ] {
        assert!(s.lines().any(|l| l == line), "{line} in\n{s}");
    }
    assert!(
        s.contains("fleet task --manifest") && s.contains("fleet summary --out"),
        "{s}"
    );
    assert!(
        out.join("logs").is_dir(),
        "Slurm does not make the log folder"
    );
}

#[test]
fn the_yaml_writer_reads_back_as_the_value_it_wrote() {
    let v = json!({
        "a": "x: y # not a comment",
        "b": [[1, 2], [], {}, {"c": "'quoted' \"and\" \\ back\nslash"}, null, true, -1.5e-3],
        "app.kubernetes.io/name": "dtg-vib-fleet",
        "with space": [{"k": [{"deep": "$(JOB_COMPLETION_INDEX)"}]}],
    });
    let back: Value = serde_norway::from_str(&yaml(&v)).unwrap();
    assert_eq!(back, v, "{}", yaml(&v));
}
