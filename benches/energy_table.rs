//! The default `lumlab energy` run: a(θ) for the four normalizations × the
//! ten default exponents × the lecture's six angles, k = 0 (240 adaptive
//! integrals). The budget is 0.5 s in release.

use criterion::{Criterion, criterion_group, criterion_main};
use lumlab::physics::Normalization;
use lumlab::physics::energy::{LECTURE_ANGLES_DEG, albedo_table};
use std::hint::black_box;

const DEFAULT_MS: [f64; 10] = [1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0, 512.0];

fn default_energy_table(c: &mut Criterion) {
    c.bench_function("energy_default_table", |b| {
        b.iter(|| {
            let rows = albedo_table(
                Normalization::ALL,
                black_box(&DEFAULT_MS),
                0.0,
                &LECTURE_ANGLES_DEG,
            );
            assert_eq!(rows.len(), 4 * 10 * 6);
            rows
        })
    });
}

criterion_group!(benches, default_energy_table);
criterion_main!(benches);
