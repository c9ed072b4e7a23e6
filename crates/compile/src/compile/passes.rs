//! From the node graph to a [`Program`]: the passes, in the order
//! [`Builder::finish`] runs them.
//!
//! 1. [`Graph::liveness`]: dead nodes are dropped;
//! 2. [`Graph::sin_cos_pairs`]: sin and cos of one argument become one
//!    `sin_cos`;
//! 3. [`Graph::fuse_dot_products`]: chains of multiply-adds become one dot
//!    product;
//! 4. [`Graph::fixed_registers`]: constants and inputs get their registers;
//! 5. [`Graph::dying_at`]: the last use of every value (linear scan,
//!    Poletto & Sarkar, TOPLAS 21 (1999));
//! 6. [`Graph::emit`]: instructions in node order, a register reused as
//!    soon as its value dies.

use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::builder::{Builder, Node};
use super::program::{Instr, Program, NONE};

/// A dot product `init + Σ a·b` over node ids, before register allocation.
#[derive(Clone, Debug)]
struct Dot {
    init: Option<u32>,
    terms: Vec<(u32, u32)>,
}

/// What the passes know of the graph, filled in as they run.
struct Graph<'a> {
    nodes: &'a [Node],
    index: &'a FxHashMap<Node, u32>,
    outs: &'a [u32],
    live: Vec<bool>,
    /// sin ↔ cos of one argument, both live.
    partner: FxHashMap<u32, u32>,
    /// The fused dot products, by the node they replace.
    dots: FxHashMap<u32, Dot>,
    /// Nodes folded into a dot product (not emitted).
    absorbed: Vec<bool>,
}

impl Builder<'_> {
    /// The passes of the module docs, in order.
    pub(super) fn finish(self, outs: &[u32]) -> Program {
        let nn = self.nodes.len();
        let mut g = Graph {
            nodes: &self.nodes,
            index: &self.index,
            outs,
            live: vec![false; nn],
            partner: FxHashMap::default(),
            dots: FxHashMap::default(),
            absorbed: vec![false; nn],
        };
        g.liveness();
        g.sin_cos_pairs();
        g.fuse_dot_products();
        let (reg, consts) = g.fixed_registers();
        let dying = g.dying_at();
        g.emit(reg, consts, dying)
    }
}

