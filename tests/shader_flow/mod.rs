//! Where the values of a naga function come from: constants, uniform
//! buffers, or what varies across invocations; and which branches and loop
//! exits uniforms alone decide (tests/uniform_branches.rs says why that
//! matters on lavapipe). Function calls are followed with the sources of
//! their arguments; local variables take everything stored into them, and
//! a value stored inside a branch depends on its condition too.

use naga::{
    AddressSpace, BinaryOperator, Block, Expression, Function, Handle, Literal, Module, Statement,
    UnaryOperator,
};
use std::collections::{BTreeSet, HashMap};

/// What a value depends on, from least to most: a value known here (a
/// literal, or one folded from literals), other constants, uniform
/// buffers, or what varies across invocations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Source {
    Known(Value),
    Constant,
    Uniform,
    Varying,
}

/// A scalar known when the shader is compiled (floats as their bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Value {
    Bool(bool),
    Int(i64),
    Float(u64),
}

impl Source {
    fn join(self, other: Self) -> Self {
        match (self, other) {
            (Self::Known(a), Self::Known(b)) if a == b => self,
            (Self::Known(_), Self::Known(_)) => Self::Constant,
            (Self::Known(_), o) | (o, Self::Known(_)) => o.max(Self::Constant),
            (a, b) => a.max(b),
        }
    }

    fn is_uniform(self) -> bool {
        self == Self::Uniform
    }
}

fn literal(l: &Literal) -> Source {
    Source::Known(match *l {
        Literal::Bool(b) => Value::Bool(b),
        Literal::U32(v) => Value::Int(v.into()),
        Literal::I32(v) => Value::Int(v.into()),
        Literal::F32(v) => Value::Float(f64::from(v).to_bits()),
        Literal::AbstractInt(v) => Value::Int(v),
        _ => return Source::Constant,
    })
}

/// `op` on two known scalars, where it is a comparison or logic.
fn fold(op: BinaryOperator, a: Value, b: Value) -> Option<Value> {
    use BinaryOperator as B;
    Some(match (op, a, b) {
        (B::Equal, a, b) => Value::Bool(a == b),
        (B::NotEqual, a, b) => Value::Bool(a != b),
        (B::Less, Value::Int(a), Value::Int(b)) => Value::Bool(a < b),
        (B::LessEqual, Value::Int(a), Value::Int(b)) => Value::Bool(a <= b),
        (B::Greater, Value::Int(a), Value::Int(b)) => Value::Bool(a > b),
        (B::GreaterEqual, Value::Int(a), Value::Int(b)) => Value::Bool(a >= b),
        (B::LogicalAnd | B::And, Value::Bool(a), Value::Bool(b)) => Value::Bool(a && b),
        (B::LogicalOr | B::InclusiveOr, Value::Bool(a), Value::Bool(b)) => Value::Bool(a || b),
        _ => return None,
    })
}

type Key = (Handle<Function>, Vec<Source>);

/// A function walked with given argument sources: what it returns, what
/// it branches on, and the calls it makes with their argument sources.
#[derive(Clone, Default)]
pub struct Walked {
    returns: Option<Source>,
    findings: BTreeSet<String>,
    calls: BTreeSet<Key>,
}

/// One function being walked with given argument sources.
struct Frame<'f> {
    function: &'f Function,
    args: Vec<Source>,
    locals: Vec<Option<Source>>,
    /// What this walk stored into each local (None: nothing yet).
    stored: Vec<Option<Source>>,
    calls: HashMap<Handle<Expression>, Source>,
    called: BTreeSet<Key>,
    memo: HashMap<Handle<Expression>, Source>,
    returns: Option<Source>,
    name: &'f str,
    findings: BTreeSet<String>,
}

fn join_option(a: Option<Source>, b: Source) -> Option<Source> {
    Some(a.map_or(b, |a| a.join(b)))
}

/// What `s`, computed inside branches decided by `within`, depends on.
fn under(s: Source, within: Option<Source>) -> Source {
    within.map_or(s, |w| s.join(w))
}

