//! A single self-contained `index.html`: headings, text, tables and figures.
//!
//! The page uses inline CSS only — no JavaScript, no fonts or stylesheets from
//! the network — so it opens the same from a CI artefact, an e-mail
//! attachment or an air-gapped lab machine. Every piece of text is
//! HTML-escaped: captions and table cells come from data (sensor names,
//! column names of a record) and must never become markup.

use std::fmt::Write as _;
use std::fs;
use std::path::{Component, Path, PathBuf};

use serde::Serialize;

use super::error::ReportError;
use super::figure::FigureFiles;

/// A table: a header row and rows of already-formatted cells.
///
/// Formatting numbers is left to the caller, who knows their precision and
/// units; cells that look like numbers are right-aligned so columns of
/// figures line up.
///
/// ```
/// use plot::Table;
/// let t = Table::new(["signal", "rms before (mV)", "rms after (mV)", "reduction"])
///     .row(["s0", "0.612", "0.118", "5.2×"])
///     .caption("Validation part of a blocked split");
/// assert_eq!(t.row_count(), 1);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Table {
    caption: Option<String>,
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column headings and no rows.
    ///
    /// ```
    /// use plot::Table;
    /// assert_eq!(Table::new(["a", "b"]).row_count(), 0);
    /// ```
    pub fn new(header: impl IntoIterator<Item = impl Into<String>>) -> Self {
        Table {
            caption: None,
            header: header.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    ///
    /// # Panics
    /// If the row does not have one cell per column.
    ///
    /// ```
    /// use plot::Table;
    /// let t = Table::new(["sensor", "rms (mV)"]).row(["X", &format!("{:.3}", 0.1234)]);
    /// assert_eq!(t.row_count(), 1);
    /// ```
    #[track_caller]
    pub fn row(mut self, cells: impl IntoIterator<Item = impl Into<String>>) -> Self {
        let cells: Vec<String> = cells.into_iter().map(Into::into).collect();
        assert_eq!(
            cells.len(),
            self.header.len(),
            "table row has {} cells but the header has {} columns",
            cells.len(),
            self.header.len()
        );
        self.rows.push(cells);
        self
    }

    /// A caption shown above the table.
    ///
    /// ```
    /// use plot::Table;
    /// let t = Table::new(["a"]).caption("Signal rms");
    /// # let _ = t;
    /// ```
    pub fn caption(mut self, text: impl Into<String>) -> Self {
        self.caption = Some(text.into());
        self
    }

    /// Number of data rows.
    ///
    /// ```
    /// # use plot::Table;
    /// assert_eq!(Table::new(["a"]).row(["1"]).row(["2"]).row_count(), 2);
    /// ```
    pub fn row_count(&self) -> usize {
        self.rows.len()
    }
}

/// A content block of a section, in order of appearance.
#[derive(Clone, Debug, PartialEq, Serialize)]
enum Block {
    Text(String),
    Code(String),
    Table(Table),
    Figure { files: FigureFiles, caption: String },
    Link { path: PathBuf, text: String },
}

/// A section of the report: a heading and blocks of text, tables and figures
/// in the order they were added.
///
/// ```
/// use plot::{Section, Table};
/// let s = Section::new("Signals before and after")
///     .text("Signal rms on the validation part.")
///     .table(Table::new(["signal", "rms (mV)"]).row(["s0", "0.118"]))
///     .code("mytool demo --out demo-out");
/// assert_eq!(s.heading(), "Signals before and after");
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Section {
    heading: String,
    blocks: Vec<Block>,
}

impl Section {
    /// An empty section with a heading.
    ///
    /// ```
    /// # use plot::Section;
    /// assert_eq!(Section::new("Analysis").heading(), "Analysis");
    /// ```
    pub fn new(heading: impl Into<String>) -> Self {
        Section {
            heading: heading.into(),
            blocks: Vec::new(),
        }
    }

    /// A paragraph of plain text (escaped; blank lines start new paragraphs).
    ///
    /// ```
    /// # use plot::Section;
    /// let s = Section::new("s").text("First.\n\nSecond.");
    /// # let _ = s;
    /// ```
    pub fn text(mut self, text: impl Into<String>) -> Self {
        self.blocks.push(Block::Text(text.into()));
        self
    }

    /// Preformatted text in a monospace box (a command line, a JSON excerpt).
    ///
    /// ```
    /// # use plot::Section;
    /// let s = Section::new("s").code("mytool analyse --model m.json --data d.csv");
    /// # let _ = s;
    /// ```
    pub fn code(mut self, text: impl Into<String>) -> Self {
        self.blocks.push(Block::Code(text.into()));
        self
    }

    /// A link to another file (another report page, a data file), made
    /// relative to the directory the page is written to, like figures.
    ///
    /// ```
    /// use plot::{HtmlReport, Section};
    /// let dir = std::path::Path::new("/out");
    /// let html = HtmlReport::new("r")
    ///     .section(Section::new("s").link("/out/other/index.html", "the other report"))
    ///     .to_html(dir);
    /// assert!(html.contains(r#"<a href="other/index.html">the other report</a>"#));
    /// ```
    pub fn link(mut self, path: impl Into<PathBuf>, text: impl Into<String>) -> Self {
        self.blocks.push(Block::Link {
            path: path.into(),
            text: text.into(),
        });
        self
    }

    /// A table.
    ///
    /// ```
    /// # use plot::{Section, Table};
    /// let s = Section::new("s").table(Table::new(["a"]).row(["1"]));
    /// # let _ = s;
    /// ```
    pub fn table(mut self, table: Table) -> Self {
        self.blocks.push(Block::Table(table));
        self
    }

    /// A saved figure: its PNG inline, a link to the SVG, the caption, and
    /// the figure's drawing warnings (if any) in small print under it.
    ///
    /// Save figures inside the report directory (or a sub-directory) so the
    /// links are relative and the directory can be moved as a whole.
    ///
    /// ```
    /// use plot::{Figure, Panel, Section, Series};
    /// let dir = std::env::temp_dir().join("plot-doc");
    /// let files = Figure::new("Fig. 5")
    ///     .panel(Panel::new("az", "time (s)", "az (g)").series(Series::sampled("az", 0.0, 0.02, vec![0.1, 0.3, -0.2])))
    ///     .save(&dir, "fig5")?;
    /// let s = Section::new("Pre-processing").figure(&files, "Fig. 5: processed acceleration and rate.");
    /// # let _ = s;
    /// # Ok::<(), plot::ReportError>(())
    /// ```
    pub fn figure(mut self, files: &FigureFiles, caption: impl Into<String>) -> Self {
        self.blocks.push(Block::Figure {
            files: files.clone(),
            caption: caption.into(),
        });
        self
    }

    /// The heading.
    ///
    /// ```
    /// # use plot::Section;
    /// assert_eq!(Section::new("h").heading(), "h");
    /// ```
    pub fn heading(&self) -> &str {
        &self.heading
    }
}

/// The report page: a title, summary paragraphs, then sections, with a table
/// of contents when there is more than one section.
///
/// ```
/// use plot::{Figure, HtmlReport, Panel, Section, Series, Table};
///
/// let dir = std::env::temp_dir().join("plot-doc-report");
/// let t: Vec<f64> = (0..500).map(|i| i as f64 * 0.02).collect();
/// let k0: Vec<f64> = t.iter().map(|t| (3.0 * t).sin()).collect();
/// let fig = Figure::new("Signal s0")
///     .panel(Panel::new("s0", "time (s)", "s0 (mV)").series(Series::line("s0", t, k0)))
///     .save(&dir, "k0")?;
/// let path = HtmlReport::new("shaker-table test")
///     .summary("Signal rms fell 5.2-fold on the validation part.")
///     .section(
///         Section::new("Signals")
///             .table(Table::new(["signal", "before (mV)", "after (mV)"]).row(["s0", "0.612", "0.118"]))
///             .figure(&fig, "Signal s0 over the record."),
///     )
///     .write(&dir)?;
/// let html = std::fs::read_to_string(&path)?;
/// assert!(html.contains(r#"<img src="k0.png""#));
/// assert!(html.contains(r#"href="k0.svg""#));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HtmlReport {
    title: String,
    summary: Vec<String>,
    sections: Vec<Section>,
}

