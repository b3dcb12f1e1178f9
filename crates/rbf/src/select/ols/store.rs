//! Where candidate columns live while the engine refreshes some of them.
//!
//! A refreshed column (deflated in place, see the module docs) replaces the stored one.
//! A borrowed candidate matrix is never written: refreshed columns go to an overlay, so a
//! run that refreshes every column costs one extra copy. An owned matrix
//! ([`crate::forward_select_owned`]) is overwritten column by column instead, which keeps
//! the peak memory at one candidate matrix (the large-N case).

use faer::{Mat, MatRef};

pub(crate) enum Store<'a> {
    Borrowed {
        base: MatRef<'a, f64>,
        overlay: Vec<Option<Box<[f64]>>>,
    },
    Owned(Mat<f64>),
}

impl<'a> Store<'a> {
    /// A borrowed store; a view without unit row stride is copied once (columns must be
    /// contiguous for the streaming kernel).
    pub(crate) fn borrowed(base: MatRef<'a, f64>) -> Self {
        if base.row_stride() == 1 {
            Store::Borrowed {
                base,
                overlay: vec![None; base.ncols()],
            }
        } else {
            Store::Owned(base.to_owned())
        }
    }

    #[inline]
    pub(crate) fn col(&self, j: usize) -> &[f64] {
        match self {
            Store::Borrowed { base, overlay } => match &overlay[j] {
                Some(c) => c,
                // Unit row stride was checked in `borrowed`.
                None => base
                    .col(j)
                    .try_as_col_major()
                    .expect("unit row stride")
                    .as_slice(),
            },
            Store::Owned(m) => m.col_as_slice(j),
        }
    }

    pub(crate) fn replace(&mut self, j: usize, data: &[f64]) {
        match self {
            Store::Borrowed { overlay, .. } => match &mut overlay[j] {
                Some(c) => c.copy_from_slice(data),
                slot @ None => *slot = Some(data.into()),
            },
            Store::Owned(m) => m.col_as_slice_mut(j).copy_from_slice(data),
        }
    }
}