pub struct Walk<'m> {
    module: &'m Module,
    done: HashMap<Key, Walked>,
}

impl<'m> Walk<'m> {
    pub fn new(module: &'m Module) -> Self {
        Self {
            module,
            done: HashMap::new(),
        }
    }

    /// Walks `function` until what its locals hold settles.
    pub fn function(&mut self, function: &'m Function, name: &'m str, args: Vec<Source>) -> Walked {
        let mut locals = vec![None; function.local_variables.len()];
        loop {
            let mut frame = Frame {
                function,
                args: args.clone(),
                locals: locals.clone(),
                stored: locals.clone(),
                calls: HashMap::new(),
                called: BTreeSet::new(),
                memo: HashMap::new(),
                returns: None,
                name,
                findings: BTreeSet::new(),
            };
            for (handle, local) in function.local_variables.iter() {
                if let Some(init) = local.init {
                    let s = self.expression(&mut frame, init);
                    frame.stored[handle.index()] = join_option(frame.stored[handle.index()], s);
                }
            }
            self.block(&mut frame, &function.body, None);
            if frame.stored == locals {
                return Walked {
                    returns: frame.returns,
                    findings: frame.findings,
                    calls: frame.called,
                };
            }
            locals = frame.stored;
        }
    }

    fn call(&mut self, handle: Handle<Function>, args: Vec<Source>) -> Source {
        let key = (handle, args.clone());
        if let Some(w) = self.done.get(&key) {
            // Still being walked: a recursive call (WGSL has none).
            return w.returns.unwrap_or(Source::Varying);
        }
        self.done.insert(key.clone(), Walked::default());
        let function = &self.module.functions[handle];
        let name = function.name.as_deref().unwrap_or_default();
        let walked = self.function(function, name, args);
        let returns = walked.returns.unwrap_or(Source::Constant);
        self.done.insert(key, walked);
        returns
    }

    /// The findings of the walk `top` and of every call it makes, with the
    /// argument sources of its settled walk.
    pub fn reachable(&self, top: &Walked) -> BTreeSet<String> {
        let mut found = top.findings.clone();
        let mut seen = BTreeSet::new();
        let mut todo: Vec<Key> = top.calls.iter().cloned().collect();
        while let Some(key) = todo.pop() {
            if seen.insert(key.clone()) {
                let w = &self.done[&key];
                found.extend(w.findings.iter().cloned());
                todo.extend(w.calls.iter().cloned());
            }
        }
        found
    }

    fn known_bool(&mut self, frame: &mut Frame<'m>, h: Handle<Expression>) -> Option<bool> {
        match self.expression(frame, h) {
            Source::Known(Value::Bool(b)) => Some(b),
            _ => None,
        }
    }

    fn expression(&mut self, frame: &mut Frame<'m>, h: Handle<Expression>) -> Source {
        if let Some(&s) = frame.memo.get(&h) {
            return s;
        }
        let e = &frame.function.expressions[h];
        let s = match e {
            Expression::Literal(l) => literal(l),
            Expression::Constant(c) => {
                match &self.module.global_expressions[self.module.constants[*c].init] {
                    Expression::Literal(l) => literal(l),
                    _ => Source::Constant,
                }
            }
            Expression::Override(_) | Expression::ZeroValue(_) => Source::Constant,
            Expression::FunctionArgument(i) => frame.args[*i as usize],
            // A pointer: what a load through it reads.
            Expression::GlobalVariable(g) => match self.module.global_variables[*g].space {
                AddressSpace::Uniform => Source::Uniform,
                _ => Source::Varying,
            },
            Expression::LocalVariable(l) => frame.locals[l.index()].unwrap_or(Source::Constant),
            Expression::CallResult(_) => frame.calls.get(&h).copied().unwrap_or(Source::Varying),
            Expression::Select {
                condition,
                accept,
                reject,
            } => match self.known_bool(frame, *condition) {
                Some(true) => self.expression(frame, *accept),
                Some(false) => self.expression(frame, *reject),
                None => self.join(frame, &[*condition, *accept, *reject]),
            },
            Expression::Binary { op, left, right } => {
                let (a, b) = (self.expression(frame, *left), self.expression(frame, *right));
                match (a, b) {
                    (Source::Known(x), Source::Known(y)) => {
                        fold(*op, x, y).map_or(Source::Constant, Source::Known)
                    }
                    _ => a.join(b).max(Source::Constant),
                }
            }
            Expression::Unary {
                op: UnaryOperator::LogicalNot,
                expr,
            } => match self.expression(frame, *expr) {
                Source::Known(Value::Bool(b)) => Source::Known(Value::Bool(!b)),
                s => s.max(Source::Constant),
            },
            Expression::Load { pointer } => self.expression(frame, *pointer),
            Expression::Compose { .. }
            | Expression::Access { .. }
            | Expression::AccessIndex { .. }
            | Expression::Splat { .. }
            | Expression::Swizzle { .. }
            | Expression::Unary { .. }
            | Expression::Relational { .. }
            | Expression::Math { .. }
            | Expression::As { .. } => {
                let all = operands(e);
                self.join(frame, &all).max(Source::Constant)
            }
            // Textures, derivatives, atomics, array lengths...
            _ => Source::Varying,
        };
        frame.memo.insert(h, s);
        s
    }

