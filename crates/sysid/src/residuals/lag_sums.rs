//! Σ_t x_t·x_{t+k} for many lags k at once.
//!
//! The correlation tests sum a series' lagged products for hundreds of lags
//! (a Bartlett sum reads up to 500 of them at each of ten τ, for every
//! channel and operating signal); one lag at a time, each sum is a chain of
//! dependent additions that waits on the adder's latency. Here four lags
//! run side by side over the same samples: each sum still adds its terms
//! in time order from the empty sum, as `Iterator::sum` does, so every
//! value is the one the one-lag loop gives, bit for bit (the test below).

/// `out[k] = Σ_{t < n−k} x[t]·x[t+k]` for `k` in `0..out.len()` (terms added
/// in time order); lags at or beyond `x.len()` get the empty sum.
pub(crate) fn lag_sums_into(x: &[f64], out: &mut [f64]) {
    let n = x.len();
    let empty: f64 = std::iter::empty::<f64>().sum();
    let mut k0 = 0;
    while k0 + 4 <= out.len() && k0 + 3 < n {
        let mut s = [empty; 4];
        // Every t at which all four lags have a term…
        let common = n - (k0 + 3);
        for t in 0..common {
            let a = x[t];
            let w = &x[t + k0..t + k0 + 4];
            s[0] += a * w[0];
            s[1] += a * w[1];
            s[2] += a * w[2];
            s[3] += a * w[3];
        }
        // …then the later terms of the shorter lags, still in time order.
        for (j, sj) in s.iter_mut().enumerate().take(3) {
            for t in common..n - (k0 + j) {
                *sj += x[t] * x[t + k0 + j];
            }
        }
        out[k0..k0 + 4].copy_from_slice(&s);
        k0 += 4;
    }
    for (k, o) in out.iter_mut().enumerate().skip(k0) {
        *o = match k < n {
            true => x[..n - k].iter().zip(&x[k..]).map(|(a, b)| a * b).sum(),
            false => empty,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sums are the one-lag loop's, bit for bit, at every lag, for
    /// lengths around the blocks of four.
    #[test]
    fn four_lags_at_once_give_the_one_lag_sums() {
        let mut s = 7u64;
        let mut next = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for n in [0, 1, 2, 3, 4, 5, 7, 8, 9, 64, 1001] {
            let x: Vec<f64> = (0..n).map(|_| next() * 1e3).collect();
            for lags in [1, 3, 4, 5, 8, 13, n, n + 6] {
                let mut out = vec![f64::NAN; lags];
                lag_sums_into(&x, &mut out);
                for (k, &got) in out.iter().enumerate() {
                    let want: f64 = match k < n {
                        true => x[..n - k].iter().zip(&x[k..]).map(|(a, b)| a * b).sum(),
                        false => std::iter::empty::<f64>().sum(),
                    };
                    assert_eq!(got.to_bits(), want.to_bits(), "n {n} lag {k}");
                }
            }
        }
    }
}