impl Graph<'_> {
    fn fixed(&self, id: u32) -> bool {
        matches!(self.nodes[id as usize], Node::Const(_) | Node::Input(_))
    }

    fn emitted(&self, id: usize) -> bool {
        self.live[id] && !self.absorbed[id]
    }

    /// Mark the nodes the outputs depend on (nodes are in topological
    /// order: operands first).
    fn liveness(&mut self) {
        for &o in self.outs {
            self.live[o as usize] = true;
        }
        for id in (0..self.nodes.len()).rev() {
            if self.live[id] {
                for a in self.nodes[id].operands() {
                    self.live[a as usize] = true;
                }
            }
        }
    }

    /// sin and cos of one argument: one sin_cos, at the first of the two.
    fn sin_cos_pairs(&mut self) {
        for id in 0..self.nodes.len() {
            if let (true, Node::Sin(a)) = (self.live[id], self.nodes[id]) {
                if let Some(&c) = self.index.get(&Node::Cos(a)) {
                    if self.live[c as usize] {
                        self.partner.insert(id as u32, c);
                        self.partner.insert(c, id as u32);
                    }
                }
            }
        }
    }

    /// How many live nodes (and outputs) read each node.
    fn use_counts(&self) -> Vec<u32> {
        let mut uses = vec![0u32; self.nodes.len()];
        for (id, node) in self.nodes.iter().enumerate() {
            if self.live[id] {
                for a in node.operands() {
                    uses[a as usize] += 1;
                }
            }
        }
        for &o in self.outs {
            uses[o as usize] += 1;
        }
        uses
    }

    /// Dot products: a multiply-add (or a sum of products) whose
    /// accumulated operand is a product or a dot product used nowhere
    /// else absorbs it, so a chain of k multiply-adds is one instruction
    /// with a tight loop (summed in the same order).
    fn fuse_dot_products(&mut self) {
        let uses = self.use_counts();
        for id in 0..self.nodes.len() {
            if !self.live[id] {
                continue;
            }
            let dot = match self.nodes[id] {
                Node::MulAdd(x, y, c) => {
                    let mut d = match self.take_dot(c, &uses) {
                        Some(d) => d,
                        None => Dot {
                            init: Some(c),
                            terms: Vec::new(),
                        },
                    };
                    d.terms.push((x, y));
                    d
                }
                Node::Add(x, y) => {
                    let (dx, dy) = (self.as_dot(x, &uses), self.as_dot(y, &uses));
                    match (dx, dy) {
                        (Some(mut dx), Some(dy)) if dx.init.is_none() || dy.init.is_none() => {
                            self.absorb(x);
                            self.absorb(y);
                            dx.init = dx.init.or(dy.init);
                            dx.terms.extend(dy.terms);
                            dx
                        }
                        (Some(mut d), None) if d.init.is_none() => {
                            self.absorb(x);
                            d.init = Some(y);
                            d
                        }
                        (None, Some(mut d)) if d.init.is_none() => {
                            self.absorb(y);
                            d.init = Some(x);
                            d
                        }
                        _ => continue,
                    }
                }
                _ => continue,
            };
            self.dots.insert(id as u32, dot);
        }
    }

    /// Node `c` as a dot product, when it can be absorbed: read once, a
    /// product or an earlier dot product.
    fn as_dot(&self, c: u32, uses: &[u32]) -> Option<Dot> {
        if uses[c as usize] != 1 || self.fixed(c) {
            return None;
        }
        match self.nodes[c as usize] {
            Node::Mul(x, y) => Some(Dot {
                init: None,
                terms: vec![(x, y)],
            }),
            Node::MulAdd(..) | Node::Add(..) => self.dots.get(&c).cloned(),
            _ => None,
        }
    }

    /// [`Graph::as_dot`], absorbing `c` when it is one.
    fn take_dot(&mut self, c: u32, uses: &[u32]) -> Option<Dot> {
        let d = self.as_dot(c, uses)?;
        self.absorb(c);
        Some(d)
    }

    fn absorb(&mut self, c: u32) {
        self.absorbed[c as usize] = true;
        self.dots.remove(&c);
    }

    /// The operands an emitted node reads.
    fn operands(&self, id: u32) -> SmallVec<[u32; 3]> {
        match self.dots.get(&id) {
            Some(d) => d
                .init
                .iter()
                .copied()
                .chain(d.terms.iter().flat_map(|&(a, b)| [a, b]))
                .collect(),
            None => self.nodes[id as usize].operands(),
        }
    }

    /// Constants and inputs get fixed registers: the constants first, then
    /// the inputs; every other node `u32::MAX` (not yet allocated).
    fn fixed_registers(&self) -> (Vec<u32>, Vec<f64>) {
        let nn = self.nodes.len();
        let mut reg = vec![u32::MAX; nn];
        let mut consts = Vec::new();
        for (r, (&live, node)) in reg.iter_mut().zip(self.live.iter().zip(self.nodes)) {
            if let (true, Node::Const(b)) = (live, node) {
                *r = consts.len() as u32;
                consts.push(f64::from_bits(*b));
            }
        }
        let nc = consts.len() as u32;
        for (r, node) in reg.iter_mut().zip(self.nodes) {
            if let Node::Input(i) = *node {
                *r = nc + i;
            }
        }
        (reg, consts)
    }

    /// An instruction's position: its node's, a sin_cos's the earlier of
    /// the pair.
    fn position(&self, id: u32) -> u32 {
        match self.partner.get(&id) {
            Some(&p) => id.min(p),
            None => id,
        }
    }

    /// For every position, the nodes whose last use is there (their
    /// registers are free from then on); outputs never die.
    fn dying_at(&self) -> Vec<Vec<u32>> {
        let nn = self.nodes.len();
        let mut last = vec![0u32; nn];
        for id in 0..nn {
            if self.emitted(id) {
                for a in self.operands(id as u32) {
                    last[a as usize] = last[a as usize].max(self.position(id as u32));
                }
            }
        }
        for &o in self.outs {
            last[o as usize] = u32::MAX;
        }
        let mut dying: Vec<Vec<u32>> = vec![Vec::new(); nn];
        for id in 0..nn {
            if self.emitted(id) && !self.fixed(id as u32) && (last[id] as usize) < nn {
                dying[last[id] as usize].push(id as u32);
            }
        }
        dying
    }

    /// The instructions in node order, each result in a register freed by
    /// a value dying there, else a new one.
    fn emit(&self, mut reg: Vec<u32>, consts: Vec<f64>, dying: Vec<Vec<u32>>) -> Program {
        let n_inputs = self
            .nodes
            .iter()
            .filter(|n| matches!(n, Node::Input(_)))
            .count();
        let mut free: Vec<u32> = Vec::new();
        let mut next = consts.len() as u32 + n_inputs as u32;
        let mut code = Vec::new();
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut alloc = |free: &mut Vec<u32>| -> u32 {
            free.pop().unwrap_or_else(|| {
                next += 1;
                next - 1
            })
        };
        for id in 0..self.nodes.len() {
            if !self.emitted(id) || self.fixed(id as u32) || reg[id] != u32::MAX {
                continue; // dead, absorbed, preloaded, or the second of a sin_cos
            }
            let node = self.nodes[id];
            let ops: SmallVec<[u32; 3]> =
                node.operands().iter().map(|&a| reg[a as usize]).collect();
            let dot = self.dots.get(&(id as u32)).map(|d| {
                let start = pairs.len() as u32;
                pairs.extend(
                    d.terms
                        .iter()
                        .map(|&(a, b)| (reg[a as usize], reg[b as usize])),
                );
                (
                    d.init.map_or(NONE, |i| reg[i as usize]),
                    start,
                    d.terms.len() as u32,
                )
            });
            // Operands dying here may be reused for the result.
            for &d in &dying[id] {
                free.push(reg[d as usize]);
            }
            if let Some(&p) = self.partner.get(&(id as u32)) {
                let s_id = if matches!(node, Node::Sin(_)) {
                    id as u32
                } else {
                    p
                };
                let c_id = if s_id == id as u32 { p } else { id as u32 };
                let rs = alloc(&mut free);
                let rc = alloc(&mut free);
                reg[s_id as usize] = rs;
                reg[c_id as usize] = rc;
                code.push(Instr::SinCos {
                    sin: rs,
                    cos: rc,
                    a: ops[0],
                });
                continue;
            }
            let dst = alloc(&mut free);
            reg[id] = dst;
            if let Some((init, start, len)) = dot {
                code.push(dot_instr(dst, init, start, len, &mut pairs));
            } else if let Some(instr) = node_instr(node, dst, &ops) {
                code.push(instr);
            }
        }
        let outputs = self.outs.iter().map(|&o| reg[o as usize]).collect();
        Program {
            consts,
            n_inputs,
            n_regs: next as usize,
            code,
            pairs,
            outputs,
        }
    }
}

