//! Machine code for a [`Program`] at run time (Cranelift; feature `jit`).
//!
//! The register program is straight-line code, so each register becomes an
//! SSA value: no register file, no dispatch, the constants as immediates,
//! and Cranelift's register allocator in place of the interpreter's loads
//! and stores. sin, cos, exp, ln, atan, asin and acos are calls to Rust
//! shims (`f64::sin` and so on, the interpreter's own functions); a
//! `sin_cos` pair is one call to `f64::sin_cos`; √ is the `sqrt`
//! instruction (correctly rounded, as `f64::sqrt`).
//!
//! [`compile_rhs`] compiles the whole right-hand side y' = (q̇, q̈) of a
//! [`super::CompiledDynamics`] into one function: the program, then by the
//! mode M's Cholesky factorization and the two triangular solves fully
//! unrolled (or the product with the kept M⁻¹, or nothing). Every
//! operation is the interpreter's, in the interpreter's order
//! ([`crate::dense::solve_spd`]'s loops, sums from −0.0 as `Iterator::sum`),
//! with no fused multiply-add, so the results are bit for bit the
//! interpreter's (the tests check it). A pivot that is not positive makes
//! the function return 1, and the caller then runs the interpreter (whose
//! `solve_spd` goes on by Gaussian elimination) for that call.
//!
//! [`compile_program`] compiles a program alone (inputs → outputs).
//!
//! The unsafe code, the calls through the function pointers and the memory
//! they point into, is `native`'s.

mod native;

use super::program::{Instr, Program, NONE};
use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{
    types, AbiParam, Block, FuncRef, InstBuilder, MemFlagsData, Signature, StackSlotData,
    StackSlotKind, UserFuncName, Value,
};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::Context;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, FuncId, Linkage, Module};
use std::fmt;
use std::sync::Arc;
use std::time::Instant;

/// Why a program could not be compiled to machine code.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JitError(pub String);

impl fmt::Display for JitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for JitError {}

/// What follows the program in the right-hand side.
#[derive(Clone, Copy, Debug)]
pub enum Tail<'a> {
    /// The outputs are q̈.
    Accelerations,
    /// The outputs are f; q̈ = M⁻¹·f with this M⁻¹ (row-major n×n).
    ConstantMass(&'a [f64]),
    /// The outputs are M's upper triangle (row by row) then f; q̈ by
    /// Cholesky.
    MassMatrix,
}

/// A compiled right-hand side y' = (q̇, q̈) for y = (q, q̇) of n coordinates.
#[derive(Clone)]
pub struct JitRhs {
    _code: Arc<native::Code>,
    f: native::RhsFn,
    n: usize,
    seconds: f64,
    bytes: usize,
}

impl fmt::Debug for JitRhs {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "JitRhs {{ n: {}, bytes: {} }}", self.n, self.bytes)
    }
}

impl JitRhs {
    /// y' at (t, y) into `dy` (both of length 2n); `false` when M's
    /// Cholesky factorization met a pivot that is not positive (`dy` is
    /// then partly written: evaluate it another way).
    ///
    /// # Panics
    /// When `y` or `dy` is not of length 2n.
    #[inline]
    pub fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) -> bool {
        native::call_rhs(self.f, self.n, t, y, dy)
    }
    /// Wall time of the compilation, in seconds.
    pub fn compile_seconds(&self) -> f64 {
        self.seconds
    }
    /// The size of the machine code, in bytes.
    pub fn code_bytes(&self) -> usize {
        self.bytes
    }
}

/// A [`Program`] compiled alone: inputs → outputs.
#[derive(Clone)]
pub struct JitProgram {
    _code: Arc<native::Code>,
    f: native::ProgramFn,
    n_in: usize,
    n_out: usize,
}

impl fmt::Debug for JitProgram {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "JitProgram {{ {} → {} }}", self.n_in, self.n_out)
    }
}

impl JitProgram {
    /// Every output at `inputs`, as [`Program::eval`].
    ///
    /// # Panics
    /// When `inputs` or `out` has the wrong length.
    #[inline]
    pub fn eval(&self, inputs: &[f64], out: &mut [f64]) {
        native::call_program(self.f, self.n_in, self.n_out, inputs, out)
    }
}

