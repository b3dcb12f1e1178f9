//! The evaluator against sums written out here, on small tables built
//! here: of the layout written now and of layout 2, read as it was.

use super::*;
use fastexp::exp_neg11;
use std::vec::Vec;

#[test]
fn exp_neg_is_within_four_ulps_of_the_c_library() {
    let mut x = 0.0f64;
    while x > -720.0 {
        let (got, want) = (exp_neg11(x), x.exp());
        let ulps = (got.to_bits() as i64 - want.to_bits() as i64).abs();
        assert!(
            ulps <= 4 || want < f64::MIN_POSITIVE * 16.0,
            "x = {x}: {got} vs {want}"
        );
        x -= 0.0123;
    }
    assert_eq!(exp_neg11(0.0), 1.0);
    assert_eq!(exp_neg11(-1000.0), 0.0);
}

/// Tables of six uncalibrated DTG channels on three accelerometers, the
/// window of L = 4 samples: layout `version`, `input`, `k` centres per
/// channel (channel c's centre i at 1 + ((7i + 3d + c) mod 5 − 2)/10 in
/// input number d, width 1 + i/k, weight (−1)ⁱ/(i + 1), bias c), channel c
/// on the signals of `masks[c]` (layout 2: every signal) among the
/// accelerometers `signals` (codes).
fn tables(version: u32, input: u32, k: usize, masks: [u32; 6], signals: &[u32]) -> Vec<u8> {
    let ns = signals.len();
    let mut words: Vec<u32> = Vec::from([u32::from_le_bytes(MAGIC), version, 0, 0, 0, 0, 0, 4]);
    words.push(ns as u32);
    if version != LAYOUT_2 {
        words.extend([6, 3]);
    }
    words.extend([0; 6]);
    words.extend([k as u32; 6]);
    if version != LAYOUT_2 {
        words.extend([gyro::DTG; 6]);
        words.extend(masks);
    }
    words.extend(signals);
    words.extend([input, 0]);
    if words.len() % 2 == 1 {
        words.push(0);
    }
    words[2] = words.len() as u32;
    let mut f: Vec<f64> = Vec::from([0.02]);
    if version != LAYOUT_2 {
        f.extend([1.0, 1.0]);
    }
    f.extend([0.0; 54 + 18]);
    if version != LAYOUT_2 {
        f.extend([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]);
    }
    let per = if input == input::STATISTICS { 3 } else { 4 };
    for (c, mask) in masks.iter().enumerate() {
        let dim = per * mask.count_ones() as usize;
        f.push(c as f64);
        f.extend((0..k).map(|i| 1.0 + i as f64 / k as f64));
        f.extend((0..k).map(|i| if i % 2 == 0 { 1.0 } else { -1.0 } / (i + 1) as f64));
        for i in 0..k {
            f.extend((0..dim).map(|d| 1.0 + (((7 * i + 3 * d + c) % 5) as f64 - 2.0) / 10.0));
        }
    }
    let mut b = Vec::new();
    for w in &words {
        b.extend(w.to_le_bytes());
    }
    for v in &f {
        b.extend(v.to_le_bytes());
    }
    b
}

/// Seeded accelerations (x, y, z) of `n` samples.
fn accels(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let t = i as f64;
            [
                0.3 * (0.7 * t).sin(),
                0.2 * (1.3 * t).cos(),
                1.0 + 0.25 * (0.45 * t).sin(),
            ]
        })
        .collect()
}

/// The tables' model by the direct sum (libm's exp) on the window ending
/// at sample `i` of `acc`: channel c's error.
fn direct(b: &[u8], acc: &[[f64; 3]], i: usize, c: usize) -> f64 {
    let m = Model::parse(b).unwrap();
    let at = |p: Part| m.floats(p).collect::<Vec<f64>>();
    let (widths, weights, centres) = (
        at(Part::Widths(c)),
        at(Part::Weights(c)),
        at(Part::Centres(c)),
    );
    let mut x = Vec::new();
    for s in 0..m.n_signals() {
        if m.signal_mask(c) & (1 << s) == 0 {
            continue;
        }
        let code = m.signal_code(s);
        let win: Vec<f64> = acc[i + 1 - m.window_len()..=i]
            .iter()
            .map(|a| a[code])
            .collect();
        if m.input_kind() == input::STATISTICS {
            let n = win.len() as f64;
            let mean = win.iter().sum::<f64>() / n;
            let var = win.iter().map(|v| v * v).sum::<f64>() / n - mean * mean;
            x.extend([win[win.len() - 1], mean, var.max(0.0).sqrt()]);
        } else {
            x.extend(win);
        }
    }
    let dim = x.len();
    at(Part::Bias(c))[0]
        + (0..widths.len())
            .map(|k| {
                let r2: f64 = (0..dim)
                    .map(|d| (x[d] - centres[k * dim + d]).powi(2))
                    .sum();
                weights[k] * (-r2 / (widths[k] * widths[k])).exp()
            })
            .sum::<f64>()
}

