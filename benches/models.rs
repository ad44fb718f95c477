//! Cost of one evaluation of each paper model: force and state rate, and the analytic
//! partials a Newton iteration needs. Run: `cargo bench --bench models`.

use criterion::{criterion_group, criterion_main, Criterion};
use friction_models::{FrictionParams, ModelId, SignLaw, Variant};
use std::hint::black_box;

fn evaluation(c: &mut Criterion) {
    let params = FrictionParams::paper();
    let mut group = c.benchmark_group("response+partials");
    for &id in ModelId::PAPER.iter().chain(&[ModelId::LuGre]) {
        let model = id.build(Variant::Odd, &params).unwrap();
        let law = SignLaw::Smooth { epsilon: 1e-3 };
        group.bench_function(id.name(), |b| {
            b.iter(|| {
                let r = model.response(0.0, black_box(0.05), black_box(0.3), law);
                let p = model.partials(0.0, black_box(0.05), black_box(0.3), law);
                r.force + r.state_rate + p.force_dv + p.rate_dz
            })
        });
    }
    group.finish();
}

criterion_group!(benches, evaluation);
criterion_main!(benches);
