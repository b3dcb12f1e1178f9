//! Where candidate columns live while the engine refreshes some of them.
//!
//! A refreshed column (deflated in place, see the module docs) replaces the stored one.
//! A borrowed candidate matrix is never written: at its first refresh it is copied once
//! (so a [`crate::forward_select`] run that needs refreshing holds two candidate
//! matrices); an owned matrix ([`crate::forward_select_owned`]) is overwritten column by
//! column, which keeps the peak memory at one candidate matrix (the large-N case).

use faer::{Mat, MatRef};

pub(crate) enum Store<'a> {
    Borrowed(MatRef<'a, f64>),
    Owned(Mat<f64>),
}

impl Store<'_> {
    /// The whole candidate matrix, for the streaming products.
    pub(crate) fn mat(&self) -> MatRef<'_, f64> {
        match self {
            Store::Borrowed(m) => *m,
            Store::Owned(m) => m.as_ref(),
        }
    }

    /// Overwrites column `j`, copying a borrowed matrix first.
    pub(crate) fn replace(&mut self, j: usize, data: &[f64]) {
        if let Store::Borrowed(m) = self {
            *self = Store::Owned(m.to_owned());
        }
        let Store::Owned(m) = self else {
            unreachable!("made owned above")
        };
        m.col_as_slice_mut(j).copy_from_slice(data);
    }
}
