//! The JIT's only unsafe code: the machine code's owner, the calls into it
//! and the math shims it calls.
//!
//! Everything here rests on one invariant of [`super`]: a function pointer
//! is only taken from a [`Code`] after `finalize_definitions`, for a
//! function whose Cranelift signature is the Rust type it is called as, and
//! its body reads only `len_in` and writes only `len_out` doubles at the
//! pointers it is given (the emitter's loads and stores use fixed offsets
//! below those lengths, checked by the callers here).

use cranelift_jit::JITModule;

/// Finished machine code: the module that owns its memory, freed on drop.
pub(super) struct Code(Option<JITModule>);

impl Code {
    /// Take ownership of a finalized module.
    pub(super) fn new(module: JITModule) -> Code {
        Code(Some(module))
    }
}

// SAFETY: after `finalize_definitions` the module is never used again except
// to free it on drop; the code it owns is immutable and reentrant (it keeps
// no state: every call works on its own stack frame and the pointers it is
// given), so sharing and sending it between threads is sound. The module's
// own non-Send parts (a RefCell of symbols, raw pointers of compiled blobs)
// are only touched while building, on one thread, before `Code::new`.
unsafe impl Send for Code {}
// SAFETY: see `Send`: `&Code` gives no access to the module.
unsafe impl Sync for Code {}

impl Drop for Code {
    fn drop(&mut self) {
        if let Some(m) = self.0.take() {
            // SAFETY: `Code` is only held by `Arc`s inside the `JitRhs` and
            // `JitProgram` values whose function pointers point into it; when
            // the last one drops, no pointer into it remains to be called.
            unsafe { m.free_memory() }
        }
    }
}

/// `extern "C" fn(t, y, dy) -> i32`: the right-hand side.
pub(super) type RhsFn = extern "C" fn(f64, *const f64, *mut f64) -> i32;
/// `extern "C" fn(inputs, outputs)`: a whole program.
pub(super) type ProgramFn = extern "C" fn(*const f64, *mut f64);

/// The right-hand side's entry point, from a finalized function of the
/// signature `(f64, i64, i64) -> i32` (`super::rhs_signature`).
pub(super) fn rhs_fn(ptr: *const u8) -> RhsFn {
    // SAFETY: `ptr` is a finalized function of `module` whose Cranelift
    // signature (f64, pointer, pointer) -> i32 in the host's default call
    // convention is this `extern "C"` type (the module invariant).
    unsafe { std::mem::transmute::<*const u8, RhsFn>(ptr) }
}

/// A program's entry point, from a finalized function of the signature
/// `(i64, i64)`.
pub(super) fn program_fn(ptr: *const u8) -> ProgramFn {
    // SAFETY: as in `rhs_fn`, for the signature (pointer, pointer).
    unsafe { std::mem::transmute::<*const u8, ProgramFn>(ptr) }
}

/// Call the right-hand side on y (length `2n`) into dy (length `2n`).
/// `false` when a Cholesky pivot was not positive (dy then partly written).
#[inline]
pub(super) fn call_rhs(f: RhsFn, n: usize, t: f64, y: &[f64], dy: &mut [f64]) -> bool {
    assert!(y.len() == 2 * n && dy.len() == 2 * n, "wrong state length");
    // `f` is a safe `extern "C"` fn pointer type, but its body is generated
    // code that reads y[0..2n] and writes dy[0..2n]: the lengths are checked
    // above (the module invariant), and the code neither unwinds nor keeps
    // the pointers.
    f(t, y.as_ptr(), dy.as_mut_ptr()) == 0
}

/// Call a program on `inputs` into `out`.
#[inline]
pub(super) fn call_program(
    f: ProgramFn,
    n_in: usize,
    n_out: usize,
    inputs: &[f64],
    out: &mut [f64],
) {
    assert!(
        inputs.len() == n_in && out.len() == n_out,
        "wrong number of inputs or outputs"
    );
    // As in `call_rhs`: the code reads inputs[0..n_in], writes out[0..n_out].
    f(inputs.as_ptr(), out.as_mut_ptr())
}

/// `(sin x, cos x)` by `f64::sin_cos`, written to `out[0]` and `out[1]`
/// (the generated code passes a 16-byte stack slot).
pub(super) extern "C" fn sin_cos(x: f64, out: *mut f64) {
    let (s, c) = x.sin_cos();
    // SAFETY: the only caller is generated code passing the address of a
    // 16-byte, 8-aligned stack slot of its own frame.
    unsafe {
        out.write(s);
        out.add(1).write(c);
    }
}
