//! Running `qdot` under a CPU-time and an address-space bound.
//!
//! The bound on time is the child's CPU time (`ulimit -t`: the kernel
//! kills it past the bound), so a loaded machine slows a run but never
//! fails it; the CPU time it took is measured (the shell's `times`) for
//! the tests that assert a run is quick. A wall-clock backstop, far past
//! any CPU bound, only ends a child that waits without computing.

use std::io::{Read, Write};
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// What a bounded run of `qdot` ended with.
pub struct Outcome {
    /// The exit code; `None` when a signal ended it (a crash).
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
    /// Killed at the CPU-time bound (or, waiting, at the backstop).
    pub timed_out: bool,
    /// The CPU time it took (user and system, all its threads).
    pub cpu: Duration,
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
            "code {:?}, timed out {}, {:?} of CPU\n--- stdout ({} bytes)\n{}\n--- stderr ({} bytes)\n{}",
            self.code,
            self.timed_out,
            self.cpu,
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
            "timed out after {:?} of CPU: {self:?}",
            self.cpu
        );
        assert!(self.code.is_some(), "killed by a signal (crash): {self:?}");
        assert!(
            !self.stderr.contains("panicked") && !self.stderr.contains("overflow"),
            "panic or overflow: {self:?}"
        );
    }

    /// Took less than `seconds` of CPU time.
    #[track_caller]
    pub fn assert_cpu_below(&self, seconds: f64) {
        assert!(
            self.cpu.as_secs_f64() < seconds,
            "{:?} of CPU, more than {seconds} s: {self:?}",
            self.cpu
        );
    }
}

/// Default bounds: 20 s of CPU time and 3 GiB of address space.
pub const SECONDS: u64 = 20;
pub const MEMORY_MIB: u64 = 3072;

/// How long a child may wait without being done, whatever its CPU time:
/// only a child blocked without computing comes near it.
pub const BACKSTOP: Duration = Duration::from_secs(900);

/// A child started by [`spawn_bounded`]: the process (a shell that runs
/// the program and then writes its CPU times) and the file of the times.
pub struct BoundedChild {
    pub child: Child,
    times: PathBuf,
}

