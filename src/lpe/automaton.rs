//! An expression's tree made into a deterministic automaton over a scene's events
//! ([`Alphabet`]): a Thompson automaton first, then its subsets, so that following a path
//! is one table lookup per event and per expression. State 0 is the dead state (no path
//! that went through it can match), so a render can tell when an expression is done with.

use super::LpeError;
use super::alphabet::{Alphabet, Symbol};
use super::parse::{EventPattern, Node};
use std::collections::{BTreeSet, HashMap};

/// The most states an expression's automaton may have.
pub const MAX_STATES: usize = 4096;

/// A deterministic automaton over an alphabet's symbols.
#[derive(Clone, Debug)]
pub struct Dfa {
    /// Symbols in the alphabet.
    symbols: usize,
    /// `next[state * symbols + symbol]`.
    next: Vec<u16>,
    /// Whether each state accepts.
    accept: Vec<bool>,
    /// The state after the camera's event.
    after_camera: u16,
}

impl Dfa {
    /// The automaton of `node` over `alphabet`'s symbols; `Err` where it would be too big.
    pub fn new(node: &Node, alphabet: &Alphabet) -> Result<Dfa, LpeError> {
        let symbols = alphabet.len();
        let mut nfa = Nfa::default();
        let start = nfa.state();
        let end = nfa.add(node, start, alphabet);
        // Subsets of NFA states, the dead (empty) one first.
        let mut ids: HashMap<BTreeSet<usize>, u16> = HashMap::new();
        let mut sets: Vec<BTreeSet<usize>> = vec![];
        let dead = BTreeSet::new();
        ids.insert(dead.clone(), 0);
        sets.push(dead);
        let first = nfa.closure([start].into());
        ids.insert(first.clone(), 1);
        sets.push(first);
        let mut next = vec![];
        let mut done = 0;
        while done < sets.len() {
            let set = sets[done].clone();
            for s in 0..symbols {
                let moved: BTreeSet<usize> = set
                    .iter()
                    .flat_map(|&q| nfa.edges[q].iter())
                    .filter(|(on, _)| on.as_ref().is_some_and(|m| m[s]))
                    .map(|&(_, to)| to)
                    .collect();
                let target = nfa.closure(moved);
                let id = match ids.get(&target) {
                    Some(&id) => id,
                    None => {
                        if sets.len() >= MAX_STATES {
                            return Err(LpeError::new(
                                1,
                                "the expression is too complex for this scene",
                                "write it shorter, or split it into several expressions",
                            ));
                        }
                        let id = sets.len() as u16;
                        ids.insert(target.clone(), id);
                        sets.push(target);
                        id
                    }
                };
                next.push(id);
            }
            done += 1;
        }
        let accept = sets.iter().map(|s| s.contains(&end)).collect();
        let mut dfa = Dfa {
            symbols,
            next,
            accept,
            after_camera: 0,
        };
        dfa.after_camera = dfa.step(1, alphabet.camera());
        Ok(dfa)
    }

    /// The state after `symbol` from `state`.
    #[inline]
    pub fn step(&self, state: u16, symbol: Symbol) -> u16 {
        self.next[state as usize * self.symbols + symbol.0 as usize]
    }

    /// Whether a path that has come to `state` matches.
    #[inline]
    pub fn accepts(&self, state: u16) -> bool {
        self.accept[state as usize]
    }

    /// The state of a path that has left the camera.
    #[inline]
    pub fn after_camera(&self) -> u16 {
        self.after_camera
    }

    /// Whether some path the renderer makes (the camera, any scattering events, then a
    /// light) matches.
    pub fn matches_some_path(&self, alphabet: &Alphabet) -> bool {
        let mut seen = vec![false; self.accept.len()];
        let mut todo = vec![self.after_camera];
        seen[self.after_camera as usize] = true;
        while let Some(s) = todo.pop() {
            if alphabet.lights().any(|l| self.accepts(self.step(s, l))) {
                return true;
            }
            for sym in alphabet.scatterings() {
                let t = self.step(s, sym);
                if !seen[t as usize] {
                    seen[t as usize] = true;
                    todo.push(t);
                }
            }
        }
        false
    }

    /// How many states it has (the dead one included).
    pub fn states(&self) -> usize {
        self.accept.len()
    }
}

/// A Thompson automaton: each edge on a set of symbols (`None`: an empty move).
#[derive(Default)]
struct Nfa {
    edges: Vec<Vec<(Option<Vec<bool>>, usize)>>,
}

impl Nfa {
    fn state(&mut self) -> usize {
        self.edges.push(vec![]);
        self.edges.len() - 1
    }

    fn edge(&mut self, from: usize, on: Option<Vec<bool>>, to: usize) {
        self.edges[from].push((on, to));
    }

    /// Adds `node` from state `from`; returns the state it ends in.
    fn add(&mut self, node: &Node, from: usize, alphabet: &Alphabet) -> usize {
        match node {
            Node::Event(p) => {
                let to = self.state();
                self.edge(
                    from,
                    Some(symbols_of(alphabet, |s| alphabet.matches(p, s))),
                    to,
                );
                to
            }
            Node::Set { items, negated } => {
                let any = |s: Symbol| items.iter().any(|p: &EventPattern| alphabet.matches(p, s));
                let to = self.state();
                self.edge(from, Some(symbols_of(alphabet, |s| any(s) != *negated)), to);
                to
            }
            Node::Seq(parts) => parts.iter().fold(from, |at, p| self.add(p, at, alphabet)),
            Node::Alt(alts) => {
                let to = self.state();
                for a in alts {
                    let end = self.add(a, from, alphabet);
                    self.edge(end, None, to);
                }
                to
            }
            Node::Repeat { node, min, max } => {
                let mut at = from;
                for _ in 0..*min {
                    at = self.add(node, at, alphabet);
                }
                match max {
                    None => {
                        // Any number more: a loop through one copy.
                        let loop_start = self.state();
                        self.edge(at, None, loop_start);
                        let end = self.add(node, loop_start, alphabet);
                        self.edge(end, None, loop_start);
                        loop_start
                    }
                    Some(max) => {
                        let to = self.state();
                        self.edge(at, None, to);
                        for _ in *min..*max {
                            at = self.add(node, at, alphabet);
                            self.edge(at, None, to);
                        }
                        to
                    }
                }
            }
        }
    }

    /// The states reachable from `set` by empty moves.
    fn closure(&self, set: BTreeSet<usize>) -> BTreeSet<usize> {
        let mut out = set.clone();
        let mut todo: Vec<usize> = set.into_iter().collect();
        while let Some(q) = todo.pop() {
            for (on, to) in &self.edges[q] {
                if on.is_none() && out.insert(*to) {
                    todo.push(*to);
                }
            }
        }
        out
    }
}

fn symbols_of(alphabet: &Alphabet, f: impl Fn(Symbol) -> bool) -> Vec<bool> {
    (0..alphabet.len()).map(|i| f(Symbol(i as u16))).collect()
}
