//! Reducing long series to what a pixel grid can show.
//!
//! A 100 s record at 50 Hz is 5000 samples, a long one 500 000; a panel is
//! about 1000 pixels wide. Drawing every sample makes SVG files of tens of
//! megabytes and slow PNGs without changing a single pixel, while naive
//! subsampling (every k-th sample) loses exactly the spikes a shaker
//! engineer is looking for. M4 decimation keeps, for each pixel column, the
//! first, minimum, maximum and last sample, which draws the same picture as
//! the full series (Jugel et al., "M4: a visualization-oriented time series
//! data aggregation", VLDB 2014).

/// Decimates a line for drawing `columns` pixels wide, keeping in every pixel
/// column the first, lowest, highest and last point (M4), in their original
/// order, so that peaks and the global minimum and maximum survive.
///
/// Points with a non-finite coordinate are skipped. `x` is expected to be
/// non-decreasing (a sampled signal); if it is not, only consecutive points
/// that fall in the same column are merged, so nothing is reordered and every
/// extreme is still kept, there is just less reduction. Series of at most
/// `4 · columns` points are returned whole.
///
/// # Panics
/// If `x` and `y` differ in length (a programmer error).
///
/// ```
/// use plot::decimate_m4;
///
/// let x: Vec<f64> = (0..100_000).map(|i| i as f64 * 0.02).collect();
/// let mut y: Vec<f64> = x.iter().map(|t| (t * 3.0).sin()).collect();
/// y[54_321] = 40.0; // a single-sample spike
/// let d = decimate_m4(&x, &y, 1000);
/// assert!(d.len() <= 4000);
/// assert!(d.iter().any(|&(_, v)| v == 40.0));
/// ```
#[track_caller]
pub fn decimate_m4(x: &[f64], y: &[f64], columns: usize) -> Vec<(f64, f64)> {
    assert_eq!(
        x.len(),
        y.len(),
        "decimate_m4: x has {} values but y has {}",
        x.len(),
        y.len()
    );
    let points: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(&a, &b)| (a, b))
        .collect();
    m4(&points, columns)
}

/// M4 over finite points (the drawing code has already split the series at
/// NaNs and log-axis exclusions, and works in plot space).
pub(crate) fn m4(points: &[(f64, f64)], columns: usize) -> Vec<(f64, f64)> {
    let columns = columns.max(1);
    if points.len() <= 4 * columns {
        return points.to_vec();
    }
    let (x0, x1) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
    let width = x1 - x0;
    let column_of = |x: f64| -> usize {
        if width > 0.0 && width.is_finite() {
            (((x - x0) / width) * columns as f64)
                .floor()
                .clamp(0.0, (columns - 1) as f64) as usize
        } else {
            0
        }
    };

    let mut out = Vec::with_capacity(4 * columns + 4);
    // Indices of the first, min, max and last point of the current run.
    let mut run: Option<(usize, [usize; 4])> = None;
    let flush = |out: &mut Vec<(f64, f64)>, idx: [usize; 4]| {
        let mut idx = idx;
        idx.sort_unstable();
        let mut prev = usize::MAX;
        for i in idx {
            if i != prev {
                out.push(points[i]);
                prev = i;
            }
        }
    };
    for (i, p) in points.iter().enumerate() {
        let c = column_of(p.0);
        match &mut run {
            Some((col, idx)) if *col == c => {
                if p.1 < points[idx[1]].1 {
                    idx[1] = i;
                }
                if p.1 > points[idx[2]].1 {
                    idx[2] = i;
                }
                idx[3] = i;
            }
            _ => {
                if let Some((_, idx)) = run {
                    flush(&mut out, idx);
                }
                run = Some((c, [i; 4]));
            }
        }
    }
    if let Some((_, idx)) = run {
        flush(&mut out, idx);
    }
    out
}

