//! Criterion benchmark of `poly::factor::factor` on a few polynomials: the
//! same list as `scripts/anchor_factor.py`, which times SymPy's
//! `factor_list` on them for side-by-side ratios.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// `(name, polynomial)`; keep in step with `scripts/anchor_factor.py`.
pub const CASES: [(&str, &str); 8] = [
    ("x15_minus_1", "x^15 - 1"),
    (
        "swinnerton_dyer_8",
        "x^8 - 40*x^6 + 352*x^4 - 960*x^2 + 576",
    ),
    (
        "univariate_deg12",
        "(3*x^4 - 7*x^3 + 2*x - 11)*(x^5 + 13*x^2 - 5)*(2*x^3 + x^2 - 17)",
    ),
    ("x6_minus_y6", "x^6 - y^6"),
    (
        "bivariate_quartics",
        "(x^2 + x*y + y^2 + 1)*(x^2 - x*y + y^2 - 3)*(x^2*y^2 - 2)",
    ),
    ("charpoly_irreducible", "2*k^2 - 4*k*m*l + m^2*l^2"),
    ("charpoly_split", "(k^2 - m^2*l^2)*(2*k - m*l)*(k - 6*m*l)"),
    (
        "trivariate",
        "(x^2*y + z^2 - 3)*(x*z^2 + y^2 + 2*x)*(y^2*z^2 + x^2 + 1)",
    ),
];

fn factor(c: &mut Criterion) {
    let scene = qdot::Scene::parse("parameters x, y, z, k, m, l").expect("scene");
    let mut g = c.benchmark_group("factor");
    for (name, src) in CASES {
        let e = scene.expr(src).expect("polynomial");
        let p = e.num().clone();
        g.bench_function(name, |b| {
            b.iter(|| black_box(qdot::engine::poly::factor::factor(black_box(&p))))
        });
    }
    g.finish();
}

criterion_group!(benches, factor);
criterion_main!(benches);
