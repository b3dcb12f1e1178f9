//! Every link a report writes resolves from the page itself (issue 26 item
//! 1): the demo and every other report writer (`report`, `diagnose
//! --report`, `check --report`, `allan --report`, `explain --report`) run
//! with relative paths from a working directory that is not the reports'
//! own, then every written `.html` is read and each `href`, `src` and
//! `srcset` that is not a web address must name a file that exists
//! relative to the page, and each `#anchor` an `id` on the page it points
//! into. The same for the pages of units other than the paper's.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

/// One link that does not resolve: the page, the link as written, why.
#[derive(Debug)]
struct Broken {
    page: PathBuf,
    link: String,
    why: String,
}

impl std::fmt::Display for Broken {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {:?} {}", self.page.display(), self.link, self.why)
    }
}

/// The values of attribute `name` (double-quoted, as the reports write
/// them) in `html`, entities decoded.
fn attribute_values(html: &str, name: &str) -> Vec<String> {
    let pat = format!(" {name}=\"");
    let mut out = Vec::new();
    let mut rest = html;
    while let Some(i) = rest.find(&pat) {
        rest = &rest[i + pat.len()..];
        let end = rest.find('"').unwrap_or(rest.len());
        out.push(decode_entities(&rest[..end]));
        rest = &rest[end..];
    }
    out
}