/// `command` (whose program and arguments become a shell's `"$0" "$@"`)
/// started in a process group of its own, under `seconds` of CPU time
/// and `memory_mib` MiB of address space; the caller takes its pipes,
/// then [`BoundedChild::wait`]s.
pub fn spawn_bounded(
    program: &Path,
    command: &mut Command,
    seconds: u64,
    memory_mib: u64,
) -> BoundedChild {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("qdot-bound-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let times = dir.join(format!("times-{n}"));
    let _ = std::fs::remove_file(&times);
    // not `exec`: the shell outlives the program to report its CPU time
    let script = format!(
        "ulimit -v {} && ulimit -t {} || exit 97\n\"$0\" \"$@\"\ns=$?\ntimes > \"$QDOT_TIMES\"\nexit $s",
        memory_mib * 1024,
        seconds
    );
    let args: Vec<_> = command.get_args().map(|a| a.to_os_string()).collect();
    let envs: Vec<_> = command
        .get_envs()
        .map(|(k, v)| (k.to_os_string(), v.map(|v| v.to_os_string())))
        .collect();
    let mut sh = Command::new("sh");
    sh.arg("-c").arg(script).arg(program).args(args);
    for (k, v) in envs {
        match v {
            Some(v) => sh.env(k, v),
            None => sh.env_remove(k),
        };
    }
    if let Some(d) = command.get_current_dir() {
        sh.current_dir(d);
    }
    let child = sh
        .env("QDOT_TIMES", &times)
        .process_group(0)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the child starts");
    BoundedChild { child, times }
}

impl BoundedChild {
    /// Wait for the end: the program's exit code (`None`: a signal),
    /// whether it passed its CPU time (or the backstop), and its CPU time.
    pub fn wait(mut self) -> (Option<i32>, bool, Duration) {
        let start = Instant::now();
        let status: ExitStatus = loop {
            if let Some(status) = self.child.try_wait().expect("wait") {
                break status;
            }
            if start.elapsed() > BACKSTOP {
                // the whole group: the shell and the program
                let _ = Command::new("kill")
                    .arg("-KILL")
                    .arg(format!("-{}", self.child.id()))
                    .status();
                let _ = self.child.wait();
                return (None, true, Duration::ZERO);
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let times = std::fs::read_to_string(&self.times).unwrap_or_default();
        let _ = std::fs::remove_file(&self.times);
        let cpu = children_cpu(&times);
        // the shell exits 128 + n when a signal n ended the program
        let (code, signal) = match status.code() {
            Some(c) if c > 128 => (None, Some(c - 128)),
            Some(c) => (Some(c), None),
            None => (None, status.signal()),
        };
        // SIGXCPU at the soft limit, SIGKILL at the hard one
        let timed_out = matches!(signal, Some(9 | 24));
        (code, timed_out, cpu)
    }
}

/// The children's user and system time from the shell's `times` (its
/// second line: `0m1.910000s 0m0.020000s`).
fn children_cpu(times: &str) -> Duration {
    let seconds = |t: &str| -> f64 {
        let t = t.trim().trim_end_matches('s');
        match t.split_once('m') {
            Some((m, s)) => {
                m.parse::<f64>().unwrap_or(0.0) * 60.0 + s.parse::<f64>().unwrap_or(0.0)
            }
            None => 0.0,
        }
    };
    let line = times.lines().nth(1).unwrap_or("");
    Duration::from_secs_f64(line.split_whitespace().map(seconds).sum())
}

/// `qdot ARGS` with `stdin`, under `seconds` of CPU time and `memory_mib`
/// MiB of address space.
pub fn qdot_bounded(args: &[&str], stdin: &str, seconds: u64, memory_mib: u64) -> Outcome {
    let exe = Path::new(env!("CARGO_BIN_EXE_qdot"));
    let mut command = Command::new(exe);
    command.args(args).current_dir(env!("QDOT_ROOT"));
    let mut bounded = spawn_bounded(exe, &mut command, seconds, memory_mib);
    let child = &mut bounded.child;
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
    let (code, timed_out, cpu) = bounded.wait();
    let _ = feeder.join();
    Outcome {
        code,
        stdout: String::from_utf8_lossy(&out_reader.join().unwrap_or_default()).into_owned(),
        stderr: String::from_utf8_lossy(&err_reader.join().unwrap_or_default()).into_owned(),
        timed_out,
        cpu,
    }
}

/// `qdot COMMAND scene.qd REST…` on `src` (bytes: invalid UTF-8 allowed)
/// written to a temporary file; the file's path in messages reads
/// `scene.qd`. Default bounds.
pub fn qdot_scene(tag: &str, src: &[u8], command: &str, rest: &[&str]) -> Outcome {
    qdot_scene_within(tag, src, command, rest, SECONDS, MEMORY_MIB)
}

/// [`qdot_scene`] under `seconds` of CPU time and `memory_mib` MiB.
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

/// The bound is on CPU time: a program that computes past it is killed
/// and reported as timed out, with the CPU time it took.
#[test]
fn the_cpu_bound_ends_a_program_that_computes() {
    let sh = Path::new("/bin/sh");
    let mut command = Command::new(sh);
    command.args(["-c", "while :; do :; done"]);
    let mut b = spawn_bounded(sh, &mut command, 1, MEMORY_MIB);
    drop(b.child.stdin.take());
    let (code, timed_out, cpu) = b.wait();
    assert_eq!(code, None, "{cpu:?}");
    assert!(timed_out, "{cpu:?}");
    assert!(cpu > Duration::ZERO, "the CPU time is measured");
}
