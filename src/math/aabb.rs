//! Axis-aligned bounding boxes: union, growth, the slab test.

use super::Vec3A;

/// Axis-aligned bounding box. An empty box has `min > max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3A,
    /// Largest corner.
    pub max: Vec3A,
}

impl Aabb {
    /// The box that contains nothing.
    pub const EMPTY: Aabb = Aabb {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    /// The box spanning two corners (in any order).
    pub fn new(a: Vec3A, b: Vec3A) -> Self {
        Aabb {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// Smallest box holding both.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// Grows the box to hold `p`.
    pub fn grow(&mut self, p: Vec3A) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    /// Centre of the box.
    pub fn center(&self) -> Vec3A {
        0.5 * (self.min + self.max)
    }

    /// True when all of the box is finite.
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }
}