    fn join(&mut self, frame: &mut Frame<'m>, hs: &[Handle<Expression>]) -> Source {
        let mut s: Option<Source> = None;
        for &h in hs {
            let e = self.expression(frame, h);
            s = join_option(s, e);
        }
        s.unwrap_or(Source::Constant)
    }

    /// The local variable a pointer expression points into, if any.
    fn local_root(frame: &Frame, mut h: Handle<Expression>) -> Option<usize> {
        loop {
            match frame.function.expressions[h] {
                Expression::LocalVariable(l) => return Some(l.index()),
                Expression::Access { base, .. } | Expression::AccessIndex { base, .. } => h = base,
                _ => return None,
            }
        }
    }

    /// What `condition` depends on; a finding when on uniforms alone.
    fn check(&mut self, frame: &mut Frame<'m>, condition: Handle<Expression>, what: &str) -> Source {
        let source = self.expression(frame, condition);
        if source.is_uniform() {
            let mut uniforms = BTreeSet::new();
            self.uniforms(frame, condition, &mut uniforms);
            let list: Vec<_> = uniforms.into_iter().collect();
            let finding = format!(
                "fn {}{:?}: {what} decided by {}",
                frame.name,
                frame.args,
                list.join(", ")
            );
            frame.findings.insert(finding);
        }
        source
    }

    /// The uniforms an expression reads, by name, for the message.
    fn uniforms(&self, frame: &Frame, h: Handle<Expression>, out: &mut BTreeSet<String>) {
        let e = &frame.function.expressions[h];
        match e {
            Expression::Load { pointer } => {
                let mut chain = Vec::new();
                let mut p = *pointer;
                loop {
                    match &frame.function.expressions[p] {
                        Expression::AccessIndex { base, index } => {
                            chain.push(*index);
                            p = *base;
                        }
                        Expression::Access { base, index } => {
                            self.uniforms(frame, *index, out);
                            p = *base;
                        }
                        Expression::GlobalVariable(g) => {
                            let var = &self.module.global_variables[*g];
                            if var.space == AddressSpace::Uniform {
                                let mut name = var.name.clone().unwrap_or_default();
                                let mut ty = var.ty;
                                for &i in chain.iter().rev() {
                                    match &self.module.types[ty].inner {
                                        naga::TypeInner::Struct { members, .. } => {
                                            let m = &members[i as usize];
                                            name += &format!(".{}", m.name.clone().unwrap_or_default());
                                            ty = m.ty;
                                        }
                                        _ => break,
                                    }
                                }
                                out.insert(name);
                            }
                            return;
                        }
                        Expression::LocalVariable(l) => {
                            if frame.locals[l.index()] == Some(Source::Uniform) {
                                out.insert(format!(
                                    "var {}",
                                    frame.function.local_variables[*l]
                                        .name
                                        .clone()
                                        .unwrap_or_default()
                                ));
                            }
                            return;
                        }
                        _ => return,
                    }
                }
            }
            Expression::FunctionArgument(i) => {
                if frame.args[*i as usize] == Source::Uniform {
                    out.insert(format!("argument {i}"));
                }
            }
            Expression::CallResult(f) => {
                if frame.calls.get(&h) == Some(&Source::Uniform) {
                    out.insert(format!(
                        "{}()",
                        self.module.functions[*f].name.clone().unwrap_or_default()
                    ));
                }
            }
            _ => {
                for c in operands(e) {
                    self.uniforms(frame, c, out);
                }
            }
        }
    }

