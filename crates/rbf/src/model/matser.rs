//! serde for faer matrices: `{"rows": r, "cols": c, "data": [[row 0], [row 1], ...]}`.

use faer::Mat;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

#[derive(Serialize, Deserialize)]
struct Repr {
    rows: usize,
    cols: usize,
    data: Vec<Vec<f64>>,
}

fn to_repr(m: &Mat<f64>) -> Repr {
    Repr {
        rows: m.nrows(),
        cols: m.ncols(),
        data: (0..m.nrows())
            .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
            .collect(),
    }
}

fn from_repr(r: Repr) -> Result<Mat<f64>, String> {
    if r.data.len() != r.rows || r.data.iter().any(|row| row.len() != r.cols) {
        return Err(format!(
            "matrix data does not have {}×{} entries",
            r.rows, r.cols
        ));
    }
    Ok(Mat::from_fn(r.rows, r.cols, |i, j| r.data[i][j]))
}

pub(crate) fn serialize<S: Serializer>(m: &Mat<f64>, s: S) -> Result<S::Ok, S::Error> {
    to_repr(m).serialize(s)
}

pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Mat<f64>, D::Error> {
    from_repr(Repr::deserialize(d)?).map_err(D::Error::custom)
}

pub(crate) mod option {
    use super::*;

    pub(crate) fn serialize<S: Serializer>(m: &Option<Mat<f64>>, s: S) -> Result<S::Ok, S::Error> {
        m.as_ref().map(to_repr).serialize(s)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<Mat<f64>>, D::Error> {
        Option::<Repr>::deserialize(d)?
            .map(from_repr)
            .transpose()
            .map_err(D::Error::custom)
    }
}