/// Every output of the evaluator on `acc`, twice (the second run after
/// the flush's reset), with the sample each belongs to.
fn run(b: &[u8], acc: &[[f64; 3]]) -> [Vec<(usize, Output)>; 2] {
    let m = Model::parse(b).unwrap();
    let mut state = std::vec![0.0; m.state_len()];
    let mut ev = Evaluator::new(m, &mut state).unwrap();
    core::array::from_fn(|_| {
        let mut outs = Vec::new();
        for (i, a) in acc.iter().enumerate() {
            if let Some(o) = ev.step(&[10.0; 6], a, &[]).unwrap() {
                outs.push((i - LOOKAHEAD, o));
            }
        }
        for (k, o) in ev.flush().into_iter().enumerate() {
            outs.extend(o.map(|o| (acc.len() + k - LOOKAHEAD, o)));
        }
        assert_eq!(ev.steps(), 0, "flush leaves the evaluator at rest");
        outs
    })
}

#[test]
fn each_refusal_has_its_error() {
    let good = doc_tables();
    let m = Model::parse(&good).unwrap();
    assert_eq!(m.size_bytes(), good.len());

    let mut bad = good;
    bad[0] = b'X';
    assert_eq!(Model::parse(&bad).unwrap_err(), Error::Magic);

    let mut bad = good;
    bad[4..8].copy_from_slice(&9u32.to_le_bytes());
    assert_eq!(
        Model::parse(&bad).unwrap_err(),
        Error::Version {
            found: 9,
            supported: VERSION
        }
    );
    assert_eq!(
        Model::parse(&good[..good.len() - 1]).unwrap_err(),
        Error::Truncated {
            need: good.len(),
            have: good.len() - 1
        }
    );
    // The signal code 3: no extra column.
    let code = FIXED_HEADER_WORDS + 24;
    let mut bad = good;
    bad[4 * code..4 * code + 4].copy_from_slice(&3u32.to_le_bytes());
    assert_eq!(
        Model::parse(&bad).unwrap_err(),
        Error::Header { word: code }
    );
    // Channel 2 on signal 1 of one: no such signal; on none.
    for mask in [2u32, 0] {
        let at = FIXED_HEADER_WORDS + 18 + 2;
        let mut bad = good;
        bad[4 * at..4 * at + 4].copy_from_slice(&mask.to_le_bytes());
        assert_eq!(Model::parse(&bad).unwrap_err(), Error::Header { word: at });
    }
    // 17 channels: more than the evaluator holds.
    let mut bad = good;
    bad[36..40].copy_from_slice(&17u32.to_le_bytes());
    assert_eq!(
        Model::parse(&bad).unwrap_err(),
        Error::TooMany {
            what: "channels",
            found: 17,
            max: MAX_CHANNELS
        }
    );
    let mut small = [0.0; 4];
    assert_eq!(
        Evaluator::new(m, &mut small).unwrap_err(),
        Error::StateTooSmall {
            need: m.state_len(),
            have: 4
        }
    );
    let mut state = [0.0; 256];
    let mut ev = Evaluator::new(m, &mut state).unwrap();
    assert_eq!(
        ev.step(&[0.0; 6], &[0.0; 3], &[1.0]).unwrap_err(),
        Error::Extra { need: 0, have: 1 }
    );
    assert_eq!(
        ev.step(&[0.0; 4], &[0.0; 3], &[]).unwrap_err(),
        Error::Sensors {
            what: "gyro outputs",
            need: 6,
            have: 4
        }
    );
}

#[test]
fn channels_with_the_same_signals_centres_and_widths_share_one_set() {
    let b = doc_tables();
    let m = Model::parse(&b).unwrap();
    assert!((0..6).all(|c| m.centre_set(c) == 0));
    // Channel Z (4) with another width has a set of its own.
    let mut other = b;
    let width_of_z = 4 * DOC_WORDS + 8 * (1 + 2 + 54 + 18 + 9 + 4 * 7 + 1);
    other[width_of_z..width_of_z + 8].copy_from_slice(&2.0f64.to_le_bytes());
    let m2 = Model::parse(&other).unwrap();
    let sets: Vec<usize> = (0..6).map(|c| m2.centre_set(c)).collect();
    assert_eq!(sets, [0, 0, 0, 0, 4, 0]);
    assert!(m2.flops_per_step() > m.flops_per_step());
    assert_eq!((m.exps_per_step(), m2.exps_per_step()), (LANES, 2 * LANES));
    // The same centres on other signals are another set.
    let t = tables(VERSION, input::STATISTICS, 3, [1, 1, 2, 1, 1, 1], &[0, 2]);
    let m3 = Model::parse(&t).unwrap();
    assert_eq!((m3.centre_set(1), m3.centre_set(2)), (1, 2));
}

