//! The memory-bandwidth bound of one OLS pick, for `peers/scripts/run.sh`.
//!
//! An OLS pick streams the N × M candidates once, like one matrix–vector product. This
//! times faer's products vᵀP (one row) and [q r]ᵀP (two rows) over the f64 Gaussian
//! kernel matrix of the training rows of a peer data file, and one read of an f32 copy
//! of it (what the library's default engine streams: the bytes bound of its pick), and
//! prints the medians as one JSON line.
//!
//! ```sh
//! cargo run --release -p rbf-cli --example stream_bound -- DATA.csv BETA
//! ```

use std::time::Instant;

use anyhow::{Context, Result};
use rbf::faer::linalg::matmul::matmul;
use rbf::faer::{Accum, Mat};
use rbf::{Kernel, Widths, kernel_matrix};
use rbf_cli::data;

fn median_seconds(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[reps / 2]
}

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let (path, beta) = (args.next(), args.next());
    let (Some(path), Some(beta)) = (path, beta) else {
        anyhow::bail!("usage: stream_bound DATA.csv BETA");
    };
    let beta: f64 = beta.parse().context("BETA")?;
    let table = tabular::Table::read(&path)?;
    let rows = data::split_by_column(&table, "split")?;
    let inputs = data::input_columns(&table, "y", None, &["split"])?;
    let x = data::take_rows(data::numeric_matrix(&table, &inputs)?.as_ref(), &rows.train);
    // RBF_THREADS=1 measures one core, as `rbf --threads 1` fits on one.
    if let Ok(t) = std::env::var("RBF_THREADS") {
        let t: usize = t.parse::<usize>().context("RBF_THREADS")?.max(1);
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build_global();
        rbf::faer::set_global_parallelism(if t <= 1 {
            rbf::Par::Seq
        } else {
            rbf::Par::rayon(t)
        });
    }
    let par = rbf::faer::get_global_parallelism();
    let p = kernel_matrix(
        x.as_ref(),
        x.as_ref(),
        Kernel::Gaussian,
        &Widths::Uniform(beta),
        par,
    );
    let n = p.nrows();
    // The small factor as an s × n faer matrix, laid out as the library's engine
    // builds it.
    let v = Mat::from_fn(1, n, |_, i| (i as f64).sin());
    let v2 = Mat::from_fn(2, n, |j, i| ((i + j) as f64).sin());
    let mut out1 = Mat::zeros(1, p.ncols());
    let mut out2 = Mat::zeros(2, p.ncols());
    let one = median_seconds(31, || {
        matmul(
            out1.as_mut(),
            Accum::Replace,
            v.as_ref(),
            p.as_ref(),
            1.0,
            par,
        )
    });
    let two = median_seconds(31, || {
        matmul(
            out2.as_mut(),
            Accum::Replace,
            v2.as_ref(),
            p.as_ref(),
            1.0,
            par,
        )
    });
    let gbps = (n * p.ncols() * 8) as f64 / one / 1e9;
    // One read of an f32 copy, column by column, summed in f64 (as the engine does):
    // split between the threads like the engine's pass.
    let p32: Vec<f32> = (0..p.ncols())
        .flat_map(|j| (0..n).map(move |i| (j, i)))
        .map(|(j, i)| p[(i, j)] as f32)
        .collect();
    let mut sums = vec![0.0f64; p.ncols()];
    let threads = par.degree().max(1);
    let read32 = median_seconds(31, || {
        use rayon::prelude::*;
        let per = p.ncols().div_ceil(threads * 4).max(1);
        sums.par_chunks_mut(per).enumerate().for_each(|(c, out)| {
            for (k, o) in out.iter_mut().enumerate() {
                let col = &p32[(c * per + k) * n..(c * per + k + 1) * n];
                let mut acc = [0.0f64; 8];
                for chunk in col.chunks_exact(8) {
                    for l in 0..8 {
                        acc[l] += f64::from(chunk[l]);
                    }
                }
                *o = acc.iter().sum::<f64>();
            }
        });
    });
    std::hint::black_box(&sums);
    println!(
        "{{\"side\":\"rust\",\"method\":\"matvec\",\"threads\":{},\"n\":{n},\"m\":{},\"seconds\":{one},\"seconds_2row\":{two},\"gb_per_s\":{gbps},\"seconds_read_f32\":{read32}}}",
        par.degree(),
        p.ncols()
    );
    Ok(())
}
