//! Instruction counts for the dimension check against `solve` (run under
//! `valgrind --tool=callgrind`): `dimprof FILE check|solve N` repeats one
//! of them N times after parsing once.

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let src = std::fs::read_to_string(&args[1]).unwrap();
    let n: usize = args[3].parse().unwrap();
    let stmts = qdot::parse::parse_scene(&src).unwrap();
    let scene = qdot::Scene::parse(&src).unwrap();
    let constant = |n: &str| scene.definition(n).and_then(qdot::Expr::as_rational);
    let cmd = if scene.has_dynamics() || !scene.systems.is_empty() {
        qdot::Command::Solve
    } else {
        qdot::Command::Equilibrium
    };
    for _ in 0..n {
        if args[2] == "check" {
            qdot::scene::dimension::validate(&src, &stmts, &constant).unwrap();
        } else {
            let out = qdot::output::run(cmd, &src, qdot::Format::Text, &Default::default());
            std::hint::black_box(out.unwrap());
        }
    }
}
