//! An expression graph with hash-consing: the representation code generation works on.
//!
//! Running the recursion (RNEA, `Jᵀ𝔍J`, …) on [`Sx`] values records every operation once:
//! an operation on operands already seen returns the existing node (common-subexpression
//! elimination by construction), constants fold, and `0`/`±1` operands vanish — so a joint axis
//! along `z` or a `cos(π/2) = 0` from a DH twist costs nothing in the generated code. Nothing is
//! expanded, so the size grows like the recursion (linearly in the joints for `τ`), not like the
//! expanded polynomial.

use super::poly::{Poly, Var};
use super::ring::Ring;
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// An input of generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Input {
    /// `q[i]`.
    Q(u16),
    /// `v[i]`.
    V(u16),
    /// `a[i]`.
    A(u16),
    /// `params[k]` (index in the parameter table).
    Param(u16),
}

/// One node of the graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// A constant (bit pattern of the `f64`).
    Const(u64),
    /// An input.
    In(Input),
    /// `cos(q[i])`.
    Cos(u16),
    /// `sin(q[i])`.
    Sin(u16),
    /// `a + b`.
    Add(u32, u32),
    /// `a − b`.
    Sub(u32, u32),
    /// `a · b`.
    Mul(u32, u32),
    /// `−a`.
    Neg(u32),
}

/// The graph: nodes in creation order (operands before their uses) and the hash-consing table.
#[derive(Debug, Default)]
pub struct Dag {
    /// The nodes.
    pub nodes: Vec<Op>,
    table: HashMap<Op, u32>,
}

