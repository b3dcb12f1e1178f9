//! The step harnesses' inputs (harness.rs, harness.c and the step bench
//! take the same): 100 samples from an LCG seeded with 7, per sample each
//! gyro in −15 … 15 deg/h, each accelerometer in −0.3 … 0.3 g (+1 g on
//! every third).

/// Samples in the cycle.
pub const PER: usize = 100;

/// The samples of `n_g` gyros and `n_a` accelerometers.
pub fn inputs(n_g: usize, n_a: usize) -> Vec<(Vec<f64>, Vec<f64>)> {
    let mut seed: u64 = 7;
    let mut next = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
        (seed >> 11) as f64 / 9007199254740992.0
    };
    (0..PER)
        .map(|_| {
            let g = (0..n_g).map(|_| 30.0 * next() - 15.0).collect();
            let a = (0..n_a)
                .map(|k| f64::from(u8::from(k % 3 == 2)) + 0.6 * next() - 0.3)
                .collect();
            (g, a)
        })
        .collect()
}
