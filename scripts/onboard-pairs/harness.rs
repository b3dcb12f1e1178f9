//! One onboard step timed, or counted: the `dtg-onboard` evaluator of the
//! checkout this is built against (scripts/onboard-pairs.sh builds it once
//! against the baseline's crate and once against the current one) over the
//! tables `model.dtgo` given, on the same seeded inputs as `harness.c`.
//!
//!     harness TABLES [STEPS]
//!
//! (inputs.rs beside it: the baseline's copy is examples/onboard_harness/.)
//!
//! Without STEPS: the median ns per step of 1001 batches of 100 steps (a
//! batch short against the scheduler's time slice). With STEPS: that many
//! steps and nothing printed but a checksum (for `valgrind --tool=callgrind`).

#[path = "inputs.rs"]
mod inputs;

use dtg_onboard::{Evaluator, Model};
use inputs::{PER, inputs};
use std::hint::black_box;
use std::time::Instant;

const BATCHES: usize = 1001;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[1]).expect("the tables");
    let m = Model::parse(&bytes).expect("tables this evaluator reads");
    let data = inputs(m.n_channels(), m.n_accels());
    let extra = vec![0.0; m.n_extra()];
    let mut state = vec![0.0; m.state_len()];
    let mut ev = Evaluator::new(m, &mut state).expect("state");
    let mut sink = 0.0;
    for (g, a) in &data {
        if let Some(o) = ev.step(g, a, &extra).expect("a step") {
            sink += o.rate_deg_h[0];
        }
    }
    if let Some(steps) = args.get(2) {
        let steps: usize = steps.parse().expect("STEPS");
        for i in 0..steps {
            let (g, a) = &data[i % PER];
            if let Some(o) = ev.step(g, a, &extra).expect("a step") {
                sink += o.rate_deg_h[0];
            }
        }
        println!("{sink}");
        return;
    }
    let mut times = Vec::with_capacity(BATCHES);
    for _ in 0..BATCHES {
        let t0 = Instant::now();
        for (g, a) in &data {
            black_box(ev.step(black_box(g), black_box(a), &extra).expect("a step"));
        }
        times.push(t0.elapsed().as_nanos() as f64 / PER as f64);
    }
    times.sort_by(f64::total_cmp);
    println!("{:.1} {sink}", times[BATCHES / 2]);
}