#[test]
fn the_window_fills_then_every_step_gives_the_rbf_sum() {
    // doc_tables: bias c on channel c, one centre of four 1 g samples,
    // width 1 g, weight 0.5; no calibration, no filter.
    let b = doc_tables();
    let az = [1.0, 2.0, 1.0, 0.0, 1.0, 1.0];
    let acc: Vec<[f64; 3]> = az.iter().map(|a| [0.0, 0.0, *a]).collect();
    let [outs, again] = run(&b, &acc);
    assert_eq!(outs, again, "a flushed evaluator steps as a new one");
    assert_eq!(outs.len(), 3, "the first three samples fill the window");
    for (i, o) in &outs {
        // The window is the last four az samples, oldest first.
        let r2: f64 = az[i - 3..=*i].iter().map(|a| (a - 1.0) * (a - 1.0)).sum();
        for c in 0..6 {
            let want = c as f64 + 0.5 * exp_neg11(-r2);
            assert!((o.error_deg_h[c] - want).abs() < 1e-15, "{i} {c}");
            assert!((o.rate_deg_h[c] - (10.0 - want)).abs() < 1e-14);
        }
    }
}

#[test]
fn each_channel_reads_its_own_signals_on_either_input() {
    // 13 centres: one whole block of lanes and a part block; channels on
    // x, on z, on both, and on the three.
    let masks = [1, 4, 5, 7, 2, 7];
    let acc = accels(40);
    for input in [input::STATISTICS, input::RAW] {
        let b = tables(VERSION, input, 13, masks, &[0, 1, 2]);
        let m = Model::parse(&b).unwrap();
        let per = if input == input::STATISTICS { 3 } else { 4 };
        assert_eq!(m.input_dim(2), 2 * per);
        let [outs, again] = run(&b, &acc);
        assert_eq!(outs, again, "a flushed evaluator steps as a new one");
        for (i, o) in &outs {
            for c in 0..6 {
                let want = direct(&b, &acc, *i, c);
                let err = (o.error_deg_h[c] - want).abs();
                assert!(
                    err < 1e-13,
                    "input {input}, sample {i}, channel {c}: {err:e}"
                );
            }
        }
    }
}

#[test]
fn tables_of_layout_2_run_as_the_same_model_of_the_layout_written_now() {
    let acc = accels(30);
    for input in [input::STATISTICS, input::RAW] {
        let old = tables(LAYOUT_2, input, 11, [7; 6], &[0, 1, 2]);
        let new = tables(VERSION, input, 11, [7; 6], &[0, 1, 2]);
        assert_eq!(Model::parse(&old).unwrap().version(), LAYOUT_2);
        let (a, b) = (run(&old, &acc), run(&new, &acc));
        assert_eq!(a[0], b[0], "input {input}");
        for (i, o) in &a[0] {
            let want = direct(&old, &acc, *i, 3);
            assert!((o.error_deg_h[3] - want).abs() < 1e-13, "{i}");
        }
    }
}

/// The kernels at the CPU's vector width (vector.rs: AVX2 where the CPU
/// runs it) give the bits of the baseline build, on either input, with a
/// part block of lanes and channels of different signals. On a CPU without
/// AVX2 both calls take the baseline build.
#[test]
fn the_kernels_at_the_cpus_width_give_the_baseline_bits() {
    let masks = [1, 4, 5, 7, 2, 7];
    let acc = accels(40);
    for input in [input::STATISTICS, input::RAW] {
        let b = tables(VERSION, input, 21, masks, &[0, 1, 2]);
        let m = Model::parse(&b).unwrap();
        for n in [9, 17, 26, 40] {
            let mut state = std::vec![0.0; m.state_len()];
            {
                let mut ev = Evaluator::new(m, &mut state).unwrap();
                for a in &acc[..n] {
                    ev.step(&[0.0; 6], a, &[]).unwrap();
                }
            }
            // LOOKAHEAD samples are pending; the windows hold the n − 3
            // before them.
            let ring_pos = (n - crate::LOOKAHEAD) % m.window_len();
            let mut got = ([0.0; MAX_CHANNELS], [0.0; MAX_CHANNELS]);
            let mut want = got;
            crate::vector::network_terms(&m, &state, ring_pos, &mut got.0, &mut got.1);
            crate::kernels::network_terms(&m, &state, ring_pos, &mut want.0, &mut want.1);
            assert!(want.0[..6].iter().all(|v| *v != 0.0), "input {input}");
            let bits = |v: &[f64; MAX_CHANNELS]| v.map(f64::to_bits);
            assert_eq!(bits(&got.0), bits(&want.0), "input {input}, {n} samples");
            assert_eq!(bits(&got.1), bits(&want.1), "input {input}, {n} samples");
        }
    }
}
