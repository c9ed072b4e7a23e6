//! Criterion benchmarks of printing large results: the expanded equations
//! of the 3D rod chain (`qdot::engine::gallery::rod_chain_3d`, n = 4 and
//! 5: 38 KB and 164 KB of text) as `qdot derive --expand` writes them, and
//! each entry of M and f in input syntax as its JSON does. The derivation
//! is made once, outside the timing. Printing searches each expression's
//! compact form within its work allowance (`qdot::limits::COMPACT_WORK_BASE`
//! and `COMPACT_WORK_PER_TERM`), so its time grows with the text printed;
//! each run prints the bytes and the search's work per byte.
//!
//! `cargo bench -p qdot-benches --bench print`

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use qdot::{Lagrange, Scene};
use std::hint::black_box;

fn chain(n: usize) -> Lagrange {
    let src = qdot::engine::gallery::rod_chain_3d(n);
    let scene = Scene::parse(&src).expect("parses");
    scene.lagrange().expect("derives")
}

/// M and f in input syntax, one string per entry.
fn entries(l: &Lagrange) -> Vec<String> {
    let m = l.mass_matrix.iter().flatten();
    m.chain(&l.forcing).map(|e| e.to_input()).collect()
}

fn print(c: &mut Criterion) {
    let mut g = c.benchmark_group("print/chain3d");
    g.sample_size(10);
    for n in [4usize, 5] {
        let l = chain(n);
        let before = qdot::expr::compact::search_work();
        let text = qdot::output::derive_text(&l);
        let work = qdot::expr::compact::search_work() - before;
        eprintln!(
            "chain3d n = {n}: {} bytes of text, search work {:.2} terms per byte",
            text.len(),
            work as f64 / text.len() as f64
        );
        g.bench_with_input(BenchmarkId::new("text", n), &l, |b, l| {
            b.iter(|| black_box(qdot::output::derive_text(black_box(l))))
        });
        g.bench_with_input(BenchmarkId::new("input", n), &l, |b, l| {
            b.iter(|| black_box(entries(black_box(l))))
        });
    }
    g.finish();
}

criterion_group!(benches, print);
criterion_main!(benches);
