//! The REPL's numeric commands (`:cycle`, `:response`, `:floquet`,
//! `:simulate`, `:sweep`, `:codegen`): the same bytes as the CLI for the
//! same options, in each format; their options' did-you-mean and
//! completion; the one table of commands.

use crate::common::run::qdot;
use qdot::repl::Session;

const SET_213: &str =
    "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20";

/// A session with `file` loaded (paths from the repository's root, where
/// the tests run).
fn loaded(file: &str) -> Session {
    let mut s = Session::new();
    let r = s.execute(&format!(":load {file}"));
    assert!(!r.failed, "{}", r.err);
    s
}

/// The CLI's standard output for `args`, which must succeed.
fn cli(args: &[&str]) -> String {
    let (code, out, err) = qdot(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// `entry`'s output, which must succeed.
fn ok(s: &mut Session, entry: &str) -> String {
    let r = s.execute(entry);
    assert!(!r.failed, "{entry}: {}", r.err);
    r.out
}

/// The CLI's output as the REPL prints it: every REPL output ends its
/// line (the CLI's JSON ends without a line break).
fn as_printed(out: String) -> String {
    if out.ends_with('\n') {
        out
    } else {
        out + "\n"
    }
}

/// `:CMD OPTS` in the REPL in each of `formats` (by `:format` and by
/// `--output`) against `qdot CMD FILE OPTS --output FORMAT`.
fn same_as_cli(file: &str, cmd: &str, opts: &[&str], formats: &[&str]) {
    let mut s = loaded(file);
    let quoted: Vec<String> = opts
        .iter()
        .map(|o| {
            if o.starts_with("--") {
                o.to_string()
            } else {
                format!("\"{o}\"")
            }
        })
        .collect();
    let line = format!(":{cmd} {}", quoted.join(" "));
    for fmt in formats {
        let theirs = as_printed(cli(&[&[cmd, file][..], opts, &["--output", fmt]].concat()));
        assert!(!theirs.is_empty());
        ok(&mut s, &format!(":format {fmt}"));
        assert_eq!(ok(&mut s, &line), theirs, "{line} in :format {fmt}");
        ok(&mut s, ":format latex");
        let asked = ok(&mut s, &format!("{line} --output {fmt}"));
        assert_eq!(asked, theirs, "{line} --output {fmt}");
    }
}

#[test]
fn cycle_on_seed_21_3_is_the_clis() {
    let opts = [
        "--over",
        "phi=0:360deg:13",
        "--set",
        SET_213,
        "--guess",
        "x2=0.25,xB=0.5",
    ];
    same_as_cli(
        "examples/seed_21_3.qd",
        "cycle",
        &opts,
        &["text", "json", "csv"],
    );
    let mut s = loaded("examples/seed_21_3.qd");
    ok(&mut s, ":format csv");
    let csv = ok(
        &mut s,
        &format!(
            ":cycle --over phi=0:360deg:13 --set {SET_213} --guess x2=0.25,xB=0.5 --columns M"
        ),
    );
    let header = csv.lines().next().expect("a header");
    assert_eq!(header, "phi,M,note");
    let theirs = cli(&[
        "cycle",
        "examples/seed_21_3.qd",
        "--over",
        "phi=0:360deg:13",
        "--set",
        SET_213,
        "--guess",
        "x2=0.25,xB=0.5",
        "--columns",
        "M",
    ]);
    assert_eq!(csv, as_printed(theirs));
    // the balancing couple at 90°, as the book prints it
    assert!(csv.contains("\n1.57079632679489656e0,1.51637"), "{csv}");
}

#[test]
fn response_on_the_absorber_is_the_clis() {
    let file = "examples/vibration_absorber.qd";
    same_as_cli(file, "response", &[], &["text", "json"]);
    let over = [
        "--set",
        "m1=1,m2=0.2,k1=1,k2=0.2,c=0.02,F0=1",
        "--over",
        "Omega=0.6:1.4:9",
    ];
    same_as_cli(file, "response", &over, &["text", "json", "csv"]);
}

#[test]
fn floquet_on_mathieu_is_the_clis() {
    let set = ["--set", "delta=0.25,eps=0.2,m=1,w=1"];
    same_as_cli("examples/mathieu.qd", "floquet", &set, &["text", "json"]);
    let over = ["--set", "m=1,w=1", "--over", "delta=-0.5:2.5:13,eps=0:2:5"];
    same_as_cli("examples/mathieu.qd", "floquet", &over, &["csv"]);
    // --threads as on the command line: the grid on one thread
    let one = [&over[..], &["--threads", "1"]].concat();
    same_as_cli("examples/mathieu.qd", "floquet", &one, &["csv"]);
}

#[test]
fn simulate_sweep_and_codegen_on_the_pendulum_are_the_clis() {
    let file = "examples/pendulum.qd";
    let mut s = loaded(file);
    let sim = [
        "--set",
        "m=1,l=1,g=1",
        "--init",
        "theta=3,theta'=0",
        "--t-end",
        "10",
        "--points",
        "3",
    ];
    let theirs = as_printed(cli(&[&["simulate", file][..], &sim].concat()));
    assert_eq!(ok(&mut s, &format!(":simulate {}", sim.join(" "))), theirs);
    assert_eq!(theirs.lines().count(), 4, "{theirs}");
    // JSON: the same table (the timings differ run to run)
    let json = |t: &str| -> serde_json::Value {
        let v: serde_json::Value = serde_json::from_str(t).expect("json");
        serde_json::json!([v["columns"], v["rows"], v["status"]])
    };
    let theirs = cli(&[&["simulate", file][..], &sim, &["--output", "json"]].concat());
    let ours = ok(
        &mut s,
        &format!(":simulate {} --output json", sim.join(" ")),
    );
    assert_eq!(json(&ours), json(&theirs));
    assert_eq!(json(&ours)[2], "done");

    let sweep = [
        "--set",
        "m=1,g=9.81",
        "--init",
        "theta'=0",
        "--vary",
        "l=0.5:2:3",
        "--vary",
        "theta=0.5:3:2",
        "--t-end",
        "5",
        "--points",
        "11",
        "--threads",
        "1",
    ];
    let theirs = as_printed(cli(&[&["sweep", file][..], &sweep].concat()));
    assert_eq!(ok(&mut s, &format!(":sweep {}", sweep.join(" "))), theirs);
    assert_eq!(theirs.lines().count(), 7, "{theirs}");

    let gen = ["--lang", "python", "--set", "g=9.81,l=1"];
    let theirs = as_printed(cli(&[&["codegen", file][..], &gen].concat()));
    let ours = ok(&mut s, &format!(":codegen {}", gen.join(" ")));
    assert_eq!(ours, theirs);
    assert!(ours.contains("def pendulum_rhs("), "{ours}");
}

#[test]
fn a_misspelt_option_or_command_is_named() {
    let mut s = loaded("examples/mathieu.qd");
    let r = s.execute(":floquet --perod 6.28");
    assert!(r.failed);
    assert_eq!(
        r.err,
        "error: `:floquet` takes no option `--perod`\n  = hint: did you mean `--period`? :floquet takes --at, --set, --function, --period, --max-steps, --over, --threads, --output, --plot\n"
    );
    let r = s.execute(":flokuet");
    assert_eq!(
        r.err,
        "error: unknown command `:flokuet`\n  = hint: did you mean `:floquet`? :help lists the commands\n"
    );
    let r = s.execute(":respons");
    assert!(r.err.contains("did you mean `:response`?"), "{}", r.err);
    let r = s.execute(":simulate --t-ned 1");
    assert!(r.err.contains("did you mean `--t-end`?"), "{}", r.err);
    let r = s.execute(":cycle --set m=1");
    assert_eq!(
        r.err,
        "error: `:cycle` needs --over\n  = hint: the varied quantity, `t` or a driven coordinate: --over phi=0:360deg:73\n"
    );
    let r = s.execute(":response --output html");
    assert_eq!(
        r.err,
        "error: unknown output `html`\n  = hint: `response` writes text, json, csv\n"
    );
    let r = s.execute(":codegen --lang fortran");
    assert!(
        r.err.starts_with("error: unknown language `fortran`"),
        "{}",
        r.err
    );
    // an error of the run is the CLI's
    let (_, _, theirs) = qdot(&["floquet", "examples/mathieu.qd", "--set", "m=1"]);
    let r = s.execute(":floquet --set m=1");
    assert!(r.failed && !r.err.is_empty());
    let first = |t: &str| t.lines().next().unwrap_or("").to_string();
    assert_eq!(first(&r.err), first(&theirs));
}

#[test]
fn the_command_table_is_the_applications_and_the_repls() {
    let names: Vec<&str> = qdot::repl::commands().iter().map(|c| c.name).collect();
    for c in qdot::app::Command::ALL {
        let name = if c == qdot::app::Command::Derive {
            "equations"
        } else {
            c.name()
        };
        assert!(names.contains(&name), "{name} in {names:?}");
    }
    for own in ["simulate", "sweep", "codegen", "load", "undo", "quit"] {
        assert!(names.contains(&own), "{own}");
    }
    let mut sorted = names.clone();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(sorted.len(), names.len(), "no command twice: {names:?}");
    let help = Session::new().execute(":help").out;
    for c in [
        ":cycle --over",
        ":response",
        ":floquet",
        ":simulate",
        ":sweep",
        ":codegen",
    ] {
        assert!(help.contains(c), "{c} in {help}");
    }
}

/// A command may be named as on the command line: `:derive` is
/// `:equations`.
#[test]
fn the_clis_names_run_too() {
    let mut s = loaded("examples/pendulum.qd");
    let eq = ok(&mut s, ":equations");
    assert!(eq.starts_with("Lagrange's equations"), "{eq}");
    assert_eq!(ok(&mut s, ":derive"), eq);
    assert_eq!(ok(&mut s, ":eq"), eq);
}

#[test]
fn commands_and_their_options_complete() {
    use qdot::repl::editing::completions;
    let shown = |line: &str| -> Vec<String> {
        let (_, c) = completions(line, line.len(), &[]);
        c.into_iter().map(|c| c.display).collect()
    };
    assert_eq!(shown(":fl"), [":floquet"]);
    // in the table's order: the application's commands first
    assert_eq!(shown(":res"), [":response", ":reset"]);
    assert_eq!(shown(":floquet --p"), ["--period", "--plot"]);
    assert_eq!(shown(":cycle --set m=1 --g"), ["--guess"]);
    let (start, c) = completions(":response --o", 13, &[]);
    assert_eq!(start, 10);
    assert_eq!(c[0].replacement, "--over ");
    assert_eq!(shown(":solve --"), Vec::<String>::new());
}

#[test]
fn pictures_are_written_from_the_repl() {
    let dir = std::env::temp_dir().join(format!("qdot-repl-pictures-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a folder");
    let svg = dir.join("chart.svg");
    let mut s = loaded("examples/mathieu.qd");
    let out = ok(
        &mut s,
        &format!(
            ":floquet --set m=1,w=1,eps=0.1 --over delta=-0.5:2.5:4 --plot {}",
            svg.display()
        ),
    );
    assert!(
        out.ends_with(&format!("(wrote {})\n", svg.display())),
        "{out}"
    );
    let text = std::fs::read_to_string(&svg).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        text.starts_with("<svg") || text.starts_with("<?xml"),
        "{text}"
    );
}
