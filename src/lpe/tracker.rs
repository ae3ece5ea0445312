//! One sample's path followed through every expression at once: each expression's state
//! after the events so far, and the light each has gathered. The path tracer reports its
//! events to it (it is a [`PathRecorder`] that wants events and no records).

use super::LpeSet;
use crate::bsdf::Lobe;
use crate::integrator::path_explain::{PathEnd, PathRecorder, VertexRecord};
use crate::math::Color;

/// The most expressions rendered at once.
pub const MAX_LAYERS: usize = 32;

/// Where light a path met itself came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightFrom {
    /// Object `0`'s glowing surface.
    Object(usize),
    /// The environment (`true`) or the background, where the path left the scene.
    Sky(bool),
}

/// A sample's path through every expression of a set.
pub struct Tracker<'a> {
    set: &'a LpeSet,
    states: [u16; MAX_LAYERS],
    /// The light each expression has gathered (the first [`LpeSet::len`]).
    pub sums: [Color; MAX_LAYERS],
}

impl<'a> Tracker<'a> {
    /// A path that has just left the camera.
    pub fn new(set: &'a LpeSet) -> Self {
        let mut states = [0; MAX_LAYERS];
        for (s, d) in states.iter_mut().zip(&set.dfas) {
            *s = d.after_camera();
        }
        Tracker {
            set,
            states,
            sums: [Color::ZERO; MAX_LAYERS],
        }
    }

    /// Adds `c` to each expression the path matches once `symbol` ends it.
    #[inline]
    fn ends(&mut self, states: &[u16; MAX_LAYERS], symbol: super::Symbol, c: Color) {
        let set = self.set;
        for ((d, s), sum) in set
            .dfas
            .iter()
            .zip(&states[..set.len()])
            .zip(&mut self.sums)
        {
            if *s != 0 && d.accepts(d.step(*s, symbol)) {
                *sum += c;
            }
        }
    }

    /// The states after `symbol`.
    #[inline]
    fn after(&self, symbol: super::Symbol) -> [u16; MAX_LAYERS] {
        let mut next = [0; MAX_LAYERS];
        let n = self.set.len();
        for ((d, s), o) in self.set.dfas.iter().zip(&self.states[..n]).zip(&mut next) {
            *o = if *s == 0 { 0 } else { d.step(*s, symbol) };
        }
        next
    }
}

impl PathRecorder for Tracker<'_> {
    const ACTIVE: bool = false;
    const EVENTS: bool = true;

    fn vertex(&mut self, _: VertexRecord) {}

    fn end(&mut self, _: PathEnd) {}

    fn scattered(&mut self, lobe: Lobe, material: usize) {
        self.states = self.after(self.set.alphabet.scatter(lobe, material));
    }

    fn reached(&mut self, c: Color, from: LightFrom) {
        let a = &self.set.alphabet;
        let symbol = match from {
            LightFrom::Object(o) => a.object(o),
            LightFrom::Sky(environment) => a.sky(environment),
        };
        let states = self.states;
        self.ends(&states, symbol, c);
    }

    fn sampled(&mut self, c: Color, diffuse: Color, transmit: bool, material: usize, light: usize) {
        let a = &self.set.alphabet;
        let l = a.light(light);
        // The diffuse part of the BSDF's value and the rest (glossy: a light sample never
        // reaches a singular lobe), each ended by the light.
        let glossy = c - diffuse;
        if diffuse != Color::ZERO {
            let states = self.after(a.scatter_as(transmit, 0, material));
            self.ends(&states, l, diffuse);
        }
        if glossy != Color::ZERO {
            let states = self.after(a.scatter_as(transmit, 1, material));
            self.ends(&states, l, glossy);
        }
    }

    fn finished(&mut self, l: Color, clamped: Color) {
        if l == clamped {
            return;
        }
        // The sample's light was cut to the clamp: each expression's share of it is cut in
        // the same ratio, channel by channel, so that they still add up to the sample.
        let ratio = Color::select(l.cmpgt(Color::ZERO), clamped / l, Color::ZERO);
        for s in &mut self.sums[..self.set.len()] {
            *s *= ratio;
        }
    }
}
