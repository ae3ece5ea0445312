//! Which objects a group of rays may meet, from a test of the pyramid that holds them all
//! against the objects' bounds: a pixel's camera rays (the pyramid through the film around
//! the pixel). Objects left out need not be tested; a pixel whose rays may meet none needs
//! no query at all.

use super::{Bvh, LEAF, NO_CHILD, Node4};
use crate::geometry::{Object, Shape};
use crate::math::{Aabb, Frustum, Vec3A};

/// Which objects a group of rays may meet, as far as a test of their pyramid against the
/// objects' bounds can tell: a bit per slot of a small scene's flat layout, or everything.
/// Objects left out are met by none of the rays, so a query among the rest finds the same
/// hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reach(pub(super) u32);

impl Reach {
    /// Any object (what is not known).
    pub const ALL: Reach = Reach(u32::MAX);
    /// None: the rays meet nothing.
    pub const NONE: Reach = Reach(0);

    /// Whether the rays meet nothing.
    pub fn is_none(self) -> bool {
        self.0 == 0
    }

    /// How many objects the rays may meet (32 for [`Reach::ALL`]).
    pub fn count(self) -> u32 {
        self.0.count_ones()
    }
}

impl Default for Reach {
    fn default() -> Self {
        Reach::ALL
    }
}

impl Bvh {
    /// Which objects' bounds may meet the rays of `f` ([`Reach::NONE`] only where every
    /// one lies wholly outside it). No unbounded object may be (an infinite plane is met
    /// almost everywhere); a tree is looked at two levels down, below which any box still
    /// inside counts as met (a pixel that sees nothing is mostly beside the whole scene),
    /// and says all or none. A sphere in world space whose box `f` does not exclude is
    /// looked at itself (the corners of a large sphere's box are much of a picture's
    /// background).
    #[inline]
    pub fn reach(&self, objects: &[Object], f: &Frustum) -> Reach {
        if !self.unbounded.is_empty() {
            return Reach::ALL;
        }
        if let Some(flat) = &self.flat {
            let mut met = flat.used & !f.excludes_8(flat.node.bounds());
            let mut left = met;
            while left != 0 {
                let k = left.trailing_zeros() as usize;
                left &= left - 1;
                let o = &objects[flat.node.child[k] as usize];
                if let (None, Shape::Sphere(s)) = (&o.transform, &o.shape)
                    && f.excludes_sphere(s.center, s.radius)
                {
                    met &= !(1 << k);
                }
            }
            return Reach(met);
        }
        if self.tree_meets(f) {
            Reach::ALL
        } else {
            Reach::NONE
        }
    }

    /// Whether the tree's boxes may meet the rays of `f`, two levels down.
    fn tree_meets(&self, f: &Frustum) -> bool {
        let Some((root, bounds)) = self.root else {
            return false;
        };
        if f.excludes(&bounds) {
            return false;
        }
        // A bit per lane of `n` that holds a child whose box `f` does not exclude.
        let lanes_met = |n: &Node4| {
            (0..4).fold(0u32, |met, lane| {
                let b = Aabb {
                    min: Vec3A::new(n.min[0][lane], n.min[1][lane], n.min[2][lane]),
                    max: Vec3A::new(n.max[0][lane], n.max[1][lane], n.max[2][lane]),
                };
                met | (((n.child[lane] != NO_CHILD && !f.excludes(&b)) as u32) << lane)
            })
        };
        if root & LEAF != 0 {
            return true;
        }
        let top = &self.nodes[root as usize];
        let mut met = lanes_met(top);
        while met != 0 {
            let child = top.child[met.trailing_zeros() as usize];
            met &= met - 1;
            if child & LEAF != 0 || lanes_met(&self.nodes[child as usize]) != 0 {
                return true;
            }
        }
        false
    }
}
