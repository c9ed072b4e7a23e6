fn main() {
    let src = std::fs::read_to_string("examples/seed_23_4.qd").unwrap();
    let stmts = qdot::parse::parse_scene(&src).unwrap();
    let scene = qdot::Scene::parse(&src).unwrap();
    let constant = |n: &str| scene.definition(n).and_then(qdot::Expr::as_rational);
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20000);
    for _ in 0..n {
        std::hint::black_box(qdot::scene::dimension::check(&src, &stmts, &constant).unwrap());
    }
}