/// Thins a scatter to at most one point per pixel cell of a `w × h` grid over
/// the given plot-space ranges, keeping the first point of each cell: a dense
/// cloud looks the same, with far fewer SVG elements.
pub(crate) fn thin_points(
    points: &[(f64, f64)],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    (w, h): (usize, usize),
) -> Vec<(f64, f64)> {
    let (w, h) = (w.max(1), h.max(1));
    if points.len() <= 2 * w.min(h) {
        return points.to_vec();
    }
    let cell = |v: f64, lo: f64, hi: f64, n: usize| -> usize {
        let span = hi - lo;
        if span > 0.0 && span.is_finite() {
            (((v - lo) / span) * n as f64)
                .floor()
                .clamp(0.0, (n - 1) as f64) as usize
        } else {
            0
        }
    };
    let mut seen = vec![false; w * h];
    points
        .iter()
        .copied()
        .filter(|&(x, y)| {
            let k = cell(y, y0, y1, h) * w + cell(x, x0, x1, w);
            !std::mem::replace(&mut seen[k], true)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spiky(n: usize) -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..n).map(|i| i as f64 / 50.0).collect();
        let y: Vec<f64> = (0..n)
            .map(|i| ((i * 7919) % 1000) as f64 / 1000.0 - 0.5)
            .collect();
        (x, y)
    }

    #[test]
    fn keeps_global_extremes_of_a_spiky_series() {
        let (x, mut y) = spiky(500_000);
        y[123_457] = 1.0e3; // one-sample spikes, far from column edges
        y[400_001] = -2.0e3;
        let d = decimate_m4(&x, &y, 800);
        assert!(d.len() <= 4 * 800, "{} points", d.len());
        let max = d.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        let min = d.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert_eq!(max, 1.0e3);
        assert_eq!(min, -2.0e3);
        // The spike keeps its time too.
        assert!(d.contains(&(x[123_457], 1.0e3)));
        // And the ends of the record survive.
        assert_eq!(d.first().copied(), Some((x[0], y[0])));
        assert_eq!(d.last().copied(), Some((x[499_999], y[499_999])));
    }

    #[test]
    fn keeps_every_column_extreme_and_order() {
        let (x, y) = spiky(20_000);
        let d = decimate_m4(&x, &y, 100);
        assert!(d.windows(2).all(|w| w[0].0 <= w[1].0), "order kept");
        // Each column's max is present.
        let width = x[x.len() - 1] - x[0];
        for c in 0..100 {
            let in_col = |t: f64| ((t - x[0]) / width * 100.0).floor().min(99.0) as usize == c;
            let col_max = x
                .iter()
                .zip(&y)
                .filter(|(t, _)| in_col(**t))
                .map(|(_, v)| *v)
                .fold(f64::NEG_INFINITY, f64::max);
            assert!(
                d.iter().any(|p| in_col(p.0) && p.1 == col_max),
                "column {c}"
            );
        }
    }

    #[test]
    fn short_nan_constant_and_empty_inputs() {
        assert!(decimate_m4(&[], &[], 10).is_empty());
        let d = decimate_m4(&[0.0, 1.0, 2.0], &[1.0, f64::NAN, 3.0], 10);
        assert_eq!(d, vec![(0.0, 1.0), (2.0, 3.0)]);
        // Constant x (zero width) and zero columns do not divide by zero.
        let x = vec![1.0; 1000];
        let y: Vec<f64> = (0..1000).map(|i| i as f64).collect();
        let d = decimate_m4(&x, &y, 0);
        assert_eq!(d, vec![(1.0, 0.0), (1.0, 999.0)]);
    }

    #[test]
    #[should_panic(expected = "x has 2 values but y has 1")]
    fn mismatched_lengths_panic() {
        decimate_m4(&[0.0, 1.0], &[0.0], 10);
    }

    #[test]
    fn thinning_keeps_one_point_per_cell() {
        let pts: Vec<(f64, f64)> = (0..10_000).map(|i| ((i % 100) as f64, 0.0)).collect();
        let t = thin_points(&pts, (0.0, 99.0), (-1.0, 1.0), (100, 10));
        assert_eq!(t.len(), 100);
    }
}
