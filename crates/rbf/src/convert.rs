//! Zero-copy conversions between faer and ndarray (ndarray only at the linfa boundary).

use faer::MatRef;
use ndarray::{ArrayBase, ArrayView2, CowArray, Data, Ix1, Ix2, ShapeBuilder};

/// A faer view of a 2-D ndarray (any strides, no copy).
///
/// ```
/// let a = ndarray::array![[1.0, 2.0], [3.0, 4.0]];
/// let m = rbf::convert::mat_from_array(&a);
/// assert_eq!(m[(1, 0)], 3.0);
/// let t = a.t();
/// assert_eq!(rbf::convert::mat_from_array(&t)[(1, 0)], 2.0);
/// ```
pub fn mat_from_array<S: Data<Elem = f64>>(a: &ArrayBase<S, Ix2>) -> MatRef<'_, f64> {
    let (n, d) = a.dim();
    let s = a.strides();
    // SAFETY: `a` is borrowed for the lifetime of the view; ndarray guarantees that
    // ptr + i·s0 + j·s1 is in bounds for i < n, j < d, and faer accepts any strides.
    unsafe { MatRef::from_raw_parts(a.as_ptr(), n, d, s[0], s[1]) }
}

/// A faer n × 1 view of a 1-D ndarray (no copy).
///
/// ```
/// let a = ndarray::array![1.0, 2.0, 3.0];
/// let m = rbf::convert::mat_from_array1(&a);
/// assert_eq!((m.nrows(), m.ncols(), m[(2, 0)]), (3, 1, 3.0));
/// ```
pub fn mat_from_array1<S: Data<Elem = f64>>(a: &ArrayBase<S, Ix1>) -> MatRef<'_, f64> {
    let n = a.len();
    let s = a.strides();
    // SAFETY: as in `mat_from_array`; the single column has stride 0 which is never used
    // to step since there is one column.
    unsafe { MatRef::from_raw_parts(a.as_ptr(), n, 1, s[0], 0) }
}

/// An ndarray view of a faer matrix when its strides are non-negative (the usual
/// case), otherwise an owned copy.
///
/// ```
/// let m = faer::mat![[1.0, 2.0], [3.0, 4.0]];
/// let a = rbf::convert::as_array(m.as_ref());
/// assert_eq!(a[[1, 0]], 3.0);
/// let r = rbf::convert::as_array(m.as_ref().reverse_rows());
/// assert_eq!(r[[0, 0]], 3.0);
/// ```
pub fn as_array(m: MatRef<'_, f64>) -> CowArray<'_, f64, Ix2> {
    let (n, d) = (m.nrows(), m.ncols());
    let (rs, cs) = (m.row_stride(), m.col_stride());
    if rs >= 0 && cs >= 0 && n > 0 && d > 0 {
        // SAFETY: `m` is borrowed for the view's lifetime; the strides are non-negative
        // and address exactly the n × d elements of `m`.
        let v = unsafe {
            ArrayView2::from_shape_ptr((n, d).strides((rs as usize, cs as usize)), m.as_ptr())
        };
        CowArray::from(v)
    } else {
        CowArray::from(ndarray::Array2::from_shape_fn((n, d), |(i, j)| m[(i, j)]))
    }
}
