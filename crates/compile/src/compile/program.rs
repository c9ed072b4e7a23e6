//! The compiled program: straight-line register instructions and their
//! interpreter.

/// One instruction of a [`Program`]: registers are indices into the
/// register file; `dst` is written after all operands are read.
#[derive(Clone, Copy, Debug, PartialEq)]
#[doc(hidden)]
pub enum Instr {
    /// `dst = a + b`.
    Add { dst: u32, a: u32, b: u32 },
    /// `dst = a − b`.
    Sub { dst: u32, a: u32, b: u32 },
    /// `dst = a · b`.
    Mul { dst: u32, a: u32, b: u32 },
    /// `dst = a · b + c` (two roundings, not a fused multiply-add).
    MulAdd { dst: u32, a: u32, b: u32, c: u32 },
    /// `dst = init + Σ a_k·b_k` over the register pairs
    /// `start..start + len` of [`Program::pairs`], summed left to right
    /// (`init == u32::MAX`: no initial value).
    Dot {
        dst: u32,
        init: u32,
        start: u32,
        len: u32,
    },
    /// `dst = a / b`.
    Div { dst: u32, a: u32, b: u32 },
    /// `dst = −a`.
    Neg { dst: u32, a: u32 },
    /// `dst = aⁿ` (n ≥ 2) by repeated squaring and multiplication.
    Powi { dst: u32, a: u32, n: u32 },
    /// `dst = sin a`.
    Sin { dst: u32, a: u32 },
    /// `dst = cos a`.
    Cos { dst: u32, a: u32 },
    /// `(sin, cos) = (sin a, cos a)` by one `f64::sin_cos`.
    SinCos { sin: u32, cos: u32, a: u32 },
    /// `dst = exp a`.
    Exp { dst: u32, a: u32 },
    /// `dst = ln a`.
    Ln { dst: u32, a: u32 },
    /// `dst = √a`.
    Sqrt { dst: u32, a: u32 },
    /// `dst = atan a`.
    Atan { dst: u32, a: u32 },
    /// `dst = asin a`.
    Asin { dst: u32, a: u32 },
    /// `dst = acos a`.
    Acos { dst: u32, a: u32 },
}

/// A compiled straight-line program: constants in registers
/// `0..consts.len()`, the inputs in the next `n_inputs` registers, then
/// temporaries; [`Program::eval`] runs the instructions and copies the
/// output registers out.
#[derive(Clone, Debug)]
pub struct Program {
    pub(super) consts: Vec<f64>,
    pub(super) n_inputs: usize,
    pub(super) n_regs: usize,
    pub(super) code: Vec<Instr>,
    pub(super) pairs: Vec<(u32, u32)>,
    pub(super) outputs: Vec<u32>,
}

impl Program {
    /// The number of input values [`Program::eval`] expects.
    pub fn n_inputs(&self) -> usize {
        self.n_inputs
    }
    /// The number of outputs.
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }
    /// The size of the register file [`Program::eval`] needs.
    pub fn n_registers(&self) -> usize {
        self.n_regs
    }
    /// The instructions, in execution order.
    pub fn instructions(&self) -> &[Instr] {
        &self.code
    }
    /// The register pairs of the [`Instr::Dot`] instructions.
    pub fn pairs(&self) -> &[(u32, u32)] {
        &self.pairs
    }
    /// The folded constants (loaded into the first registers).
    pub fn constants(&self) -> &[f64] {
        &self.consts
    }
    /// A register file of the right size with the constants loaded (no
    /// instruction ever writes a constant's or an input's register, so they
    /// stay loaded: see [`Program::run`]).
    pub fn registers(&self) -> Vec<f64> {
        let mut r = vec![0.0; self.n_regs];
        r[..self.consts.len()].copy_from_slice(&self.consts);
        r
    }
    /// Where the inputs go in the register file, for [`Program::run`]:
    /// input k is register `input_offset() + k`.
    pub fn input_offset(&self) -> usize {
        self.consts.len()
    }
    /// The register holding each output after [`Program::run`].
    pub fn output_registers(&self) -> &[u32] {
        &self.outputs
    }
    /// Floating-point operations per evaluation: `(additions, subtractions
    /// and negations; multiplications, powers counted once; divisions;
    /// function calls)`. A mul-add counts one addition and one
    /// multiplication, a dot product of k pairs k multiplications and k − 1
    /// or k additions, a sin_cos one call.
    pub fn op_counts(&self) -> (usize, usize, usize, usize) {
        let (mut add, mut mul, mut div, mut fun) = (0, 0, 0, 0);
        for i in &self.code {
            match i {
                Instr::Add { .. } | Instr::Sub { .. } | Instr::Neg { .. } => add += 1,
                Instr::Mul { .. } | Instr::Powi { .. } => mul += 1,
                Instr::MulAdd { .. } => {
                    mul += 1;
                    add += 1;
                }
                Instr::Dot { len, init, .. } => {
                    mul += *len as usize;
                    add += *len as usize - usize::from(*init == NONE);
                }
                Instr::Div { .. } => div += 1,
                _ => fun += 1,
            }
        }
        (add, mul, div, fun)
    }

    /// Evaluate every output at `inputs` (in the order given to
    /// [`super::compile`]), using `regs` as scratch. Allocation-free.
    ///
    /// # Panics
    /// When `inputs.len() != self.n_inputs()`, `regs.len() <
    /// self.n_registers()` or `out.len() != self.n_outputs()`.
    pub fn eval(&self, inputs: &[f64], regs: &mut [f64], out: &mut [f64]) {
        assert_eq!(inputs.len(), self.n_inputs, "wrong number of inputs");
        assert!(regs.len() >= self.n_regs, "register file too small");
        assert_eq!(out.len(), self.outputs.len(), "wrong number of outputs");
        let nc = self.consts.len();
        regs[..nc].copy_from_slice(&self.consts);
        regs[nc..nc + self.n_inputs].copy_from_slice(inputs);
        self.run(regs);
        for (o, &k) in out.iter_mut().zip(&self.outputs) {
            *o = regs[k as usize];
        }
    }

    /// Run the instructions on a register file that already holds the
    /// constants (as [`Program::registers`] returns it) and the inputs (at
    /// [`Program::input_offset`]); the outputs are then in the registers
    /// [`Program::output_registers`] names. The allocation- and copy-free
    /// core of [`Program::eval`], for callers that evaluate in a loop.
    ///
    /// # Panics
    /// When `regs.len() < self.n_registers()`.
    #[inline]
    pub fn run(&self, regs: &mut [f64]) {
        let r = &mut regs[..self.n_regs];
        for ins in &self.code {
            // SAFETY: `Program`s are only built by `Builder::finish`, which
            // gives every operand and destination an index < n_regs, and
            // `r.len() == n_regs` here.
            unsafe { step(r, &self.pairs, *ins) }
        }
    }
}

