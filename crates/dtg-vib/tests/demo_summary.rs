//! The demo's final page says at the top what its tables show further down
//! (issue 26 item 8): the summary states that bias instability rose when
//! the Allan table shows it, the residual's ratio to the noise floor as the
//! floor table prints it, and whether the diagnosis of the refit names
//! anything. The tables are read from the written page, as a reader sees
//! them.

use std::process::Command;

/// The cells of each body row of the first table after heading `h2`.
fn table_after(html: &str, h2: &str) -> Vec<Vec<String>> {
    let at = html
        .find(&format!("<h2>{h2}</h2>"))
        .unwrap_or_else(|| panic!("no section {h2:?}"));
    let body = &html[at..];
    let start = body.find("<tbody>").expect("a table body");
    let end = body[start..].find("</tbody>").expect("the body's end") + start;
    body[start..end]
        .split("<tr>")
        .skip(1)
        .map(|row| {
            row.split("<td")
                .skip(1)
                .map(|cell| {
                    let open = cell.find('>').expect("cell tag") + 1;
                    let close = cell.find("</td>").expect("cell end");
                    cell[open..close]
                        .replace("&lt;", "<")
                        .replace("&gt;", ">")
                        .replace("&amp;", "&")
                })
                .collect()
        })
        .collect()
}

/// `value [low, high]` → (value, low, high); `< bound (not resolved)` →
/// (bound, 0, bound).
fn term(cell: &str) -> (f64, f64, f64) {
    if let Some(b) = cell.strip_prefix("< ") {
        let b: f64 = b.split_whitespace().next().unwrap().parse().unwrap();
        return (b, 0.0, b);
    }
    let (v, rest) = cell.split_once(" [").expect("value [low, high]");
    let (lo, hi) = rest.trim_end_matches(']').split_once(", ").unwrap();
    (v.parse().unwrap(), lo.parse().unwrap(), hi.parse().unwrap())
}

/// The page's summary paragraphs, entities decoded.
fn summary(html: &str) -> String {
    html.split("<p class=\"summary\">")
        .skip(1)
        .map(|p| p.split("</p>").next().unwrap())
        .collect::<Vec<_>>()
        .join("\n")
        .replace("&#39;", "'")
        .replace("&amp;", "&")
}

#[test]
fn the_final_page_summary_states_what_is_left_and_what_got_worse() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("demo");
    let run = Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
        .args(["--quiet", "demo", "--out"])
        .arg(&out)
        .output()
        .expect("run dtg-vib demo");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let top = summary(&html);

    // Allan: BI before is column 3, after column 4 (after series, ARW
    // before and after). Worse = after's interval wholly above before's.
    for (h2, what) in [
        ("Allan deviation: gyro channels", "channels"),
        ("Allan deviation: parity residues", "parity residues"),
    ] {
        let rows = table_after(&html, h2);
        assert_eq!(rows.len(), 6, "{h2}");
        let worse = rows
            .iter()
            .filter(|r| {
                let (_, _, b_hi) = term(&r[3]);
                !r[4].starts_with('<') && term(&r[4]).1 > b_hi
            })
            .count();
        let claim = format!("on {worse} of 6 {what}");
        let said = top.contains("Bias instability after compensation is higher than before")
            && top.contains(&claim);
        if worse > 0 {
            assert!(
                said,
                "the table shows BI higher on {worse} {what}; summary:\n{top}"
            );
        } else {
            assert!(!top.contains(&claim), "{top}");
        }
    }
    // On the demo the refit's bias instability rose on every channel
    // (0.33–0.40 → 0.51–0.60 deg/h) until the fit chose its input and
    // prediction smoother under the Allan constraint (issue 23); now it
    // falls (0.30–0.37 deg/h, docs/dtg-vib.md): the summary must not say
    // it got worse. If that changes, the docs quoting it must too.
    assert!(
        !top.contains("Bias instability after compensation is higher than before"),
        "{top}"
    );

    // The residual against the noise floor: the table's smallest and largest
    // ratio, as printed.
    let floor = table_after(&html, "Residual distribution against the noise floor");
    let mut ratios: Vec<(f64, String)> = floor
        .iter()
        .map(|r| (r[3].trim_end_matches('×').parse().unwrap(), r[3].clone()))
        .collect();
    ratios.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (lo, hi) = (&ratios[0].1, &ratios[ratios.len() - 1].1);
    assert!(
        top.contains(&format!("The residual is {lo} to {hi} the noise floor")),
        "{top}"
    );

    // The diagnosis of the refit: nothing suggested on any channel, and the
    // summary says so with the top candidates' ERR below the threshold.
    let diag = table_after(&html, "Diagnosis");
    assert!(diag.iter().all(|r| r[1] == "nothing"), "{diag:?}");
    assert!(
        top.contains("found no missing effect that explains it")
            && top.contains("below the worth threshold ERR 0.1164"),
        "{top}"
    );
    for r in &diag {
        assert!(top.contains("ERR ") && r[3].parse::<f64>().unwrap() < 0.1164);
    }
}
