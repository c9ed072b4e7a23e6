//! Criterion benchmark of the parser: `parse::parse_scene` on each seed
//! example, including dropping the syntax tree (target: under 10 µs for
//! `seed_21_2`, about 1 KB).

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

fn parse(c: &mut Criterion) {
    let mut g = c.benchmark_group("parse");
    for name in qdot::engine::gallery::SEED_EXAMPLES {
        let path = format!(
            "{}/examples/{name}.qd",
            concat!(env!("CARGO_MANIFEST_DIR"), "/..")
        );
        let src = std::fs::read_to_string(&path).expect("example exists");
        g.throughput(Throughput::Bytes(src.len() as u64));
        g.bench_function(*name, |b| {
            b.iter(|| black_box(qdot::parse::parse_scene(black_box(&src)).expect("parses")))
        });
    }
    g.finish();
}

criterion_group!(benches, parse);
criterion_main!(benches);
