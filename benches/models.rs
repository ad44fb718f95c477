//! Cost of one evaluation of each paper model, LuGre and GMS: force and state rates, and the
//! analytic partials a Newton iteration needs. Run: `cargo bench --bench models`.

use criterion::{criterion_group, criterion_main, Criterion};
use friction_models::{FrictionParams, ModelId, SignLaw, StatePartials, Variant};
use std::hint::black_box;

fn evaluation(c: &mut Criterion) {
    let params = FrictionParams::paper();
    let mut group = c.benchmark_group("response+partials");
    for &id in ModelId::PAPER.iter().chain(&[ModelId::LuGre, ModelId::Gms]) {
        let model = id.build(Variant::Odd, &params).unwrap();
        let law = SignLaw::Smooth { epsilon: 1e-3 };
        let n = model.n_states();
        let z = vec![0.3; n];
        let (mut rate, mut states) = (vec![0.0; n], vec![StatePartials::default(); n]);
        group.bench_function(id.name(), |b| {
            b.iter(|| {
                let (force, p) = model.evaluate(
                    0.0,
                    black_box(0.05),
                    black_box(&z),
                    law,
                    &mut rate,
                    &mut states,
                );
                force
                    + p.force_dv
                    + rate.iter().sum::<f64>()
                    + states.iter().map(|d| d.rate_dz).sum::<f64>()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, evaluation);
criterion_main!(benches);
