//! End-to-end tests: figures are written, are valid images, show what they
//! should, and survive hostile data.

use std::path::{Path, PathBuf};

use super::style::hex;
use super::*;

/// A fresh directory per test (tests run in parallel), removed when the test
/// passes and kept for inspection when it fails (or with `KEEP_TEST_FIGURES`).
struct TestDir(PathBuf);

impl TestDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("plot-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        TestDir(dir)
    }
}

impl std::ops::Deref for TestDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for TestDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TestDir {
    fn drop(&mut self) {
        if !std::thread::panicking() && std::env::var_os("KEEP_TEST_FIGURES").is_none() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

fn test_dir(name: &str) -> TestDir {
    TestDir::new(name)
}

fn time(n: usize) -> Vec<f64> {
    (0..n).map(|i| i as f64 * 0.02).collect()
}

/// Reads the PNG signature and IHDR, and decodes the whole image.
fn check_png(path: &Path, size: (u32, u32)) -> image::RgbImage {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!((w, h), size, "IHDR dimensions");
    let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
        .expect("decodable PNG")
        .to_rgb8();
    assert_eq!(img.dimensions(), size);
    img
}

fn count_pixels(img: &image::RgbImage, c: plotters::style::RGBColor) -> usize {
    img.pixels().filter(|p| p.0 == [c.0, c.1, c.2]).count()
}

/// `<polyline>` elements drawn in colour `c` with more than `min_points` points
/// (legend swatches have two).
fn polylines(svg: &str, c: plotters::style::RGBColor, min_points: usize) -> usize {
    let stroke = format!("stroke=\"{}\"", hex(c));
    svg.split("<polyline")
        .skip(1)
        .map(|el| &el[..el.find("/>").unwrap_or(el.len())])
        .filter(|el| el.contains(&stroke))
        .filter(|el| {
            let pts = el.split("points=\"").nth(1).unwrap_or("");
            let pts = &pts[..pts.find('"').unwrap_or(0)];
            pts.split_whitespace().count() > min_points
        })
        .count()
}

#[test]
fn figure_writes_valid_png_and_svg_with_one_polyline_per_series() {
    let dir = test_dir("basic");
    let t = time(5000);
    let a: Vec<f64> = t.iter().map(|t| (2.0 * t).sin()).collect();
    let b: Vec<f64> = t.iter().map(|t| 0.5 * (3.0 * t).cos()).collect();
    let fig = Figure::new("Signal check").panel(
        Panel::new("s0", "time (s)", "s0 (mV)")
            .series(Series::line("before", t.clone(), a))
            .series(Series::line("after", t, b)),
    );
    let files = fig.save(&dir, "basic").unwrap();
    assert!(files.warnings.is_empty(), "{:?}", files.warnings);

    let img = check_png(&files.png, fig.pixel_size());
    // Both series are visible in their palette colours.
    assert!(count_pixels(&img, PALETTE[0]) > 500);
    assert!(count_pixels(&img, PALETTE[1]) > 500);

    let svg = std::fs::read_to_string(&files.svg).unwrap();
    assert!(svg.starts_with("<svg"));
    assert!(svg.contains("Signal check"), "figure title");
    assert!(svg.contains(">\ns0\n</text>"), "panel title");
    assert!(
        svg.contains("time (s)") && svg.contains("s0 (mV)"),
        "axis labels"
    );
    assert_eq!(polylines(&svg, PALETTE[0], 10), 1);
    assert_eq!(polylines(&svg, PALETTE[1], 10), 1);
    // Decimated: no more than 4 points per pixel column.
    assert!(svg.len() < 400_000, "SVG is {} bytes", svg.len());
}

#[test]
fn hostile_data_does_not_panic_and_is_reported() {
    let dir = test_dir("hostile");
    let t = time(1000);
    let mut nan: Vec<f64> = t.iter().map(|t| t.sin()).collect();
    for v in nan.iter_mut().step_by(7) {
        *v = f64::NAN;
    }
    nan[3] = f64::INFINITY;
    let fig = Figure::new("Hostile inputs")
        .share_x()
        .panel(
            Panel::new("empty", "time (s)", "y (g)").series(Series::line(
                "nothing",
                Vec::new(),
                Vec::new(),
            )),
        )
        .panel(Panel::new("no series at all", "time (s)", "y (g)"))
        .panel(
            Panel::new("constant", "time (s)", "y (g)").series(Series::line(
                "c",
                t.clone(),
                vec![3.25; 1000],
            )),
        )
        .panel(Panel::new("zero", "time (s)", "y (g)").series(Series::line(
            "z",
            t.clone(),
            vec![0.0; 1000],
        )))
        .panel(Panel::new("NaN", "time (s)", "y (g)").series(Series::line("gappy", t.clone(), nan)))
        .panel(
            Panel::new("all NaN", "time (s)", "y (g)").series(Series::points(
                "n",
                vec![f64::NAN; 3],
                vec![1.0; 3],
            )),
        )
        .panel(
            Panel::new("single point", "time (s)", "y (g)").series(Series::stems(
                "one",
                vec![1.0],
                vec![2.0],
            )),
        )
        .panel(
            Panel::new("huge values", "time (s)", "y (g)").series(Series::line(
                "big",
                vec![0.0, 1.0],
                vec![-f64::MAX, f64::MAX],
            )),
        )
        .panel(
            BarChart::new("bars with NaN", "rms (mV)", ["a", "b"]).group("g", vec![f64::NAN, 1.0]),
        )
        .panel(BarChart::new("no bars", "rms (mV)", Vec::<String>::new()))
        .panel(
            BarChart::new("negative bars", "change (mV)", ["a", "b"])
                .group("g", vec![-2.0, 1.0])
                .threshold(f64::NAN, "nan threshold"),
        );
    let files = fig.save(&dir, "hostile").unwrap();
    check_png(&files.png, fig.pixel_size());
    // A figure without panels is just its title.
    let bare = Figure::new("no panels");
    check_png(&bare.save(&dir, "bare").unwrap().png, bare.pixel_size());
    let w = files.warnings.join("\n");
    assert!(
        w.contains("\"gappy\": skipped 144 point(s) with NaN"),
        "{w}"
    );
    assert!(w.contains("\"n\": skipped 3 point(s)"), "{w}");
    assert!(w.contains("bars with NaN"), "{w}");
    // The gaps split the NaN series into many polylines rather than one.
    let svg = std::fs::read_to_string(&files.svg).unwrap();
    assert!(svg.contains("no data"));
}

#[test]
fn log_axes_with_zeros_and_negatives_skip_and_warn() {
    let dir = test_dir("log");
    let f: Vec<f64> = (0..=1250).map(|k| k as f64 * 0.02).collect(); // includes 0 Hz
    let mut psd: Vec<f64> = f.iter().map(|f| 1e-3 / (1.0 + f * f)).collect();
    psd[10] = 0.0;
    psd[11] = -1.0;
    let fig = Figure::new("Spectra")
        .panel(
            Panel::psd("s0", "PSD (V²/Hz)")
                .series(Series::line("before", f.clone(), psd))
                .ref_line(1e-6, "noise floor")
                .ref_line(0.0, "impossible floor"),
        )
        .panel(Panel::psd("all zero", "PSD (g²/Hz)").series(Series::line(
            "z",
            f.clone(),
            vec![0.0; f.len()],
        )))
        .panel(
            Panel::new("log band", "lag (samples)", "r (–)")
                .log_y()
                .band(0.03, "band")
                .series(Series::stems("r", vec![1.0, 2.0], vec![0.5, 0.0])),
        );
    let files = fig.save(&dir, "log").unwrap();
    check_png(&files.png, fig.pixel_size());
    let w = files.warnings.join("\n");
    // 0 Hz, the zero and the negative value.
    assert!(
        w.contains("\"before\": skipped 3 point(s) with a value ≤ 0 on a log axis"),
        "{w}"
    );
    assert!(w.contains("impossible floor"), "{w}");
    assert!(w.contains("\"z\": skipped 1251 point(s)"), "{w}");
    let svg = std::fs::read_to_string(&files.svg).unwrap();
    // The noise floor is drawn (dashed: many short segments in the reference colour).
    assert!(svg.contains(&hex(style::REFERENCE)));
    // Decade labels on the log axes.
    assert!(
        svg.contains(">10⁻") || svg.contains("0.001"),
        "log tick labels"
    );
}

#[test]
fn huge_series_is_decimated_and_keeps_its_spike() {
    let dir = test_dir("huge");
    let n = 500_000;
    let t = time(n);
    let mut y: Vec<f64> = t.iter().map(|t| 0.01 * (50.0 * t).sin()).collect();
    y[250_000] = 5.0;
    let fig = Figure::new("Long record")
        .panel(Panel::new("s0", "time (s)", "s0 (mV)").series(Series::line("s0", t, y)));
    let files = fig.save(&dir, "huge").unwrap();
    let svg = std::fs::read_to_string(&files.svg).unwrap();
    assert!(svg.len() < 300_000, "SVG is {} bytes", svg.len());
    let img = check_png(&files.png, fig.pixel_size());
    // The spike reaches the top of the plot: some series pixel sits in the
    // upper fifth of the panel.
    let (_, h) = img.dimensions();
    let top_series_pixel = img
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0 == [PALETTE[0].0, PALETTE[0].1, PALETTE[0].2])
        .map(|(_, y, _)| y)
        .min()
        .unwrap();
    assert!(
        top_series_pixel < h / 3,
        "spike drawn at row {top_series_pixel} of {h}"
    );
}

#[test]
fn scatter_and_correlation_and_bars_render() {
    let dir = test_dir("kinds");
    let x: Vec<f64> = (0..20_000)
        .map(|i| ((i * 37) % 1000) as f64 / 500.0 - 1.0)
        .collect();
    let y: Vec<f64> = x
        .iter()
        .map(|x| 0.4 * x * x + 0.05 * (x * 91.0).sin())
        .collect();
    let lags: Vec<f64> = (-25..=25).map(f64::from).collect();
    let r: Vec<f64> = lags
        .iter()
        .map(|&k: &f64| 0.3 * (-k.abs() / 3.0).exp())
        .collect();
    let fig = Figure::new("Analysis, sensor Z")
        .panel(
            Panel::new("Residual against v_sq", "v_sq (g²)", "residual (mV)")
                .series(Series::points("residual", x, y)),
        )
        .panel(Panel::correlation(
            "Cross-correlation with az",
            "lag (samples)",
            lags,
            r,
            1.96 / 5000f64.sqrt(),
        ))
        .panel(
            BarChart::ranked(
                "ERR",
                "ERR (–)",
                "ERR",
                [("v_sq", 0.31), ("v", 0.02), ("col:temp", 0.001)],
            )
            .threshold(0.01, "significance threshold"),
        );
    let files = fig.save(&dir, "kinds").unwrap();
    assert!(files.warnings.is_empty(), "{:?}", files.warnings);
    let img = check_png(&files.png, fig.pixel_size());
    assert!(count_pixels(&img, PALETTE[0]) > 1000);
    let svg = std::fs::read_to_string(&files.svg).unwrap();
    // Thinned scatter: far fewer circles than points.
    let circles = svg.matches("<circle").count();
    assert!(circles > 100 && circles < 20_000, "{circles} circles");
    for label in [
        "v_sq",
        "col:temp",
        "significance threshold",
        "95 % confidence band",
        "0.31",
    ] {
        assert!(svg.contains(label), "{label} missing from SVG");
    }
}

#[test]
fn shared_x_gives_panels_the_same_range() {
    let fig = Figure::new("shared")
        .share_x()
        .panel(Panel::new("a", "t (s)", "y (g)").series(Series::line(
            "a",
            vec![0.0, 10.0],
            vec![0.0, 1.0],
        )))
        .panel(Panel::new("b", "t (s)", "y (g)").series(Series::line(
            "b",
            vec![5.0, 100.0],
            vec![0.0, 1.0],
        )));
    let dir = test_dir("shared");
    let files = fig.save(&dir, "shared").unwrap();
    let svg = std::fs::read_to_string(&files.svg).unwrap();
    // The "100" tick appears in both panels' x axes.
    assert_eq!(svg.matches(">\n100\n</text>").count(), 2);
}

#[test]
fn unwritable_directory_is_an_io_error_with_the_path() {
    let dir = test_dir("unwritable");
    std::fs::create_dir_all(&dir).unwrap();
    let blocker = dir.join("file");
    std::fs::write(&blocker, "not a directory").unwrap();
    let err = Figure::new("t").save(blocker.join("sub"), "x").unwrap_err();
    match &err {
        ReportError::Io { path, .. } => assert_eq!(path, &blocker.join("sub")),
        other => panic!("expected Io, got {other:?}"),
    }
    assert!(err.to_string().contains("sub"));
}

#[test]
fn report_page_links_the_saved_figures() {
    let dir = test_dir("page");
    let files = Figure::new("Fig")
        .panel(
            Panel::new("s0", "time (s)", "s0 (mV)").series(Series::sampled(
                "s0",
                0.0,
                0.02,
                vec![f64::NAN, 1.0, 2.0],
            )),
        )
        .save(dir.join("figures"), "k0")
        .unwrap();
    let path = HtmlReport::new("Report <1>")
        .section(Section::new("Signals").figure(&files, "<script>alert('x')</script>"))
        .write(&dir)
        .unwrap();
    let html = std::fs::read_to_string(path).unwrap();
    assert!(html.contains("src=\"figures/k0.png\""));
    assert!(html.contains("href=\"figures/k0.svg\""));
    assert!(html.contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"));
    assert!(!html.contains("<script"));
    assert!(
        html.contains("skipped 1 point(s)"),
        "warnings shown under the figure"
    );
    assert!(
        html.contains("<details class=\"warnings\"><summary>1 drawing note(s)</summary>"),
        "folded, not a list between the figures"
    );
}

/// Renders a gallery of typical figures and prints the time of the 6-panel
/// figure. Set `REPORT_SAMPLE_DIR` to keep them somewhere to look at.
#[test]
fn sample_gallery() {
    let _cleanup;
    let dir = match std::env::var_os("REPORT_SAMPLE_DIR") {
        Some(d) => PathBuf::from(d),
        None => {
            _cleanup = test_dir("gallery");
            _cleanup.to_path_buf()
        }
    };
    let t = time(5000);
    let noise = |i: usize, s: u64| {
        // A cheap deterministic pseudo-noise in [-0.5, 0.5).
        let mut z = (i as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ s;
        z ^= z >> 29;
        z = z.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z ^= z >> 32;
        (z % 10_000) as f64 / 10_000.0 - 0.5
    };
    let az: Vec<f64> = (0..t.len())
        .map(|i| 3.0 * noise(i, 1) + 2.0 * (0.3 * t[i]).sin())
        .collect();
    let mut fig7 = Figure::new("Fig. 7 — signals with and without compensation").share_x();
    for k in 0..6 {
        let before: Vec<f64> = (0..t.len())
            .map(|i| 0.08 * az[i] * az[i] * (1.0 + 0.2 * k as f64) + 0.05 * noise(i, 10 + k))
            .collect();
        let after: Vec<f64> = (0..t.len()).map(|i| 0.06 * noise(i, 20 + k)).collect();
        fig7 = fig7.panel(
            Panel::new(format!("s{k}"), "time (s)", format!("s{k} (mV)"))
                .series(Series::line("without compensation", t.clone(), before).colour(1))
                .series(Series::line("with compensation", t.clone(), after).colour(0)),
        );
    }
    let start = std::time::Instant::now();
    let files = fig7.save(&dir, "fig7_signals").unwrap();
    let elapsed = start.elapsed();
    eprintln!(
        "6 panels × 2 series × 5000 points, PNG + SVG: {:.0} ms",
        elapsed.as_secs_f64() * 1e3
    );
    check_png(&files.png, fig7.pixel_size());

    let f: Vec<f64> = (0..=2500).map(|k| k as f64 * 0.01).collect();
    let before: Vec<f64> = f
        .iter()
        .map(|f| 2e-3 / (1.0 + (f / 3.0).powi(4)) + 4e-6 * (1.0 + noise((f * 100.0) as usize, 3)))
        .collect();
    let after: Vec<f64> = f
        .iter()
        .map(|f| 4e-6 * (1.0 + noise((f * 100.0) as usize, 4)) + 1e-5 / (1.0 + (f / 3.0).powi(4)))
        .collect();
    let psd = Figure::new("Signal spectra before and after compensation").panel(
        Panel::psd("s0", "PSD (V²/Hz)")
            .series(Series::line("before", f.clone(), before).colour(1))
            .series(Series::line("after", f, after).colour(0))
            .ref_line(4e-6, "noise floor"),
    );
    psd.save(&dir, "psd").unwrap();

    let n = 5000.0f64;
    let lags: Vec<f64> = (0..=40).map(f64::from).collect();
    let auto: Vec<f64> = lags
        .iter()
        .map(|&k| {
            if k == 0.0 {
                1.0
            } else {
                0.25 * 0.8f64.powf(k) + 0.01 * noise(k as usize, 5)
            }
        })
        .collect();
    let cross_lags: Vec<f64> = (-40..=40).map(f64::from).collect();
    let cross: Vec<f64> = cross_lags
        .iter()
        .map(|&k| 0.02 * noise((k + 40.0) as usize, 6))
        .collect();
    let corr = Figure::new("Correlation tests, sensor Z residual")
        .panel(Panel::correlation(
            "Autocorrelation φ_εε (fails: not white)",
            "lag (samples)",
            lags,
            auto,
            1.96 / n.sqrt(),
        ))
        .panel(Panel::correlation(
            "Cross-correlation φ_ε,az (passes)",
            "lag (samples)",
            cross_lags,
            cross,
            1.96 / n.sqrt(),
        ));
    corr.save(&dir, "correlation").unwrap();

    let err = Figure::new("Candidate effects for sensor Z").panel(
        BarChart::ranked(
            "Error-reduction ratio on the validation residual",
            "ERR (fraction of residual energy)",
            "ERR",
            [
                ("gg_II", 0.012),
                ("u_sq", 0.412),
                ("g_I", 0.004),
                ("g_O", 0.002),
                ("v", 0.031),
                ("gg_OO", 0.0015),
                ("v_sq", 0.0009),
                ("gg_IO", 0.0004),
                ("gg_OS", 0.0002),
                ("col:temp", 0.0001),
            ],
        )
        .threshold(0.01, "significance threshold"),
    );
    err.save(&dir, "err").unwrap();

    let sensors = ["A", "B", "C", "D", "E", "F"];
    let cmp = Figure::new("Adding u_sq to sensor Z")
        .panel(
            BarChart::new("Validation rms per sensor", "rms (mV)", sensors)
                .group_coloured(
                    "baseline",
                    vec![0.121, 0.118, 0.109, 0.131, 0.612, 0.115],
                    1,
                )
                .group_coloured(
                    "with u_sq on Z",
                    vec![0.121, 0.118, 0.109, 0.131, 0.124, 0.115],
                    0,
                ),
        )
        .panel(
            Panel::new("Sensor Z validation residual", "time (s)", "residual (mV)")
                .series(
                    Series::line(
                        "baseline",
                        t.clone(),
                        (0..t.len())
                            .map(|i| 0.5 * az[i] * 0.3 + 0.1 * noise(i, 7))
                            .collect::<Vec<_>>(),
                    )
                    .colour(1),
                )
                .series(
                    Series::line(
                        "with u_sq",
                        t.clone(),
                        (0..t.len()).map(|i| 0.1 * noise(i, 8)).collect::<Vec<_>>(),
                    )
                    .colour(0),
                ),
        );
    let cmp_files = cmp.save(&dir, "before_after").unwrap();

    // Fig. 6: target and network output on training and validation windows.
    let idx: Vec<f64> = (0..2500).map(f64::from).collect();
    let target: Vec<f64> = (0..2500)
        .map(|i| 0.3 * az[i] * az[i] / 9.0 + 0.05 * noise(i, 30))
        .collect();
    let output: Vec<f64> = (0..2500).map(|i| 0.3 * az[i] * az[i] / 9.0).collect();
    let fig6 = Figure::new("Fig. 6 — target and network output, sensor X")
        .panel(
            Panel::new("Training set", "window index (–)", "X error (mV)")
                .series(Series::line("target", idx.clone(), target.clone()).colour(6))
                .series(Series::line("network output", idx.clone(), output.clone()).colour(0)),
        )
        .panel(
            Panel::new("Validation set", "window index (–)", "X error (mV)")
                .series(Series::line("target", idx.clone(), target).colour(6))
                .series(Series::line("network output", idx, output).colour(0)),
        );
    let fig6_files = fig6.save(&dir, "fig6_network").unwrap();

    let index = HtmlReport::new("Sample report: shaker-table test")
        .summary("Signal rms fell 5.0-fold on the validation part of a blocked split.")
        .section(
            Section::new("Signals before and after")
                .table(
                    Table::new(["signal", "rms before (mV)", "rms after (mV)", "reduction"])
                        .caption("Validation part")
                        .row(["s0", "0.612", "0.118", "5.2×"])
                        .row(["s1", "0.580", "0.121", "4.8×"]),
                )
                .figure(&files, "Fig. 7: signals with and without compensation."),
        )
        .section(Section::new("Network").figure(&fig6_files, "Fig. 6: target and network output."))
        .section(
            Section::new("Analysis")
                .text("Sensor Z: u_sq is significant (ERR 0.41).")
                .code("mytool fit --data test.csv --add-effect Z=u_sq --out model.json")
                .figure(&cmp_files, "Before and after adding u_sq."),
        )
        .write(&dir)
        .unwrap();
    assert!(index.exists());
}

#[test]
fn x_span_shades_its_range_and_has_one_legend_entry_per_label() {
    let dir = test_dir("x_span");
    let t = time(1000);
    let y: Vec<f64> = t.iter().map(|t| t.sin()).collect();
    let plain = Figure::new("no span")
        .panel(Panel::new("p", "time (s)", "y (V)").series(Series::line("y", t.clone(), y.clone())))
        .save(&dir, "plain")
        .unwrap();
    let spanned = Figure::new("span")
        .panel(
            Panel::new("p", "time (s)", "y (V)")
                .series(Series::line("y", t, y))
                .x_span(0.0, 5.0, "training rows")
                .x_span(15.0, 18.0, "training rows"),
        )
        .save(&dir, "spanned")
        .unwrap();
    let grey = "#6E6E6E";
    let svg = std::fs::read_to_string(&spanned.svg).unwrap();
    assert!(svg.matches(grey).count() >= 3, "two spans and one swatch");
    assert_eq!(svg.matches("training rows").count(), 1, "one legend entry");
    assert!(!std::fs::read_to_string(&plain.svg).unwrap().contains(grey));
}

#[test]
fn a_short_panel_still_gets_at_least_four_y_labels() {
    // Six stacked panels of a tall figure leave about 150 px of plot each;
    // a range of 11 units must not fall back to steps of 5 (two labels).
    let y = crate::axis::Axis::new(13.5, 24.5, false, 150, crate::xy::Y_TICK_SPACING_PX);
    assert!(y.ticks.len() >= 4, "{:?}", y.ticks);
    let x = crate::axis::Axis::new(0.0, 100.0, false, 900, crate::xy::X_TICK_SPACING_PX);
    assert!(x.ticks.len() >= 6, "{:?}", x.ticks);
}