/// The Rust functions the generated code calls.
const SHIMS: [(&str, extern "C" fn(f64) -> f64); 7] = [
    ("qdot_jit_sin", sin),
    ("qdot_jit_cos", cos),
    ("qdot_jit_exp", exp),
    ("qdot_jit_ln", ln),
    ("qdot_jit_atan", atan),
    ("qdot_jit_asin", asin),
    ("qdot_jit_acos", acos),
];
const SIN_COS: &str = "qdot_jit_sin_cos";

extern "C" fn sin(x: f64) -> f64 {
    x.sin()
}
extern "C" fn cos(x: f64) -> f64 {
    x.cos()
}
extern "C" fn exp(x: f64) -> f64 {
    x.exp()
}
extern "C" fn ln(x: f64) -> f64 {
    x.ln()
}
extern "C" fn atan(x: f64) -> f64 {
    x.atan()
}
extern "C" fn asin(x: f64) -> f64 {
    x.asin()
}
extern "C" fn acos(x: f64) -> f64 {
    x.acos()
}

fn err(what: &str) -> impl Fn(String) -> JitError + '_ {
    move |e| JitError(format!("{what}: {e}"))
}

/// The size ([`estimated_size`]) above which registers are allocated in
/// one pass (regalloc2's `single_pass`) instead of by backtracking: for the
/// 10-link chain, above it, that is ≈ 2–3 ms to compile instead of ≈ 10 ms,
/// for ≈ 20 % more instructions per call (4,118 against 3,397, callgrind;
/// ≈ 710–800 ns against ≈ 550–760 ns), mostly spill moves: backtracking
/// pays off after some 50,000 right-hand sides, more than most runs take
/// (the 10-link chain over 10 s at rtol 1e-10: 3,617). Below it both
/// compile in well under a millisecond (`benches/examples/rhs_engines.rs`).
pub const FAST_ALLOCATION: usize = 1000;

/// About how many IR operations the right-hand side of `p` with `tail`
/// takes: a dot product of k pairs 2k, a power log₂ n + 1, a call 3, any
/// other instruction 1; M's Cholesky factorization and solves n³/3 + 2n²,
/// the product with M⁻¹ 2n².
pub fn estimated_size(p: &Program, n: usize, tail: Tail) -> usize {
    let program: usize = p
        .code
        .iter()
        .map(|i| match *i {
            Instr::Dot { len, .. } => 2 * len as usize + 1,
            Instr::Powi { n, .. } => (32 - n.leading_zeros()) as usize + 1,
            Instr::Sin { .. }
            | Instr::Cos { .. }
            | Instr::SinCos { .. }
            | Instr::Exp { .. }
            | Instr::Ln { .. }
            | Instr::Atan { .. }
            | Instr::Asin { .. }
            | Instr::Acos { .. } => 3,
            _ => 1,
        })
        .sum();
    program
        + 4 * n
        + match tail {
            Tail::MassMatrix => n * n * n / 3 + 2 * n * n,
            Tail::ConstantMass(_) => 2 * n * n,
            Tail::Accelerations => 0,
        }
}

/// A module for the host with the shims declared.
struct Jit {
    module: JITModule,
    ctx: Context,
    fctx: FunctionBuilderContext,
    /// The shims' ids, in `SHIMS` order, then `sin_cos`.
    shims: Vec<FuncId>,
}