thread_local! {
    static NODE_LIMIT: std::cell::Cell<usize> = const { std::cell::Cell::new(usize::MAX) };
    static NODES_OVER: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` with at most `limit` nodes per graph; `None` when a graph grew past it (the
/// computation then runs on without growing memory and its result is discarded).
pub fn with_node_limit<T>(limit: usize, f: impl FnOnce() -> T) -> Option<T> {
    let old = NODE_LIMIT.with(|l| l.replace(limit));
    NODES_OVER.with(|o| o.set(false));
    let out = f();
    NODE_LIMIT.with(|l| l.set(old));
    let over = NODES_OVER.with(|o| o.replace(false));
    (!over).then_some(out)
}

impl Dag {
    fn intern(&mut self, op: Op) -> u32 {
        if let Some(&id) = self.table.get(&op) {
            return id;
        }
        if self.nodes.len() >= NODE_LIMIT.with(|l| l.get()).max(1) {
            NODES_OVER.with(|o| o.set(true));
            return 0;
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(op);
        self.table.insert(op, id);
        id
    }
}

/// A shared graph.
pub type Graph = Rc<RefCell<Dag>>;

/// A value in the expression graph: a folded constant or a node.
#[derive(Clone, Debug)]
pub enum Sx {
    /// A constant, folded.
    C(f64),
    /// A node of the graph.
    N(Graph, u32),
}

impl Sx {
    /// A new node in `g`.
    pub fn node(g: &Graph, op: Op) -> Sx {
        let id = g.borrow_mut().intern(op);
        Sx::N(g.clone(), id)
    }
    /// The node id; constants are interned into `g`.
    pub fn id_in(&self, g: &Graph) -> u32 {
        match self {
            Sx::C(c) => g.borrow_mut().intern(Op::Const(c.to_bits())),
            Sx::N(_, id) => *id,
        }
    }
    fn graph<'a>(a: &'a Sx, b: &'a Sx) -> &'a Graph {
        match (a, b) {
            (Sx::N(g, _), _) | (_, Sx::N(g, _)) => g,
            _ => unreachable!("constants fold before reaching the graph"),
        }
    }
    fn binary(a: &Sx, b: &Sx, make: impl Fn(u32, u32) -> Op) -> Sx {
        let g = Sx::graph(a, b).clone();
        let (x, y) = (a.id_in(&g), b.id_in(&g));
        Sx::node(&g, make(x, y))
    }
    fn neg_inner(&self) -> Option<Sx> {
        if let Sx::N(g, id) = self {
            if let Op::Neg(x) = g.borrow().nodes[*id as usize] {
                return Some(Sx::N(g.clone(), x));
            }
        }
        None
    }
}

impl Ring for Sx {
    fn constant(x: f64) -> Self {
        Sx::C(x)
    }
    fn add(&self, o: &Self) -> Self {
        match (self, o) {
            (Sx::C(a), Sx::C(b)) => Sx::C(a + b),
            (Sx::C(z), x) | (x, Sx::C(z)) if *z == 0.0 => x.clone(),
            (Sx::C(k), x) | (x, Sx::C(k)) if *k < 0.0 => x.sub(&Sx::C(-k)),
            _ => {
                if let Some(y) = o.neg_inner() {
                    return self.sub(&y);
                }
                if let Some(x) = self.neg_inner() {
                    return o.sub(&x);
                }
                let (a, b) = order(self, o);
                Sx::binary(a, b, Op::Add)
            }
        }
    }
    fn sub(&self, o: &Self) -> Self {
        match (self, o) {
            (Sx::C(a), Sx::C(b)) => Sx::C(a - b),
            (x, Sx::C(z)) if *z == 0.0 => x.clone(),
            (Sx::C(z), x) if *z == 0.0 => x.neg(),
            (Sx::N(_, a), Sx::N(_, b)) if a == b => Sx::C(0.0),
            _ => {
                if let Some(y) = o.neg_inner() {
                    return self.add(&y);
                }
                Sx::binary(self, o, Op::Sub)
            }
        }
    }
    fn mul(&self, o: &Self) -> Self {
        match (self, o) {
            (Sx::C(a), Sx::C(b)) => Sx::C(a * b),
            (Sx::C(z), _) | (_, Sx::C(z)) if *z == 0.0 => Sx::C(0.0),
            (Sx::C(k), x) | (x, Sx::C(k)) if *k == 1.0 => x.clone(),
            (Sx::C(k), x) | (x, Sx::C(k)) if *k == -1.0 => x.neg(),
            _ => {
                // Pull signs out so that products of negated values share nodes.
                match (self.neg_inner(), o.neg_inner()) {
                    (Some(x), Some(y)) => return x.mul(&y),
                    (Some(x), None) => return x.mul(o).neg(),
                    (None, Some(y)) => return self.mul(&y).neg(),
                    _ => {}
                }
                if let (Sx::C(k), x) | (x, Sx::C(k)) = (self, o) {
                    if *k < 0.0 {
                        return x.mul(&Sx::C(-k)).neg();
                    }
                }
                let (a, b) = order(self, o);
                Sx::binary(a, b, Op::Mul)
            }
        }
    }
    fn neg(&self) -> Self {
        match self {
            Sx::C(a) => Sx::C(-a),
            Sx::N(g, id) => {
                if let Some(x) = self.neg_inner() {
                    return x;
                }
                Sx::node(g, Op::Neg(*id))
            }
        }
    }
    fn is_zero(&self) -> bool {
        matches!(self, Sx::C(z) if *z == 0.0)
    }
}

/// Commutative operands in a fixed order (constants first, then by node id).
fn order<'a>(a: &'a Sx, b: &'a Sx) -> (&'a Sx, &'a Sx) {
    match (a, b) {
        (Sx::N(_, x), Sx::N(_, y)) if y < x => (b, a),
        (Sx::N(..), Sx::C(_)) => (b, a),
        _ => (a, b),
    }
}

/// The operation count of the code that computes `outputs`: additions, subtractions,
/// multiplications, negations and `sin`/`cos` evaluations reachable from them.
pub fn op_count(g: &Graph, outputs: &[Sx]) -> usize {
    live_nodes(g, outputs)
        .iter()
        .filter(|&&id| !matches!(g.borrow().nodes[id as usize], Op::Const(_) | Op::In(_)))
        .count()
}

/// The nodes reachable from `outputs`, in creation (topological) order.
pub fn live_nodes(g: &Graph, outputs: &[Sx]) -> Vec<u32> {
    let dag = g.borrow();
    let mut live = vec![false; dag.nodes.len()];
    let mut stack: Vec<u32> = outputs
        .iter()
        .filter_map(|o| match o {
            Sx::N(_, id) => Some(*id),
            Sx::C(_) => None,
        })
        .collect();
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut live[id as usize], true) {
            continue;
        }
        match dag.nodes[id as usize] {
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => {
                stack.push(a);
                stack.push(b);
            }
            Op::Neg(a) => stack.push(a),
            _ => {}
        }
    }
    (0..dag.nodes.len() as u32)
        .filter(|&i| live[i as usize])
        .collect()
}

/// Evaluates the graph numerically (the reference interpreter the tests compare generated code
/// with).
pub fn eval(g: &Graph, outputs: &[Sx], input: &impl Fn(Input) -> f64) -> Vec<f64> {
    let dag = g.borrow();
    let mut val = vec![0.0; dag.nodes.len()];
    for (i, op) in dag.nodes.iter().enumerate() {
        let at = |k: u32| val[k as usize];
        val[i] = match *op {
            Op::Const(b) => f64::from_bits(b),
            Op::In(x) => input(x),
            Op::Cos(k) => input(Input::Q(k)).cos(),
            Op::Sin(k) => input(Input::Q(k)).sin(),
            Op::Add(a, b) => at(a) + at(b),
            Op::Sub(a, b) => at(a) - at(b),
            Op::Mul(a, b) => at(a) * at(b),
            Op::Neg(a) => -at(a),
        };
    }
    outputs
        .iter()
        .map(|o| match o {
            Sx::C(c) => *c,
            Sx::N(_, id) => val[*id as usize],
        })
        .collect()
}

/// Converts a canonical polynomial into the graph (monomials as shared power products), for
/// quantities that are computed in the polynomial form (Christoffel symbols, the Lagrangian).
pub fn from_poly(g: &Graph, p: &Poly) -> Sx {
    let var = |v: Var| -> Sx {
        match v {
            Var::Param(k) => Sx::node(g, Op::In(Input::Param(k))),
            Var::Cos(mask) => Sx::node(g, Op::Cos(mask.trailing_zeros() as u16)),
            Var::Sin(mask) => Sx::node(g, Op::Sin(mask.trailing_zeros() as u16)),
            Var::Q(i) => Sx::node(g, Op::In(Input::Q(i))),
            Var::Qd(i) => Sx::node(g, Op::In(Input::V(i))),
            Var::Qdd(i) => Sx::node(g, Op::In(Input::A(i))),
        }
    };
    let mut sum = Sx::C(0.0);
    for (mono, coef) in p.terms() {
        let mut t = Sx::C(*coef);
        for (v, e) in mono {
            let x = var(*v);
            let mut pw = x.clone();
            for _ in 1..*e {
                pw = pw.mul(&x);
            }
            t = t.mul(&pw);
        }
        sum = sum.add(&t);
    }
    sum
}
