//! The strip above each panel: the panel title on the left, the legend on the
//! right, wrapping onto more lines when it does not fit.
//!
//! A legend inside the plot (plotters' default) sits on top of the data it
//! explains, and with six stacked signals there is no corner that is always
//! empty; a strip above the plot never hides anything.

use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind};
use plotters::element::{Circle, DashedPathElement, PathElement, Rectangle};
use plotters::prelude::DrawingBackend;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, RGBColor};

use super::style::{self, INK, LEGEND_SIZE, PANEL_TITLE_SIZE};

/// How a legend entry is marked; mirrors how its item is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Swatch {
    Line(RGBColor),
    Dot(RGBColor),
    Stem(RGBColor),
    /// A filled box (bars, bands), with opacity.
    Fill(RGBColor, f64),
    Dashed(RGBColor),
    Dotted(RGBColor),
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    pub swatch: Swatch,
    pub label: String,
}

/// A header laid out for a given width: where each entry goes.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Header {
    title: String,
    /// (entry, x of its swatch, row)
    placed: Vec<(Entry, i32, u32)>,
    rows: u32,
}

/// Left padding of the title.
const PAD: i32 = 10;
/// Right padding of the legend: the plot's right margin, so the legend ends
/// where the plot does.
const PAD_RIGHT: i32 = super::xy::MARGIN_RIGHT as i32;
const ROW_H: u32 = 28;
const SWATCH_W: i32 = 26;
const SWATCH_GAP: i32 = 6;
const ENTRY_GAP: i32 = 20;

impl Header {
    /// Places the title and legend in `width` pixels: entries go right of the
    /// title while they fit, the rest on extra rows, right-aligned.
    pub fn layout(title: &str, entries: Vec<Entry>, width: u32) -> Header {
        let width = width as i32;
        let title_w = style::text_size(title, PANEL_TITLE_SIZE).0 as i32;
        let entry_w =
            |e: &Entry| SWATCH_W + SWATCH_GAP + style::text_size(&e.label, LEGEND_SIZE).0 as i32;
        // Greedy fill of rows; row 0 shares its width with the title.
        let mut rows: Vec<Vec<(Entry, i32)>> = vec![Vec::new()];
        let mut used = 0;
        for e in entries {
            let w = entry_w(&e);
            let budget = if rows.len() == 1 {
                width - PAD - PAD_RIGHT - title_w - 2 * ENTRY_GAP
            } else {
                width - PAD - PAD_RIGHT
            };
            let need = if used == 0 { w } else { used + ENTRY_GAP + w };
            // A new row, unless this is already an empty full-width row (then
            // the label is simply too long and overflows on its own row).
            if need > budget && !(rows.len() > 1 && used == 0) {
                rows.push(Vec::new());
                used = 0;
            }
            used = if used == 0 { w } else { used + ENTRY_GAP + w };
            rows.last_mut().expect("at least one row").push((e, w));
        }
        let mut placed = Vec::new();
        for (r, row) in rows.iter().enumerate() {
            let total: i32 =
                row.iter().map(|(_, w)| w).sum::<i32>() + ENTRY_GAP * (row.len() as i32 - 1).max(0);
            let mut x = (width - PAD_RIGHT - total).max(PAD);
            for (e, w) in row {
                placed.push((e.clone(), x, r as u32));
                x += w + ENTRY_GAP;
            }
        }
        let rows = rows.len() as u32;
        Header {
            title: title.to_string(),
            placed,
            rows,
        }
    }

    /// Height of the strip in pixels.
    pub fn height(&self) -> u32 {
        self.rows * ROW_H + 4
    }

    /// Draws the strip into `area` (which is `height()` tall).
    pub fn draw<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let mid = |row: u32| (row * ROW_H + ROW_H / 2 + 2) as i32;
        let left_mid = Pos::new(HPos::Left, VPos::Center);
        area.draw_text(
            &self.title,
            &style::text(PANEL_TITLE_SIZE, INK).pos(left_mid),
            (PAD, mid(0)),
        )?;
        for (entry, x, row) in &self.placed {
            let y = mid(*row);
            draw_swatch(area, entry.swatch, *x, y)?;
            area.draw_text(
                &entry.label,
                &style::text(LEGEND_SIZE, INK).pos(left_mid),
                (x + SWATCH_W + SWATCH_GAP, y),
            )?;
        }
        Ok(())
    }
}

fn draw_swatch<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    swatch: Swatch,
    x: i32,
    y: i32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (x0, x1) = (x, x + SWATCH_W);
    match swatch {
        Swatch::Line(c) => area.draw(&PathElement::new(vec![(x0, y), (x1, y)], c.stroke_width(3))),
        Swatch::Dot(c) => area.draw(&Circle::new(((x0 + x1) / 2, y), 4, c.filled())),
        Swatch::Stem(c) => {
            area.draw(&PathElement::new(
                vec![((x0 + x1) / 2, y + 8), ((x0 + x1) / 2, y - 5)],
                c.stroke_width(2),
            ))?;
            area.draw(&Circle::new(((x0 + x1) / 2, y - 5), 3, c.filled()))
        }
        Swatch::Fill(c, alpha) => area.draw(&Rectangle::new(
            [(x0, y - 7), (x1, y + 7)],
            c.mix(alpha).filled(),
        )),
        Swatch::Dashed(c) => area.draw(&DashedPathElement::new(
            vec![(x0, y), (x1, y)],
            6,
            4,
            c.stroke_width(2),
        )),
        Swatch::Dotted(c) => area.draw(&DashedPathElement::new(
            vec![(x0, y), (x1, y)],
            super::xy::DOT,
            super::xy::DOT_GAP,
            c.stroke_width(2),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(label: &str) -> Entry {
        Entry {
            swatch: Swatch::Line(INK),
            label: label.to_string(),
        }
    }

    #[test]
    fn short_legend_shares_the_title_row() {
        style::ensure_font().unwrap();
        let h = Header::layout("s0", vec![entry("before"), entry("after")], 1000);
        assert_eq!(h.rows, 1);
        assert!(h.placed.iter().all(|p| p.2 == 0));
        // Right-aligned, and clear of the title.
        assert!(h.placed[0].1 > 100);
    }

    #[test]
    fn long_legend_wraps() {
        style::ensure_font().unwrap();
        let entries: Vec<Entry> = (0..12)
            .map(|i| entry(&format!("a rather long legend label {i}")))
            .collect();
        let h = Header::layout("Title", entries, 800);
        assert!(h.rows >= 3, "rows {}", h.rows);
        assert!(
            h.placed.iter().all(|p| p.1 >= 0),
            "nothing starts left of the strip"
        );
        assert!(h.height() > 3 * ROW_H);
    }
}