impl Jit {
    /// A module for a function of about `size` operations
    /// ([`estimated_size`]).
    fn new(size: usize) -> Result<Jit, JitError> {
        let mut flags = settings::builder();
        let set = |f: &mut settings::Builder, k: &str, v: &str| {
            f.set(k, v).map_err(|e| JitError(format!("flag {k}: {e}")))
        };
        set(&mut flags, "use_colocated_libcalls", "false")?;
        set(&mut flags, "is_pic", "false")?;
        set(&mut flags, "opt_level", "speed")?;
        let ra = if size > FAST_ALLOCATION {
            "single_pass"
        } else {
            "backtracking"
        };
        set(&mut flags, "regalloc_algorithm", ra)?;
        // the IR is straight-line and built by this module: the verifier
        // only costs compile time outside debug builds
        let verify = if cfg!(debug_assertions) {
            "true"
        } else {
            "false"
        };
        set(&mut flags, "enable_verifier", verify)?;
        let isa = cranelift_native::builder()
            .map_err(|e| JitError(format!("this machine is not supported: {e}")))?
            .finish(settings::Flags::new(flags))
            .map_err(|e| err("target")(e.to_string()))?;
        let mut builder = JITBuilder::with_isa(isa, default_libcall_names());
        for (name, f) in SHIMS {
            builder.symbol(name, f as *const u8);
        }
        builder.symbol(
            SIN_COS,
            native::sin_cos as extern "C" fn(f64, *mut f64) as *const u8,
        );

        let mut module = JITModule::new(builder);
        let mut shims = Vec::new();
        let mut unary = module.make_signature();
        unary.params.push(AbiParam::new(types::F64));
        unary.returns.push(AbiParam::new(types::F64));
        for (name, _) in SHIMS {
            let id = module
                .declare_function(name, Linkage::Import, &unary)
                .map_err(|e| err("declare")(e.to_string()))?;
            shims.push(id);
        }
        let ptr = module.target_config().pointer_type();
        let mut pair = module.make_signature();
        pair.params.push(AbiParam::new(types::F64));
        pair.params.push(AbiParam::new(ptr));
        let id = module
            .declare_function(SIN_COS, Linkage::Import, &pair)
            .map_err(|e| err("declare")(e.to_string()))?;
        shims.push(id);
        let ctx = module.make_context();
        Ok(Jit {
            module,
            ctx,
            fctx: FunctionBuilderContext::new(),
            shims,
        })
    }

    /// Define the function `sig` whose body `body` emits (into the entry
    /// block, its parameters given), finalize it and return the module
    /// and the function's address and size.
    fn finish(
        mut self,
        sig: Signature,
        body: impl FnOnce(&mut Emitter, &[Value]),
    ) -> Result<(native::Code, *const u8, usize), JitError> {
        let id = self
            .module
            .declare_function("qdot_rhs", Linkage::Local, &sig)
            .map_err(|e| err("declare")(e.to_string()))?;
        self.ctx.func.signature = sig;
        self.ctx.func.name = UserFuncName::user(0, id.as_u32());
        {
            let mut b = FunctionBuilder::new(&mut self.ctx.func, &mut self.fctx);
            let refs: Vec<FuncRef> = self
                .shims
                .iter()
                .map(|&s| self.module.declare_func_in_func(s, b.func))
                .collect();
            let entry = b.create_block();
            b.append_block_params_for_function_params(entry);
            b.switch_to_block(entry);
            let params = b.block_params(entry).to_vec();
            let mut e = Emitter {
                b,
                refs,
                ptr: self.module.target_config().pointer_type(),
                pair_slot: None,
            };
            body(&mut e, &params);
            e.b.seal_all_blocks();
            e.b.finalize(self.module.target_config());
        }
        self.module
            .define_function(id, &mut self.ctx)
            .map_err(|e| err("code generation")(e.to_string()))?;
        let bytes = self
            .ctx
            .compiled_code()
            .map_or(0, |c| c.code_buffer().len());
        self.module.clear_context(&mut self.ctx);
        self.module
            .finalize_definitions()
            .map_err(|e| err("finalize")(e.to_string()))?;
        let ptr = self.module.get_finalized_function(id);
        Ok((native::Code::new(self.module), ptr, bytes))
    }
}

/// Emits IR into one function.
struct Emitter<'a> {
    b: FunctionBuilder<'a>,
    /// The shims' references in this function, in `Jit::shims` order.
    refs: Vec<FuncRef>,
    /// The type of a pointer.
    ptr: types::Type,
    /// The 16-byte slot `sin_cos` writes into.
    pair_slot: Option<cranelift_codegen::ir::StackSlot>,
}

const FLAGS: MemFlagsData = MemFlagsData::trusted();