    /// Walks the statements of `block`, inside branches decided by
    /// `within` (what a value stored there depends on, besides itself).
    fn block(&mut self, frame: &mut Frame<'m>, block: &'m Block, within: Option<Source>) {
        for statement in block.iter() {
            match statement {
                Statement::Block(b) => self.block(frame, b, within),
                Statement::If {
                    condition,
                    accept,
                    reject,
                } => match self.known_bool(frame, *condition) {
                    Some(true) => self.block(frame, accept, within),
                    Some(false) => self.block(frame, reject, within),
                    None => {
                        let c = self.check(frame, *condition, "an `if` (or `&&`, `||`)");
                        self.block(frame, accept, join_option(within, c));
                        self.block(frame, reject, join_option(within, c));
                    }
                },
                Statement::Switch { selector, cases } => {
                    let c = self.check(frame, *selector, "a `switch`");
                    for case in cases {
                        self.block(frame, &case.body, join_option(within, c));
                    }
                }
                Statement::Loop {
                    body,
                    continuing,
                    break_if,
                } => {
                    // Its counters merge at the loop's head, whatever
                    // branch the loop sits in: lavapipe folds a uniform
                    // bound inside a branch on varyings too.
                    self.block(frame, body, None);
                    self.block(frame, continuing, None);
                    if let Some(b) = break_if {
                        self.check(frame, *b, "a loop's exit");
                    }
                }
                Statement::Return { value: Some(v) } => {
                    let s = under(self.expression(frame, *v), within);
                    frame.returns = join_option(frame.returns, s);
                }
                Statement::Store { pointer, value } => {
                    if let Some(l) = Self::local_root(frame, *pointer) {
                        let mut s = under(self.expression(frame, *value), within);
                        // Into an element: its index counts too.
                        if !matches!(frame.function.expressions[*pointer], Expression::LocalVariable(_)) {
                            s = s.join(self.expression(frame, *pointer));
                        }
                        frame.stored[l] = join_option(frame.stored[l], s);
                    }
                }
                Statement::Call {
                    function,
                    arguments,
                    result,
                } => {
                    let args: Vec<Source> = arguments.iter().map(|&a| self.expression(frame, a)).collect();
                    let s = self.call(*function, args.clone());
                    frame.called.insert((*function, args));
                    if let Some(r) = result {
                        frame.calls.insert(*r, under(s, within));
                    }
                }
                _ => {}
            }
        }
    }
}

/// The operands of an expression that computes a value from others.
fn operands(e: &Expression) -> Vec<Handle<Expression>> {
    match e {
        Expression::Compose { components, .. } => components.clone(),
        Expression::Access { base, index } => vec![*base, *index],
        Expression::AccessIndex { base, .. } => vec![*base],
        Expression::Splat { value, .. } => vec![*value],
        Expression::Swizzle { vector, .. } => vec![*vector],
        Expression::Load { pointer } => vec![*pointer],
        Expression::Unary { expr, .. } | Expression::As { expr, .. } => vec![*expr],
        Expression::Binary { left, right, .. } => vec![*left, *right],
        Expression::Select {
            condition,
            accept,
            reject,
        } => vec![*condition, *accept, *reject],
        Expression::Relational { argument, .. } => vec![*argument],
        Expression::Math {
            arg,
            arg1,
            arg2,
            arg3,
            ..
        } => [Some(*arg), *arg1, *arg2, *arg3].into_iter().flatten().collect(),
        _ => Vec::new(),
    }
}
