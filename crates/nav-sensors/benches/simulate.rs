//! Simulation time of the built-in scenarios (issue 3 asks for the default
//! 100-s scenario at 4 kHz in under 2 s in release).
//!
//! ```sh
//! CARGO_TARGET_DIR=... cargo bench -p nav-sensors --bench simulate
//! ```

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use nav_sensors::sim::{Scenario, simulate_unit};
use nav_sensors::unit::Unit;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulate");
    group.sample_size(10);
    for name in Scenario::BUILTIN {
        let scenario = Scenario::builtin(name).expect("built-in");
        group.bench_function(name, |b| {
            b.iter(|| simulate_unit(&Unit::paper(), black_box(&scenario)).expect("simulates"))
        });
    }
    let scenario = Scenario::default();
    let dir = std::env::temp_dir().join("nav-sensors-bench");
    group.bench_function("paper_z_random+write_dir", |b| {
        b.iter(|| {
            simulate_unit(&Unit::paper(), black_box(&scenario))
                .expect("simulates")
                .write_dir(&dir)
                .expect("writes")
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
