//! Several targets' grids on one set of inputs, with the candidates' kernel
//! columns computed once per width and fold, give each target exactly the
//! grid it gets alone: the same picks, models and scores, bit for bit.

use faer::{Mat, Par};
use linfa::ParamGuard;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256Plus;
use rbf::{
    Candidates, CentreSelection, Grid, RbfParams, Sizes, Split, StreamPrecision, WidthRule,
    grid_search_each_with_linear, grid_search_with_linear,
};

#[test]
fn each_target_gets_its_own_grid_bit_for_bit() {
    let mut rng = Xoshiro256Plus::seed_from_u64(3);
    let (n, d, q) = (900, 12, 3);
    let x = Mat::from_fn(n, d, |_, _| rng.gen_range(-1.0f64..1.0));
    let y = Mat::from_fn(n, q, |i, t| {
        (x[(i, t)] * 3.0).sin() + x[(i, t + 1)].powi(2) + 0.05 * ((i * (t + 7)) % 11) as f64
    });
    let none = Mat::<f64>::zeros(n, 0);
    let z = Mat::from_fn(n, 1, |i, _| (i % 13) as f64);
    let grid = Grid {
        widths: vec![0.5, 1.0, 2.0]
            .into_iter()
            .map(|scale| WidthRule::MedianPairwise { scale })
            .collect(),
        sizes: Sizes::Centres(vec![2, 5, 10, 20, 30]),
        ridges: vec![],
    };
    let split = Split::Blocked { k: 3, gap: 12 };
    for stream in [StreamPrecision::F32, StreamPrecision::F64] {
        for z in [&none, &z] {
            let p = RbfParams::new()
                .centres(CentreSelection::Ols {
                    max_centres: 30,
                    tol: 0.0,
                    regularisation: 0.0,
                    candidates: Candidates::Subsample { size: 200 },
                })
                .ols_stream(stream)
                .seed(5)
                .parallelism(Par::Seq)
                .check()
                .unwrap();
            let each =
                grid_search_each_with_linear(&p, x.as_ref(), z.as_ref(), y.as_ref(), &split, &grid)
                    .unwrap();
            assert_eq!(each.len(), q);
            for (t, got) in each.iter().enumerate() {
                let alone = grid_search_with_linear(
                    &p,
                    x.as_ref(),
                    z.as_ref(),
                    y.as_ref().subcols(t, 1),
                    &split,
                    &grid,
                )
                .unwrap();
                assert_eq!(got.best, alone.best, "target {t}");
                assert_eq!(
                    format!("{:?}", got.points),
                    format!("{:?}", alone.points),
                    "target {t} {stream:?}"
                );
            }
        }
    }
}