impl HtmlReport {
    /// An empty report with a title.
    ///
    /// ```
    /// # use plot::HtmlReport;
    /// let r = HtmlReport::new("Analysis of model.json");
    /// # let _ = r;
    /// ```
    pub fn new(title: impl Into<String>) -> Self {
        HtmlReport {
            title: title.into(),
            summary: Vec::new(),
            sections: Vec::new(),
        }
    }

    /// A summary paragraph under the title (the numbers a reader wants first).
    ///
    /// ```
    /// # use plot::HtmlReport;
    /// let r = HtmlReport::new("r").summary("Suggested effect for Z: u_sq (ERR 0.41).");
    /// # let _ = r;
    /// ```
    pub fn summary(mut self, paragraph: impl Into<String>) -> Self {
        self.summary.push(paragraph.into());
        self
    }

    /// Appends a section.
    ///
    /// ```
    /// # use plot::{HtmlReport, Section};
    /// let r = HtmlReport::new("r").section(Section::new("Fit"));
    /// # let _ = r;
    /// ```
    pub fn section(mut self, section: Section) -> Self {
        self.sections.push(section);
        self
    }

    /// The page as a string; figure paths are made relative to `dir`, the
    /// directory the page will be written to.
    ///
    /// ```
    /// use plot::{HtmlReport, Section};
    /// let html = HtmlReport::new("A <b>bold</b> claim")
    ///     .section(Section::new("x").text("1 < 2 & 3 > 2"))
    ///     .to_html(std::path::Path::new("."));
    /// assert!(html.contains("A &lt;b&gt;bold&lt;/b&gt; claim"));
    /// assert!(html.contains("1 &lt; 2 &amp; 3 &gt; 2"));
    /// ```
    pub fn to_html(&self, dir: &Path) -> String {
        let mut h = String::with_capacity(16 * 1024);
        let title = escape(&self.title);
        let _ = write!(
            h,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
             <title>{title}</title>\n<style>\n{CSS}</style>\n</head>\n<body>\n<main>\n<h1>{title}</h1>\n"
        );
        for p in &self.summary {
            paragraphs(&mut h, p, "summary");
        }
        if self.sections.len() > 1 {
            h.push_str("<nav>\n<h2>Contents</h2>\n<ol>\n");
            for (i, s) in self.sections.iter().enumerate() {
                let _ = writeln!(
                    h,
                    "<li><a href=\"#s{}\">{}</a></li>",
                    i + 1,
                    escape(&s.heading)
                );
            }
            h.push_str("</ol>\n</nav>\n");
        }
        for (i, s) in self.sections.iter().enumerate() {
            let _ = writeln!(
                h,
                "<section id=\"s{}\">\n<h2>{}</h2>",
                i + 1,
                escape(&s.heading)
            );
            for block in &s.blocks {
                match block {
                    Block::Text(t) => paragraphs(&mut h, t, ""),
                    Block::Code(t) => {
                        let _ = writeln!(h, "<pre><code>{}</code></pre>", escape(t));
                    }
                    Block::Table(t) => table(&mut h, t),
                    Block::Figure { files, caption } => figure(&mut h, files, caption, dir),
                    Block::Link { path, text } => {
                        let _ = writeln!(
                            h,
                            "<p class=\"link\"><a href=\"{}\">{}</a></p>",
                            href(path, dir),
                            escape(text)
                        );
                    }
                }
            }
            h.push_str("</section>\n");
        }
        h.push_str("</main>\n</body>\n</html>\n");
        h
    }

