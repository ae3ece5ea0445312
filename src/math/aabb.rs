use super::{Ray, Vec3A};

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

    /// True when `p` lies inside or on the box.
    pub fn contains(&self, p: Vec3A) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// True when all of the box is finite.
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// Slab test: does the ray meet the box at some `t` in `(0, t_max)`? `inv_dir` is
    /// `1 / ray.dir` per component. NaN from `0 * inf` (a ray in a slab plane) is handled by
    /// `min`/`max` taking the other operand, and is conservative (reports a hit).
    #[inline]
    pub fn hit(&self, ray: &Ray, inv_dir: Vec3A, t_max: f32) -> bool {
        let t0 = (self.min - ray.origin) * inv_dir;
        let t1 = (self.max - ray.origin) * inv_dir;
        let mut near = 0.0f32;
        let mut far = t_max;
        for i in 0..3 {
            let (a, b) = if t0[i] < t1[i] {
                (t0[i], t1[i])
            } else {
                (t1[i], t0[i])
            };
            near = near.max(a);
            far = far.min(b);
        }
        // Widen by a few ulps so rays that graze an edge are not culled by rounding.
        near <= far * (1.0 + 4.0 * f32::EPSILON)
    }
}
