//! 128-bit digests of the arrays a fit is a function of, for the fits
//! remembered within a process ([`super::channel_fits`], [`super::estimates`],
//! and a plug-in's own, such as a calibration): a key holds digests, not the
//! arrays.

use faer::MatRef;
use std::collections::VecDeque;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::sync::Mutex;

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

/// Values remembered by digest, at most `capacity` (the oldest dropped
/// first); a panic elsewhere while it was held leaves it usable (an entry
/// is pushed whole or not at all).
pub struct Store<T> {
    entries: Mutex<VecDeque<(Digest, T)>>,
    capacity: usize,
}

impl<T: Clone> Store<T> {
    /// An empty store of at most `capacity` values (usable as a `static`).
    pub const fn new(capacity: usize) -> Self {
        Self {
            entries: Mutex::new(VecDeque::new()),
            capacity,
        }
    }

    /// The value remembered under `key`, if any.
    pub fn recall(&self, key: Digest) -> Option<T> {
        self.lock()
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.clone())
    }

    /// Remembers `value` under `key` unless one is there already.
    pub fn keep(&self, key: Digest, value: &T) {
        let mut all = self.lock();
        if !all.iter().any(|(k, _)| *k == key) {
            if all.len() >= self.capacity {
                all.pop_front();
            }
            all.push_back((key, value.clone()));
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, VecDeque<(Digest, T)>> {
        self.entries
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
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