impl Emitter<'_> {
    fn c(&mut self, x: f64) -> Value {
        self.b.ins().f64const(x)
    }
    fn load(&mut self, ptr: Value, k: usize) -> Value {
        self.b.ins().load(types::F64, FLAGS, ptr, 8 * k as i32)
    }
    fn store(&mut self, v: Value, ptr: Value, k: usize) {
        self.b.ins().store(FLAGS, v, ptr, 8 * k as i32);
    }
    fn call1(&mut self, shim: usize, x: Value) -> Value {
        let call = self.b.ins().call(self.refs[shim], &[x]);
        self.b.inst_results(call)[0]
    }
    fn sin_cos(&mut self, x: Value) -> (Value, Value) {
        let slot = match self.pair_slot {
            Some(s) => s,
            None => {
                let s = self.b.create_sized_stack_slot(StackSlotData::new(
                    StackSlotKind::ExplicitSlot,
                    16,
                    3,
                ));
                self.pair_slot = Some(s);
                s
            }
        };
        let addr = self.b.ins().stack_addr(self.ptr, slot, 0);
        self.b.ins().call(self.refs[SHIMS.len()], &[x, addr]);
        (self.load(addr, 0), self.load(addr, 1))
    }

    /// `x` to the power `n`, as the interpreter's `powi`.
    fn powi(&mut self, x: Value, n: u32) -> Value {
        let mul = |e: &mut Self, a, b| e.b.ins().fmul(a, b);
        match n {
            0 => self.c(1.0),
            1 => x,
            2 => mul(self, x, x),
            3 => {
                let x2 = mul(self, x, x);
                mul(self, x2, x)
            }
            _ => {
                // acc starts at 1.0: its first product 1.0·base is exact,
                // so acc starts at that base
                let (mut acc, mut base, mut e) = (None::<Value>, x, n);
                while e > 0 {
                    if e & 1 == 1 {
                        acc = Some(match acc {
                            None => base,
                            Some(a) => mul(self, a, base),
                        });
                    }
                    e >>= 1;
                    if e > 0 {
                        base = mul(self, base, base);
                    }
                }
                acc.unwrap_or(x)
            }
        }
    }

    /// Σ xₖ·yₖ as `Iterator::sum` adds them: from −0.0, left to right
    /// (−0.0 + p is p, so the sum starts at the first product).
    fn dot(&mut self, pairs: &[(Value, Value)]) -> Value {
        let mut acc = None;
        for &(x, y) in pairs {
            let p = self.b.ins().fmul(x, y);
            acc = Some(match acc {
                None => p,
                Some(a) => self.b.ins().fadd(a, p),
            });
        }
        acc.unwrap_or_else(|| self.c(-0.0))
    }

    /// The program's instructions on `inputs`; the output values.
    fn program(&mut self, p: &Program, inputs: &[Value]) -> Vec<Value> {
        let mut r: Vec<Option<Value>> = vec![None; p.n_regs];
        for (k, &c) in p.consts.iter().enumerate() {
            r[k] = Some(self.c(c));
        }
        for (k, &v) in inputs.iter().enumerate() {
            r[p.consts.len() + k] = Some(v);
        }
        // a register read before any write holds 0.0, as in the
        // interpreter's fresh register file (never, for a built program)
        let zero = self.c(0.0);
        let g = |r: &[Option<Value>], k: u32| r[k as usize].unwrap_or(zero);
        for ins in &p.code {
            match *ins {
                Instr::Add { dst, a, b } => {
                    r[dst as usize] = Some(self.b.ins().fadd(g(&r, a), g(&r, b)))
                }
                Instr::Sub { dst, a, b } => {
                    r[dst as usize] = Some(self.b.ins().fsub(g(&r, a), g(&r, b)))
                }
                Instr::Mul { dst, a, b } => {
                    r[dst as usize] = Some(self.b.ins().fmul(g(&r, a), g(&r, b)))
                }
                Instr::MulAdd { dst, a, b, c } => {
                    let m = self.b.ins().fmul(g(&r, a), g(&r, b));
                    r[dst as usize] = Some(self.b.ins().fadd(m, g(&r, c)))
                }
                Instr::Dot {
                    dst,
                    init,
                    start,
                    len,
                } => {
                    // acc = init (or 0.0); acc += a·b, left to right
                    let mut acc = if init == NONE {
                        self.c(0.0)
                    } else {
                        g(&r, init)
                    };
                    for &(a, b) in &p.pairs[start as usize..(start + len) as usize] {
                        let m = self.b.ins().fmul(g(&r, a), g(&r, b));
                        acc = self.b.ins().fadd(acc, m);
                    }
                    r[dst as usize] = Some(acc)
                }
                Instr::Div { dst, a, b } => {
                    r[dst as usize] = Some(self.b.ins().fdiv(g(&r, a), g(&r, b)))
                }
                Instr::Neg { dst, a } => r[dst as usize] = Some(self.b.ins().fneg(g(&r, a))),
                Instr::Powi { dst, a, n } => r[dst as usize] = Some(self.powi(g(&r, a), n)),
                Instr::Sqrt { dst, a } => r[dst as usize] = Some(self.b.ins().sqrt(g(&r, a))),
                Instr::SinCos { sin, cos, a } => {
                    let (s, c) = self.sin_cos(g(&r, a));
                    r[sin as usize] = Some(s);
                    r[cos as usize] = Some(c);
                }
                Instr::Sin { dst, a } => r[dst as usize] = Some(self.call1(0, g(&r, a))),
                Instr::Cos { dst, a } => r[dst as usize] = Some(self.call1(1, g(&r, a))),
                Instr::Exp { dst, a } => r[dst as usize] = Some(self.call1(2, g(&r, a))),
                Instr::Ln { dst, a } => r[dst as usize] = Some(self.call1(3, g(&r, a))),
                Instr::Atan { dst, a } => r[dst as usize] = Some(self.call1(4, g(&r, a))),
                Instr::Asin { dst, a } => r[dst as usize] = Some(self.call1(5, g(&r, a))),
                Instr::Acos { dst, a } => r[dst as usize] = Some(self.call1(6, g(&r, a))),
            }
        }
        p.outputs.iter().map(|&k| g(&r, k)).collect()
    }

    /// q̈ = M⁻¹·f by Cholesky, unrolled, as [`crate::dense::solve_spd`]
    /// does it while the pivots are positive: `m` is M's upper triangle row
    /// by row; a pivot that is not positive jumps to `fail`.
    fn cholesky_solve(&mut self, n: usize, m: &[Value], f: &[Value], fail: Block) -> Vec<Value> {
        // a[i][j], j ≤ i: M's lower triangle (the upper one mirrored), then L
        // (the upper triangle's entry (i, j), i ≤ j, is m[i(2n − i + 1)/2 + j − i])
        let upper = |i: usize, j: usize| m[i * (2 * n - i + 1) / 2 + j - i];
        let mut a: Vec<Vec<Value>> = (0..n)
            .map(|r| (0..=r).map(|c| upper(c, r)).collect())
            .collect();
        let one = self.c(1.0);
        let zero = self.c(0.0);
        for j in 0..n {
            let pairs: Vec<_> = a[j][..j].iter().map(|&x| (x, x)).collect();
            let s = self.dot(&pairs);
            let d = self.b.ins().fsub(a[j][j], s);
            // d.is_nan() || d <= 0 ⇔ !(d > 0)
            let ok = self.b.ins().fcmp(FloatCC::GreaterThan, d, zero);
            let next = self.b.create_block();
            self.b.ins().brif(ok, next, &[], fail, &[]);
            self.b.switch_to_block(next);
            let d = self.b.ins().sqrt(d);
            a[j][j] = d;
            let inv = self.b.ins().fdiv(one, d);
            for i in j + 1..n {
                let pairs: Vec<_> = (0..j).map(|c| (a[i][c], a[j][c])).collect();
                let s = self.dot(&pairs);
                let x = self.b.ins().fsub(a[i][j], s);
                a[i][j] = self.b.ins().fmul(x, inv);
            }
        }
        let mut b = f.to_vec();
        for i in 0..n {
            let pairs: Vec<_> = (0..i).map(|c| (a[i][c], b[c])).collect();
            let s = self.dot(&pairs);
            let x = self.b.ins().fsub(b[i], s);
            b[i] = self.b.ins().fdiv(x, a[i][i]);
        }
        for i in (0..n).rev() {
            let mut s = b[i];
            for (kk, &bk) in b.iter().enumerate().skip(i + 1) {
                let p = self.b.ins().fmul(a[kk][i], bk);
                s = self.b.ins().fsub(s, p);
            }
            b[i] = self.b.ins().fdiv(s, a[i][i]);
        }
        b
    }
}

