//! Running `qdot` under a wall-clock and an address-space bound.

use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What a bounded run of `qdot` ended with.
pub struct Outcome {
    /// The exit code; `None` when a signal ended it (a crash).
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
    /// Killed at the time bound.
    pub timed_out: bool,
    pub elapsed: Duration,
}

/// At most the first 2,000 bytes of a text (on a character boundary).
fn head(s: &str) -> &str {
    let mut end = s.len().min(2000);
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    &s[..end]
}

impl std::fmt::Debug for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "code {:?}, timed out {}, {:?}\n--- stdout ({} bytes)\n{}\n--- stderr ({} bytes)\n{}",
            self.code,
            self.timed_out,
            self.elapsed,
            self.stdout.len(),
            head(&self.stdout),
            self.stderr.len(),
            head(&self.stderr)
        )
    }
}

impl Outcome {
    /// Ended by itself with an exit code (no signal, no time-out), and
    /// printed no panic message.
    #[track_caller]
    pub fn assert_clean(&self) {
        assert!(
            !self.timed_out,
            "timed out after {:?}: {self:?}",
            self.elapsed
        );
        assert!(self.code.is_some(), "killed by a signal (crash): {self:?}");
        assert!(
            !self.stderr.contains("panicked") && !self.stderr.contains("overflow"),
            "panic or overflow: {self:?}"
        );
    }
}

/// Default bounds: 20 s of wall clock and 3 GiB of address space.
pub const SECONDS: u64 = 20;
pub const MEMORY_MIB: u64 = 3072;

/// `qdot ARGS` with `stdin`, killed after `seconds`, its address space
/// limited to `memory_mib` MiB (`ulimit -v` in a shell that execs it).
pub fn qdot_bounded(args: &[&str], stdin: &str, seconds: u64, memory_mib: u64) -> Outcome {
    let exe = env!("CARGO_BIN_EXE_qdot");
    let script = format!("ulimit -v {} && exec \"$0\" \"$@\"", memory_mib * 1024);
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(exe)
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("qdot starts");
    let mut input = child.stdin.take().expect("stdin");
    let text = stdin.to_string();
    let feeder = std::thread::spawn(move || {
        let _ = input.write_all(text.as_bytes());
    });
    // Both pipes drained while it runs, so a large output cannot block it.
    let mut stdout = child.stdout.take().expect("stdout");
    let mut stderr = child.stderr.take().expect("stderr");
    let out_reader = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = stdout.read_to_end(&mut b);
        b
    });
    let err_reader = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = stderr.read_to_end(&mut b);
        b
    });
    let start = Instant::now();
    let mut timed_out = false;
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > Duration::from_secs(seconds) {
            let _ = child.kill();
            timed_out = true;
            break child.wait().expect("wait");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let _ = feeder.join();
    let out = std::process::Output {
        status,
        stdout: out_reader.join().unwrap_or_default(),
        stderr: err_reader.join().unwrap_or_default(),
    };
    Outcome {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        timed_out,
        elapsed: start.elapsed(),
    }
}

/// `qdot COMMAND scene.qd REST…` on `src` (bytes: invalid UTF-8 allowed)
/// written to a temporary file; the file's path in messages reads
/// `scene.qd`. Default bounds.
pub fn qdot_scene(tag: &str, src: &[u8], command: &str, rest: &[&str]) -> Outcome {
    qdot_scene_within(tag, src, command, rest, SECONDS, MEMORY_MIB)
}

/// [`qdot_scene`] under `seconds` of wall clock and `memory_mib` MiB.
pub fn qdot_scene_within(
    tag: &str,
    src: &[u8],
    command: &str,
    rest: &[&str],
    seconds: u64,
    memory_mib: u64,
) -> Outcome {
    let dir = std::env::temp_dir().join(format!("qdot-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let path = dir.join(format!("{tag}.qd"));
    std::fs::write(&path, src).expect("scene written");
    let p = path.to_str().expect("utf-8 path").to_string();
    let mut all = vec![command, p.as_str()];
    all.extend_from_slice(rest);
    let mut o = qdot_bounded(&all, "", seconds, memory_mib);
    o.stdout = o.stdout.replace(&p, "scene.qd");
    o.stderr = o.stderr.replace(&p, "scene.qd");
    o
}

#[test]
fn the_bound_itself_works() {
    let o = qdot_scene(
        "bound",
        b"coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\n",
        "solve",
        &[],
    );
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("x\u{308} = −k/m·x"), "{}", o.stdout);
}