    /// Writes `dir/index.html` (creating `dir` if needed) and returns its path.
    ///
    /// ```
    /// use plot::HtmlReport;
    /// let path = HtmlReport::new("Empty report").write(std::env::temp_dir().join("plot-doc-empty"))?;
    /// assert!(path.ends_with("index.html"));
    /// # Ok::<(), plot::ReportError>(())
    /// ```
    pub fn write(&self, dir: impl AsRef<Path>) -> Result<PathBuf, ReportError> {
        let dir = dir.as_ref();
        fs::create_dir_all(dir).map_err(|source| ReportError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        let path = dir.join("index.html");
        outfile::write_bytes(&path, self.to_html(dir)).map_err(|source| ReportError::Io {
            path: path.clone(),
            source,
        })?;
        Ok(path)
    }
}

/// Escapes text for HTML content and for double- or single-quoted attributes.
///
/// ```
/// use plot::escape_html;
/// assert_eq!(escape_html(r#"<script>alert("x")</script> & 'y'"#),
///            "&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &#39;y&#39;");
/// ```
pub fn escape_html(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + text.len() / 8);
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

fn escape(text: &str) -> String {
    escape_html(text)
}

/// Paragraphs from text: blank lines separate paragraphs.
fn paragraphs(h: &mut String, text: &str, class: &str) {
    let class_attr = if class.is_empty() {
        String::new()
    } else {
        format!(" class=\"{class}\"")
    };
    for p in text.split("\n\n").map(str::trim).filter(|p| !p.is_empty()) {
        let _ = writeln!(h, "<p{class_attr}>{}</p>", escape(p));
    }
}

fn table(h: &mut String, t: &Table) {
    h.push_str("<div class=\"table\"><table>\n");
    if let Some(c) = &t.caption {
        let _ = writeln!(h, "<caption>{}</caption>", escape(c));
    }
    h.push_str("<thead><tr>");
    for c in &t.header {
        let _ = write!(h, "<th>{}</th>", escape(c));
    }
    h.push_str("</tr></thead>\n<tbody>\n");
    for row in &t.rows {
        h.push_str("<tr>");
        for c in row {
            if looks_numeric(c) {
                let _ = write!(h, "<td class=\"num\">{}</td>", escape(c));
            } else if c.chars().count() > LONG_CELL {
                let _ = write!(h, "<td class=\"long\">{}</td>", escape(c));
            } else {
                let _ = write!(h, "<td>{}</td>", escape(c));
            }
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody>\n</table></div>\n");
}

/// A cell longer than this many characters is prose (an effect with its
/// interval, a file path): it gets a column wide enough to read as a
/// paragraph (`td.long`), and a narrow screen scrolls the table sideways
/// inside its box rather than breaking it into a letter per line.
const LONG_CELL: usize = 24;

/// A number, possibly signed, with an exponent, a percent sign or a "×"
/// suffix: right-aligned in tables.
fn looks_numeric(cell: &str) -> bool {
    let s = cell.trim().trim_end_matches(['%', '×', 'x']).trim();
    !s.is_empty() && (s.parse::<f64>().is_ok() || s == "n/a")
}

fn figure(h: &mut String, files: &FigureFiles, caption: &str, dir: &Path) {
    let png = href(&files.png, dir);
    let svg = href(&files.svg, dir);
    let alt = escape(caption);
    // On a phone the figure laid out for its width, whose text stays
    // legible; elsewhere the full-width one.
    let narrow = files.narrow_png.as_ref().map_or(String::new(), |n| {
        format!(
            "<source media=\"(max-width: {NARROW_SCREEN}px)\" srcset=\"{}\">",
            href(n, dir)
        )
    });
    let _ = write!(
        h,
        "<figure>\n<a href=\"{svg}\"><picture>{narrow}<img src=\"{png}\" alt=\"{alt}\" loading=\"lazy\"></picture></a>\n\
         <figcaption>{alt} <a class=\"svg\" href=\"{svg}\">SVG</a></figcaption>\n"
    );
    if !files.warnings.is_empty() {
        // Folded: what was left out of a figure is there for whoever asks,
        // without a list of lines between the figures.
        let _ = writeln!(
            h,
            "<details class=\"warnings\"><summary>{} drawing note(s)</summary>",
            files.warnings.len()
        );
        h.push_str("<ul class=\"warnings\">\n");
        for w in &files.warnings {
            let _ = writeln!(h, "<li>{}</li>", escape(w));
        }
        h.push_str("</ul></details>\n");
    }
    h.push_str("</figure>\n");
}

/// Widest screen (CSS px) that gets a figure's phone rendering.
const NARROW_SCREEN: u32 = 600;

/// A relative, percent-encoded, HTML-escaped link from the page in `dir` to
/// `path`: the way from the page's directory to the file, so that it
/// resolves when the page is opened, wherever the report was written and
/// whatever directory the command ran in.
fn href(path: &Path, dir: &Path) -> String {
    let encode = |parts: &[std::ffi::OsString]| -> Vec<String> {
        parts
            .iter()
            .filter(|c| !Path::new(c).has_root())
            .map(|c| {
                if c == ".." {
                    "..".to_string()
                } else {
                    percent_encode(&c.to_string_lossy())
                }
            })
            .collect()
    };
    match relative_path(path, dir) {
        Some(rel) => escape(&encode(&rel).join("/")),
        // No way from one to the other (another drive, or no current
        // directory to place a relative path in): the file's own URL.
        None => {
            let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
            escape(&format!("file:///{}", encode(&lexical(&abs)).join("/")))
        }
    }
}

/// The components of the path from directory `dir` to `path`, both placed
/// in the current directory when relative, `.` and `..` resolved lexically
/// (a report links files it wrote by the paths it wrote them to, so no
/// symbolic link lies between the two that the lexical way would miss).
///
/// `None` when the two share no root (different drives) or a relative one
/// cannot be placed (no current directory).
fn relative_path(path: &Path, dir: &Path) -> Option<Vec<std::ffi::OsString>> {
    let (path, dir) = if path.is_absolute() && dir.is_absolute() {
        (lexical(path), lexical(dir))
    } else {
        (
            lexical(&std::path::absolute(path).ok()?),
            lexical(&std::path::absolute(dir).ok()?),
        )
    };
    let common = path.iter().zip(&dir).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return None;
    }
    let up = std::iter::repeat_n(std::ffi::OsString::from(".."), dir.len() - common);
    Some(up.chain(path[common..].iter().cloned()).collect())
}

/// The components of absolute path `p` (its prefix and root first) with `.`
/// dropped and each `..` taking back the component before it (`/..` is `/`).
fn lexical(p: &Path) -> Vec<std::ffi::OsString> {
    let mut out: Vec<std::ffi::OsString> = Vec::new();
    for c in p.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if out
                    .last()
                    .is_some_and(|l| !Path::new(l).has_root() && l != "..")
                {
                    out.pop();
                } else if out.is_empty() {
                    out.push("..".into());
                }
            }
            c => out.push(c.as_os_str().to_os_string()),
        }
    }
    out
}

