//! 128-bit digests of the arrays a fit is a function of, for the fits
//! remembered within a process ([`super::channel_fits`], [`super::estimates`],
//! and a plug-in's own, such as a calibration): a key holds digests, not the
//! arrays.

use faer::MatRef;
use std::hash::{DefaultHasher, Hash, Hasher};

/// A 128-bit digest: two SipHashes of the same words, salted apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Digest(u64, u64);

/// Words added one at a time, digested by [`Digester::finish`].
pub struct Digester(DefaultHasher, DefaultHasher);

impl Default for Digester {
    fn default() -> Self {
        Self::new()
    }
}

impl Digester {
    /// An empty digest.
    pub fn new() -> Self {
        let mut second = DefaultHasher::new();
        0x9e37_79b9_7f4a_7c15_u64.hash(&mut second);
        Self(DefaultHasher::new(), second)
    }

    /// Adds one word.
    pub fn word(&mut self, w: u64) {
        self.0.write_u64(w);
        self.1.write_u64(w);
    }

    /// Adds numbers by their bits (−0 and 0 apart), then their count.
    pub fn f64s(&mut self, v: impl Iterator<Item = f64>) {
        let mut n = 0u64;
        for x in v {
            self.word(x.to_bits());
            n += 1;
        }
        self.word(n);
    }

    /// Adds indices, then their count.
    pub fn usizes(&mut self, v: &[usize]) {
        v.iter().for_each(|&r| self.word(r as u64));
        self.word(v.len() as u64);
    }

    /// Adds a text.
    pub fn text(&mut self, s: &str) {
        s.hash(&mut self.0);
        s.hash(&mut self.1);
    }

    /// Adds a matrix's shape and entries, row by row.
    pub fn matrix(&mut self, m: MatRef<'_, f64>) {
        self.word(m.nrows() as u64);
        self.word(m.ncols() as u64);
        for i in 0..m.nrows() {
            self.f64s((0..m.ncols()).map(|j| m[(i, j)]));
        }
    }

    /// The digest of everything added so far.
    pub fn finish(&self) -> Digest {
        Digest(self.0.finish(), self.1.finish())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn digests_tell_arrays_apart() {
        let digest = |v: &[f64]| {
            let mut d = Digester::new();
            d.f64s(v.iter().copied());
            d.finish()
        };
        assert_eq!(digest(&[1.0, 2.0]), digest(&[1.0, 2.0]));
        assert_ne!(digest(&[1.0, 2.0]), digest(&[2.0, 1.0]));
        assert_ne!(digest(&[0.0]), digest(&[-0.0]));
        assert_ne!(digest(&[1.0]), digest(&[1.0, 1.0]));
    }
}