/// One instruction.
///
/// # Safety
/// Every register index of `ins` (and of its `pairs`) is `< r.len()`, and a
/// dot product's pairs are within `pairs`.
#[inline(always)]
unsafe fn step(r: &mut [f64], pairs: &[(u32, u32)], ins: Instr) {
    macro_rules! g {
        ($i:expr) => {
            *r.get_unchecked($i as usize)
        };
    }
    macro_rules! s {
        ($i:expr, $v:expr) => {{
            let v = $v;
            *r.get_unchecked_mut($i as usize) = v;
        }};
    }
    match ins {
        Instr::Add { dst, a, b } => s!(dst, g!(a) + g!(b)),
        Instr::Sub { dst, a, b } => s!(dst, g!(a) - g!(b)),
        Instr::Mul { dst, a, b } => s!(dst, g!(a) * g!(b)),
        Instr::MulAdd { dst, a, b, c } => s!(dst, g!(a) * g!(b) + g!(c)),
        Instr::Dot {
            dst,
            init,
            start,
            len,
        } => {
            let mut acc = if init == NONE { 0.0 } else { g!(init) };
            let ps = pairs.get_unchecked(start as usize..(start + len) as usize);
            for &(a, b) in ps {
                acc += g!(a) * g!(b);
            }
            s!(dst, acc)
        }
        Instr::Div { dst, a, b } => s!(dst, g!(a) / g!(b)),
        Instr::Neg { dst, a } => s!(dst, -g!(a)),
        Instr::Powi { dst, a, n } => s!(dst, powi(g!(a), n)),
        Instr::Sin { dst, a } => s!(dst, g!(a).sin()),
        Instr::Cos { dst, a } => s!(dst, g!(a).cos()),
        Instr::SinCos { sin, cos, a } => {
            let (sv, cv) = g!(a).sin_cos();
            s!(sin, sv);
            s!(cos, cv);
        }
        Instr::Exp { dst, a } => s!(dst, g!(a).exp()),
        Instr::Ln { dst, a } => s!(dst, g!(a).ln()),
        Instr::Sqrt { dst, a } => s!(dst, g!(a).sqrt()),
        Instr::Atan { dst, a } => s!(dst, g!(a).atan()),
        Instr::Asin { dst, a } => s!(dst, g!(a).asin()),
        Instr::Acos { dst, a } => s!(dst, g!(a).acos()),
    }
}

/// xⁿ by binary powering (exact for small n as repeated multiplication).
#[inline]
pub(super) fn powi(x: f64, n: u32) -> f64 {
    match n {
        0 => 1.0,
        1 => x,
        2 => x * x,
        3 => x * x * x,
        _ => {
            let (mut acc, mut base, mut e) = (1.0, x, n);
            while e > 0 {
                if e & 1 == 1 {
                    acc *= base;
                }
                base *= base;
                e >>= 1;
            }
            acc
        }
    }
}

/// "No register": a dot product without an initial value.
pub(super) const NONE: u32 = u32::MAX;