fn percent_encode(part: &str) -> String {
    let mut out = String::with_capacity(part.len());
    for b in part.bytes() {
        match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' => {
                out.push(b as char)
            }
            _ => {
                let _ = write!(out, "%{b:02X}");
            }
        }
    }
    out
}

/// Readable on screen and in print, without any external resource.
const CSS: &str = "\
body { margin: 0; background: #fafafa; color: #1e1e1e;
       font: 16px/1.5 system-ui, -apple-system, 'Segoe UI', 'DejaVu Sans', sans-serif; }
main { max-width: 1160px; margin: 0 auto; padding: 1.5rem 2rem 4rem; background: #fff; }
h1 { font-size: 1.7rem; margin: 0.5rem 0 1rem; }
h2 { font-size: 1.3rem; margin-top: 2.5rem; border-bottom: 1px solid #ddd; padding-bottom: 0.2rem; }
p.summary { font-size: 1.05rem; }
nav ol { columns: 2; }
pre { background: #f3f3f3; padding: 0.6rem 0.8rem; overflow-x: auto; border-radius: 4px; }
code { font-family: ui-monospace, 'DejaVu Sans Mono', monospace; font-size: 0.92rem; }
div.table { overflow-x: auto; margin: 1rem 0; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; }
caption { text-align: left; font-weight: 600; padding-bottom: 0.3rem; }
th, td { padding: 0.25rem 0.7rem; border-bottom: 1px solid #e3e3e3; text-align: left; }
th { background: #f0f0f0; }
td.num { text-align: right; }
figure { margin: 1.5rem 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #e3e3e3; }
figcaption { font-size: 0.95rem; color: #333; }
a.svg { font-size: 0.85rem; margin-left: 0.4rem; }
details.warnings { font-size: 0.85rem; color: #8a4b00; margin: 0.3rem 0 0; }
ul.warnings { margin: 0.2rem 0 0; }
img, svg, video { max-width: 100%; height: auto; }
th { overflow-wrap: break-word; }
td { overflow-wrap: anywhere; }
td.num { white-space: nowrap; }
td.long { min-width: 16em; overflow-wrap: break-word; }
p, li, figcaption, caption { overflow-wrap: anywhere; }
caption { position: sticky; left: 0; max-width: calc(100vw - 2rem); }
@media (max-width: 600px) {
  main { padding: 0.8rem 0.7rem 3rem; }
  h1 { font-size: 1.35rem; }
  nav ol { columns: 1; }
  th, td { padding: 0.2rem 0.35rem; font-size: 0.85rem; }
  td.long { min-width: 13em; }
  /* A table wider than the screen scrolls inside its box with its first
     column (the row's name) kept in view. */
  th:first-child, td:first-child { position: sticky; left: 0; z-index: 1;
       background: #fff; box-shadow: 1px 0 0 #e3e3e3; }
  th:first-child { background: #f0f0f0; min-width: 4.5em; }
  td:first-child { min-width: 4.5em; }
  /* Scroll shadows: a shade at the edge that has more table behind it. */
  div.table {
    background:
      linear-gradient(to left, #fff 30%, rgba(255,255,255,0)) right / 40px 100% no-repeat local,
      radial-gradient(farthest-side at 100% 50%, rgba(0,0,0,0.25), rgba(0,0,0,0)) right / 14px 100% no-repeat scroll;
  }
}
@media print { body { background: #fff; } main { padding: 0; } a.svg { display: none; } }
";

#[cfg(test)]
mod tests {
    use super::*;

    fn files(dir: &Path, stem: &str) -> FigureFiles {
        FigureFiles {
            png: dir.join(format!("{stem}.png")),
            svg: dir.join(format!("{stem}.svg")),
            narrow_png: Some(dir.join(format!("{stem}.narrow.png"))),
            warnings: vec!["panel \"<s0>\": skipped 1 point".to_string()],
        }
    }

    #[test]
    fn script_in_caption_title_and_cells_comes_out_escaped() {
        let dir = Path::new("/tmp/r");
        let html = HtmlReport::new("<script>alert(1)</script>")
            .summary("<script>alert(2)</script>")
            .section(
                Section::new("<script>")
                    .text("<script>alert(3)</script>")
                    .code("</code><script>")
                    .table(
                        Table::new(["<th>"])
                            .row(["<script>alert(4)</script>"])
                            .caption("<i>"),
                    )
                    .figure(
                        &files(dir, "fig"),
                        "<script>alert(5)</script>\" onerror=\"x",
                    ),
            )
            .to_html(dir);
        assert!(!html.contains("<script"), "{html}");
        assert!(!html.contains("\" onerror"), "attribute injection: {html}");
        assert!(html.contains("&lt;script&gt;alert(5)&lt;/script&gt;"));
        assert!(html.contains("&lt;s0&gt;"));
        // Self-contained: no external resources, no JavaScript.
        assert!(!html.contains("http://") && !html.contains("https://"));
        assert!(!html.contains("<link") && !html.contains("javascript:"));
    }

    #[test]
    fn figure_links_are_relative_and_encoded() {
        let dir = Path::new("/tmp/r");
        let html = HtmlReport::new("t")
            .section(Section::new("s").figure(&files(&dir.join("figs"), "s0 before&after"), "c"))
            .to_html(dir);
        assert!(
            html.contains("src=\"figs/s0%20before%26after.png\""),
            "{html}"
        );
        assert!(html.contains("href=\"figs/s0%20before%26after.svg\""));
        // A phone gets the figure laid out for its width.
        assert!(
            html.contains(
                "<source media=\"(max-width: 600px)\" srcset=\"figs/s0%20before%26after.narrow.png\">"
            ),
            "{html}"
        );
        // Outside the page's directory: the way there and down again.
        let outside = href(Path::new("/elsewhere/a b.png"), dir);
        assert_eq!(outside, "../../elsewhere/a%20b.png");
    }

    #[test]
    fn links_go_from_the_page_to_the_file_wherever_both_are() {
        let h = |p: &str, d: &str| href(Path::new(p), Path::new(d));
        // The demo's final page linking its sibling reports, paths as the
        // command gave them (relative to where it ran, not to the page).
        assert_eq!(
            h(
                "demo-out/baseline/report/index.html",
                "demo-out/final/report"
            ),
            "../../baseline/report/index.html"
        );
        assert_eq!(
            h(
                "demo-out/final/diagnosis/index.html",
                "demo-out/final/report"
            ),
            "../diagnosis/index.html"
        );
        assert_eq!(
            h("demo-out/final/report/fig.png", "demo-out"),
            "final/report/fig.png"
        );
        assert_eq!(h("./out/./a/../b.png", "out"), "b.png");
        assert_eq!(h("/x/y/z.png", "/x/y"), "z.png");
        assert_eq!(h("/x/y/z.png", "/x/y/"), "z.png");
        assert_eq!(h("/a/b", "/c/d"), "../../a/b");
        // One relative, one absolute: both placed in the current directory.
        let cwd = std::env::current_dir().unwrap();
        let abs = cwd.join("r").join("p.png");
        assert_eq!(href(&abs, Path::new("r")), "p.png");
        assert_eq!(href(Path::new("r/p.png"), &cwd.join("r")), "p.png");
        // From `../o` to `q/p.png` the way climbs out of `o` and back into
        // the current directory by its name.
        let here = cwd.file_name().unwrap().to_string_lossy().into_owned();
        assert_eq!(
            h("q/p.png", "../o"),
            format!("../{}/q/p.png", percent_encode(&here))
        );
    }

    #[test]
    fn numeric_cells_are_right_aligned() {
        assert!(looks_numeric("-1.5e-3"));
        assert!(looks_numeric("5.2×"));
        assert!(looks_numeric("12 %"));
        assert!(!looks_numeric("u_sq"));
        assert!(!looks_numeric(""));
    }

    #[test]
    #[should_panic(expected = "table row has 1 cells but the header has 2 columns")]
    fn short_row_panics() {
        let _ = Table::new(["a", "b"]).row(["1"]);
    }

    #[test]
    fn contents_only_with_several_sections() {
        let one = HtmlReport::new("t")
            .section(Section::new("a"))
            .to_html(Path::new("."));
        assert!(!one.contains("<nav>"));
        let two = HtmlReport::new("t")
            .section(Section::new("a"))
            .section(Section::new("b"))
            .to_html(Path::new("."));
        assert!(two.contains("<nav>") && two.contains("href=\"#s2\""));
    }
}