/// Compile the right-hand side of n coordinates whose program (inputs
/// `[t, q…, q̇…]`) and tail are given, as [`super::CompiledDynamics`]
/// evaluates it.
pub fn compile_rhs(p: &Program, n: usize, tail: Tail) -> Result<JitRhs, JitError> {
    let start = Instant::now();
    let expected = match tail {
        Tail::MassMatrix => n * (n + 1) / 2 + n,
        _ => n,
    };
    if p.n_inputs != 1 + 2 * n || p.outputs.len() != expected {
        return Err(JitError(format!(
            "the program has {} inputs and {} outputs, not {} and {expected}",
            p.n_inputs,
            p.outputs.len(),
            1 + 2 * n
        )));
    }
    if let Tail::ConstantMass(inv) = tail {
        if inv.len() != n * n {
            return Err(JitError(format!("M⁻¹ must be {n}×{n}")));
        }
    }
    let jit = Jit::new(estimated_size(p, n, tail))?;
    let ptr = jit.module.target_config().pointer_type();
    let mut sig = jit.module.make_signature();
    sig.params.push(AbiParam::new(types::F64));
    sig.params.push(AbiParam::new(ptr));
    sig.params.push(AbiParam::new(ptr));
    sig.returns.push(AbiParam::new(types::I32));
    let (code, f, bytes) = jit.finish(sig, |e, params| {
        let (t, y, dy) = (params[0], params[1], params[2]);
        let mut inputs = vec![t];
        for k in 0..2 * n {
            inputs.push(e.load(y, k));
        }
        // dq = q̇
        for k in 0..n {
            e.store(inputs[1 + n + k], dy, k);
        }
        let out = e.program(p, &inputs);
        let qdd = match tail {
            Tail::Accelerations => out,
            Tail::ConstantMass(inv) => (0..n)
                .map(|i| {
                    let pairs: Vec<_> = (0..n).map(|j| (e.c(inv[i * n + j]), out[j])).collect();
                    e.dot(&pairs)
                })
                .collect(),
            Tail::MassMatrix => {
                let fail = e.b.create_block();
                let k = n * (n + 1) / 2;
                let qdd = e.cholesky_solve(n, &out[..k], &out[k..], fail);
                for (i, &v) in qdd.iter().enumerate() {
                    e.store(v, dy, n + i);
                }
                let ok = e.b.ins().iconst(types::I32, 0);
                e.b.ins().return_(&[ok]);
                e.b.switch_to_block(fail);
                let bad = e.b.ins().iconst(types::I32, 1);
                e.b.ins().return_(&[bad]);
                return;
            }
        };
        for (i, &v) in qdd.iter().enumerate() {
            e.store(v, dy, n + i);
        }
        let ok = e.b.ins().iconst(types::I32, 0);
        e.b.ins().return_(&[ok]);
    })?;
    Ok(JitRhs {
        _code: Arc::new(code),
        f: native::rhs_fn(f),
        n,
        seconds: start.elapsed().as_secs_f64(),
        bytes,
    })
}

/// Compile a program alone: `eval(inputs, out)` as [`Program::eval`].
pub fn compile_program(p: &Program) -> Result<JitProgram, JitError> {
    let jit = Jit::new(estimated_size(p, 0, Tail::Accelerations) + p.n_inputs + p.outputs.len())?;
    let ptr = jit.module.target_config().pointer_type();
    let mut sig = jit.module.make_signature();
    sig.params.push(AbiParam::new(ptr));
    sig.params.push(AbiParam::new(ptr));
    let (code, f, _) = jit.finish(sig, |e, params| {
        let inputs: Vec<Value> = (0..p.n_inputs).map(|k| e.load(params[0], k)).collect();
        let out = e.program(p, &inputs);
        for (k, &v) in out.iter().enumerate() {
            e.store(v, params[1], k);
        }
        e.b.ins().return_(&[]);
    })?;
    Ok(JitProgram {
        _code: Arc::new(code),
        f: native::program_fn(f),
        n_in: p.n_inputs,
        n_out: p.outputs.len(),
    })
}
