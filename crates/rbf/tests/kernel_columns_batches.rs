//! A candidate kernel column comes out bit for bit the same whichever other
//! columns it is generated with: one at a time, in the OLS engine's blocks,
//! in contender batches, or all at once as a matrix. The engine regenerates
//! columns in all of these ways during one selection, and a store of the
//! columns computed once (shared by several selections on the same inputs)
//! gives the same picks only because of this.

use faer::{Mat, Par};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256Plus;
use rbf::{CandidateColumns, Kernel, KernelColumns, Widths, kernel_matrix};

fn random(n: usize, d: usize, offset: f64, seed: u64) -> Mat<f64> {
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    Mat::from_fn(n, d, |_, _| offset + rng.gen_range(-1.0..1.0))
}

#[test]
fn a_column_is_the_same_in_any_batch() {
    for &(n, m, d) in &[
        (1650, 400, 50),
        (2400, 400, 3),
        (700, 300, 150),
        (5000, 90, 1),
    ] {
        let x = random(n, d, 3.0, 1);
        let c = random(m, d, 3.0, 2);
        let w = Widths::Uniform(0.9 * (d as f64).sqrt());
        for par in [Par::Seq, Par::rayon(2)] {
            let cols = KernelColumns::new(x.as_ref(), c.as_ref(), Kernel::Gaussian, &w, par);
            let all: Vec<usize> = (0..m).collect();
            let mut whole = Mat::zeros(n, m);
            cols.columns_into(&all, whole.as_mut());
            let matrix = kernel_matrix(x.as_ref(), c.as_ref(), Kernel::Gaussian, &w, par);
            for batch in [1usize, 3, 8, 32, 257] {
                // Batches in order, and batches of scattered columns.
                let scattered: Vec<usize> = (0..m).map(|j| (j * 7919) % m).collect();
                for order in [&all, &scattered] {
                    for js in order.chunks(batch) {
                        let mut out = Mat::zeros(n, js.len());
                        cols.columns_into(js, out.as_mut());
                        for (k, &j) in js.iter().enumerate() {
                            for i in 0..n {
                                assert_eq!(
                                    out[(i, k)].to_bits(),
                                    whole[(i, j)].to_bits(),
                                    "n {n} d {d} batch {batch} column {j} row {i}"
                                );
                            }
                        }
                    }
                }
            }
            // The kernel matrix shifts by the same centres' mean: the same bits.
            for j in 0..m {
                for i in 0..n {
                    assert_eq!(matrix[(i, j)].to_bits(), whole[(i, j)].to_bits());
                }
            }
        }
    }
}