fn decode_entities(s: &str) -> String {
    s.replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

/// `%XX` escapes decoded (a link's path as the file system spells it).
fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%'
            && let Some(hex) = b.get(i + 1..i + 3)
            && let Ok(v) = u8::from_str_radix(&String::from_utf8_lossy(hex), 16)
        {
            out.push(v);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The `id`s of a page.
fn ids(html: &str) -> BTreeSet<String> {
    attribute_values(html, "id").into_iter().collect()
}

/// Every link of the page at `page` that does not resolve, and how many
/// links it checked.
fn check_page(page: &Path) -> (Vec<Broken>, usize) {
    let html = std::fs::read_to_string(page).expect("read page");
    let dir = page.parent().unwrap_or(Path::new("."));
    let mut links: Vec<String> = attribute_values(&html, "href");
    links.extend(attribute_values(&html, "src"));
    // srcset: comma-separated "URL [descriptor]".
    for set in attribute_values(&html, "srcset") {
        links.extend(
            set.split(',')
                .filter_map(|c| c.split_whitespace().next())
                .map(str::to_string),
        );
    }
    let mut broken = Vec::new();
    let bad = |link: &str, why: String| Broken {
        page: page.to_path_buf(),
        link: link.to_string(),
        why,
    };
    let here = ids(&html);
    for link in &links {
        let lower = link.to_ascii_lowercase();
        if lower.starts_with("http://") || lower.starts_with("https://") {
            continue;
        }
        if lower.starts_with("file:") || link.starts_with('/') {
            broken.push(bad(
                link,
                "is absolute: it breaks when the report is moved or opened elsewhere".into(),
            ));
            continue;
        }
        if lower.contains(':') && !lower.contains('/') {
            broken.push(bad(link, "has a scheme a report should not use".into()));
            continue;
        }
        let (path, anchor) = match link.split_once('#') {
            Some((p, a)) => (p, Some(a)),
            None => (link.as_str(), None),
        };
        if path.is_empty() {
            if let Some(a) = anchor
                && !here.contains(a)
            {
                broken.push(bad(link, "names no id on this page".into()));
            }
            continue;
        }
        let target = dir.join(percent_decode(path));
        if !target.exists() {
            broken.push(bad(
                link,
                format!("resolves to {}, which does not exist", target.display()),
            ));
            continue;
        }
        if let Some(a) = anchor {
            let there = std::fs::read_to_string(&target).map(|h| ids(&h));
            if !there.is_ok_and(|ids| ids.contains(a)) {
                broken.push(bad(link, format!("names no id on {}", target.display())));
            }
        }
    }
    (broken, links.len())
}

/// Every `.html` file under `dir`.
fn pages(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("read dir") {
            let p = e.expect("dir entry").path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "html") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// Checks every page under `dir`: the broken links and the number checked.
fn check_dir(dir: &Path) -> (Vec<Broken>, usize) {
    let mut broken = Vec::new();
    let mut n = 0;
    for p in pages(dir) {
        let (b, k) = check_page(&p);
        broken.extend(b);
        n += k;
    }
    (broken, n)
}

/// Runs `dtg-vib ARGS` in `cwd`.
fn dtg(cwd: &Path, args: &[&str]) {
    dtg_out(cwd, args);
}

/// Runs every report writer but the demo (`report`, `diagnose --report`,
/// `check --report`, `allan --report`, `explain --report`) in `work` on the
/// demo written to `../out/demo`, with relative paths and one absolute;
/// `explain` gets `explain_args` too.
fn every_writer(work: &Path, out: &Path, explain_args: &[&str]) {
    let d = "../out/demo";
    let record = format!("{d}/simulation/record.csv");
    let calib = format!("{d}/simulation/calibration.json");
    let base = format!("{d}/baseline/model.json");
    let model = format!("{d}/final/model.json");
    dtg(
        work,
        &[
            "report",
            "--model",
            &model,
            "--baseline",
            &base,
            "--data",
            &record,
            "--out",
            "../out/report/deeper",
        ],
    );
    dtg(
        work,
        &[
            "diagnose",
            "--model",
            &base,
            "--data",
            &record,
            "--report",
            "../out/diagnose",
        ],
    );
    dtg(
        work,
        &[
            "check", "--model", &model, "--data", &record, "--report", "check",
        ],
    );
    // An absolute --report too.
    let allan = out.join("allan");
    dtg(
        work,
        &[
            "allan",
            "--data",
            &record,
            "--model",
            &model,
            "--report",
            allan.to_str().unwrap(),
        ],
    );
    let mut explain = vec![
        "explain",
        "--data",
        &record,
        "--calib",
        &calib,
        "--max-rounds",
        "1",
        "--out",
        "../out/explained.json",
        "--report",
        "../out/explain",
    ];
    explain.extend_from_slice(explain_args);
    dtg(work, &explain);
}

/// Every page [`every_writer`] and the demo write exists.
fn every_page_written(out: &Path, work: &Path) {
    for page in [
        "demo/index.html",
        "demo/final/report/index.html",
        "demo/baseline/report/index.html",
        "demo/diagnosis/index.html",
        "demo/final/diagnosis/index.html",
        "report/deeper/index.html",
        "diagnose/index.html",
        "allan/index.html",
        "explain/index.html",
    ] {
        assert!(out.join(page).exists(), "{page} not written");
    }
    assert!(work.join("check/index.html").exists());
}

#[test]
fn every_link_of_every_report_resolves_from_its_page() {
    let tmp = tempfile::tempdir().unwrap();
    // The commands run in `work/` and write into `../out/...`: a link written
    // relative to where the command ran, not to the page, breaks here.
    let work = tmp.path().join("work");
    std::fs::create_dir_all(&work).unwrap();
    let out = tmp.path().join("out");
    dtg(&work, &["demo", "--out", "../out/demo"]);
    every_writer(&work, &out, &["--max-centers", "10"]);

    let mut broken = Vec::new();
    let mut checked = 0;
    for dir in [&out, &work] {
        let (b, n) = check_dir(dir);
        broken.extend(b);
        checked += n;
    }
    let written = pages(&out).len() + pages(&work).len();
    eprintln!(
        "{written} pages, {checked} links checked, {} broken",
        broken.len()
    );
    let list: Vec<String> = broken.iter().map(ToString::to_string).collect();
    assert!(list.is_empty(), "broken links:\n{}", list.join("\n"));
    // Each writer wrote its page, and the demo's pages link each other.
    every_page_written(&out, &work);
    let fin = std::fs::read_to_string(out.join("demo/final/report/index.html")).unwrap();
    for link in [
        "href=\"../../baseline/report/index.html\"",
        "href=\"../../diagnosis/index.html\"",
        "href=\"../diagnosis/index.html\"",
    ] {
        assert!(fin.contains(link), "final report lacks {link}");
    }
    assert!(checked > 300, "only {checked} links checked");
}

/// Runs `dtg-vib ARGS` in `cwd` and returns its stdout.
fn dtg_out(cwd: &Path, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
        .current_dir(cwd)
        .arg("--quiet")
        .args(args)
        .output()
        .expect("run dtg-vib");
    assert!(
        out.status.success(),
        "dtg-vib {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The pages of a unit other than the paper's: `demo --unit` (tetra, and
/// triad, which has no parity residue) and every report writer on the
/// tetra demo's models, run as above; each page's links resolve, and the
/// demo says what it hid and found.
#[test]
fn every_link_of_every_unit_report_resolves_from_its_page() {
    let tmp = tempfile::tempdir().unwrap();
    let work = tmp.path().join("work");
    std::fs::create_dir_all(&work).unwrap();
    let out = tmp.path().join("out");
    let said = dtg_out(&work, &["demo", "--unit", "tetra", "--out", "../out/demo"]);
    for line in [
        "hidden from the calibration: g2=g_y (0.5 deg/h/g), g3=col:temp (0.05 deg/h/°C)",
        "four gyros detect but cannot isolate",
    ] {
        assert!(said.contains(line), "{said}");
    }
    assert_eq!(said.matches("inside the interval").count(), 2, "{said}");
    every_writer(&work, &out, &["--unit", "tetra", "--max-centres", "8"]);
    let said = dtg_out(&work, &["demo", "--unit", "triad", "--out", "../out/triad"]);
    assert!(said.contains("gx=g_y: "), "{said}");
    let triad_page = std::fs::read_to_string(out.join("triad/index.html")).unwrap();
    assert!(triad_page.contains("no parity residue"), "the triad's page");

    let mut broken = Vec::new();
    for dir in [&out, &work] {
        broken.extend(check_dir(dir).0);
    }
    let list: Vec<String> = broken.iter().map(ToString::to_string).collect();
    assert!(list.is_empty(), "broken links:\n{}", list.join("\n"));
    every_page_written(&out, &work);
    let fin = std::fs::read_to_string(out.join("demo/index.html")).unwrap();
    for text in [
        "href=\"final/diagnosis/index.html\"",
        "Effects found",
        "Parity residues",
        "P0",
        "Allan deviation",
    ] {
        assert!(fin.contains(text), "the demo's page lacks {text}");
    }
}

#[test]
fn the_checker_finds_a_broken_link_anchor_image_and_absolute_path() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("r");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(dir.join("sub/fig 1.png"), b"png").unwrap();
    std::fs::write(
        dir.join("sub/other.html"),
        "<html><body><section id=\"s1\"></section></body></html>",
    )
    .unwrap();
    std::fs::write(
        dir.join("index.html"),
        "<html><body><nav><a href=\"#s1\">ok</a> <a href=\"#s9\">no such id</a></nav>\
         <section id=\"s1\"><img src=\"sub/fig%201.png\" alt=\"\"><img src=\"sub/missing.png\" alt=\"\">\
         <picture><source srcset=\"sub/narrow.png\"></picture>\
         <a href=\"sub/other.html#s1\">ok</a> <a href=\"sub/other.html#s2\">no id there</a>\
         <a href=\"../elsewhere/index.html\">gone</a> <a href=\"file:///tmp/x.html\">absolute</a>\
         <a href=\"https://example.org/\">web</a></section></body></html>",
    )
    .unwrap();
    let (broken, checked) = check_dir(&dir);
    assert_eq!(checked, 10);
    let links: Vec<&str> = broken.iter().map(|b| b.link.as_str()).collect();
    assert_eq!(
        links,
        [
            "#s9",
            "sub/other.html#s2",
            "../elsewhere/index.html",
            "file:///tmp/x.html",
            "sub/missing.png",
            "sub/narrow.png",
        ],
        "{broken:?}"
    );
    assert!(broken[2].to_string().contains("does not exist"));
}

/// scripts/screenshot-report.sh follows the page's links before it looks
/// for Chromium: a broken one makes it exit 1 naming the link, with or
/// without a browser; a page whose links resolve passes on to the browser
/// (exit 2 where there is none).
#[test]
fn the_browser_script_fails_naming_a_broken_link() {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/screenshot-report.sh");
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("r");
    std::fs::create_dir_all(dir.join("figs")).unwrap();
    std::fs::write(dir.join("figs/a b.png"), b"png").unwrap();
    let page = |links: &str| {
        std::fs::write(
            dir.join("index.html"),
            format!("<html><body><section id=\"s1\"><img src=\"figs/a%20b.png\" alt=\"\">{links}<a href=\"#s1\">top</a></section></body></html>"),
        )
        .unwrap();
        Command::new("bash")
            .arg(&script)
            .arg(dir.join("index.html"))
            .arg(tmp.path().join("shots"))
            .env("CHROMIUM", "/nonexistent/chromium")
            .output()
            .expect("run bash")
    };
    let bad =
        page("<a href=\"../baseline/report/index.html\">baseline</a><a href=\"#s2\">gone</a>");
    let err = String::from_utf8_lossy(&bad.stderr);
    assert_eq!(bad.status.code(), Some(1), "{err}");
    assert!(
        err.contains("broken link in")
            && err.contains("\"../baseline/report/index.html\" resolves to"),
        "{err}"
    );
    assert!(err.contains("\"#s2\" names no id on the page"), "{err}");
    assert!(String::from_utf8_lossy(&bad.stdout).contains("links=4 broken_links=2"));
    let good = page("");
    assert_eq!(
        good.status.code(),
        Some(2),
        "links resolve, then no browser: {}",
        String::from_utf8_lossy(&good.stderr)
    );
}