/// A fused dot product's instruction: a product or a multiply-add when it
/// has one term (its pair then dropped again), else a `Dot` over `pairs`.
fn dot_instr(dst: u32, init: u32, start: u32, len: u32, pairs: &mut Vec<(u32, u32)>) -> Instr {
    let one = pairs[start as usize];
    match (len, init) {
        (1, NONE) => Instr::Mul {
            dst,
            a: one.0,
            b: one.1,
        },
        (1, c) => {
            pairs.pop();
            Instr::MulAdd {
                dst,
                a: one.0,
                b: one.1,
                c,
            }
        }
        _ => Instr::Dot {
            dst,
            init,
            start,
            len,
        },
    }
}

/// The instruction of one node, its operands in registers `r`; `None` for
/// constants and inputs (preloaded).
fn node_instr(node: Node, dst: u32, r: &[u32]) -> Option<Instr> {
    Some(match node {
        Node::Add(..) => Instr::Add {
            dst,
            a: r[0],
            b: r[1],
        },
        Node::Sub(..) => Instr::Sub {
            dst,
            a: r[0],
            b: r[1],
        },
        Node::Mul(..) => Instr::Mul {
            dst,
            a: r[0],
            b: r[1],
        },
        Node::MulAdd(..) => Instr::MulAdd {
            dst,
            a: r[0],
            b: r[1],
            c: r[2],
        },
        Node::Div(..) => Instr::Div {
            dst,
            a: r[0],
            b: r[1],
        },
        Node::Neg(_) => Instr::Neg { dst, a: r[0] },
        Node::Powi(_, n) => Instr::Powi { dst, a: r[0], n },
        Node::Sin(_) => Instr::Sin { dst, a: r[0] },
        Node::Cos(_) => Instr::Cos { dst, a: r[0] },
        Node::Exp(_) => Instr::Exp { dst, a: r[0] },
        Node::Ln(_) => Instr::Ln { dst, a: r[0] },
        Node::Sqrt(_) => Instr::Sqrt { dst, a: r[0] },
        Node::Atan(_) => Instr::Atan { dst, a: r[0] },
        Node::Asin(_) => Instr::Asin { dst, a: r[0] },
        Node::Acos(_) => Instr::Acos { dst, a: r[0] },
        Node::Const(_) | Node::Input(_) => return None,
    })
}
