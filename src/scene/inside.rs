//! Solids nothing else reaches into: a ray inside one (refracted into a glass ball, or
//! reflected off its inner side) can only meet the solid's own surface next, so it is
//! tested against that alone instead of walking the scene.

use super::{Hit, Scene};
use crate::geometry::{Object, Shape};
use crate::math::{Aabb, Ray};

/// Per object, whether it is a closed convex solid (a sphere or a box, placed however)
/// without cut-outs whose inside no other object's bounds reach into: then a ray that starts
/// inside it meets its far side before anything else. A ball in world space is tested
/// itself, so a glass ball resting on a floor (the floor's box touching it at one point)
/// counts; other solids' boxes must not even touch another's box.
pub(crate) fn alone_inside(objects: &[Object], cutouts: &[bool]) -> Vec<bool> {
    let any_unbounded = objects.iter().any(|o| o.world_bounds.is_none());
    objects
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let closed = matches!(o.shape, Shape::Sphere(_) | Shape::Cuboid(_));
            let Some(own) = o
                .world_bounds
                .filter(|_| closed && !cutouts[i] && !any_unbounded)
            else {
                return false;
            };
            let reaches_in = |b: &Aabb| match (&o.transform, &o.shape) {
                (None, Shape::Sphere(s)) => {
                    // The box's nearest point to the centre, inside the open ball.
                    let nearest = s.center.clamp(b.min, b.max);
                    (nearest - s.center).length_squared() < s.radius * s.radius
                }
                _ => b.min.cmple(own.max).all() && own.min.cmple(b.max).all(),
            };
            objects
                .iter()
                .enumerate()
                .all(|(j, other)| j == i || other.world_bounds.is_some_and(|b| !reaches_in(&b)))
        })
        .collect()
}

impl Scene {
    /// The closest hit of `ray`, which starts inside object `i` (whose [`alone_inside`]
    /// holds): the same hit the walk over the scene finds, from the object alone.
    #[inline]
    pub(crate) fn hit_from_inside(&self, i: usize, ray: &Ray) -> Option<Hit> {
        let h = self.objects[i].intersect(ray, f32::INFINITY)?;
        Some(self.hit_details(ray, i, h, false))
    }

    /// Whether a ray inside object `i` can only meet `i` (see [`alone_inside`]).
    #[inline]
    pub(crate) fn is_alone_inside(&self, i: usize) -> bool {
        self.alone_inside.get(i).copied().unwrap_or(false)
    }
}

#[cfg(test)]
mod tests {
    use crate::math::{Rng, Vec3A};
    use crate::scene::{Format, load_str};
    use std::path::Path;

    /// A glass ball on a floor, a glass box and a ball inside a box: the ball and the lone
    /// box are alone inside, the box holding a ball is not, nor the ball it holds; and from
    /// random points inside each solid alone, random rays meet what the walk meets.
    #[test]
    fn rays_inside_a_lone_solid_meet_what_the_walk_meets() {
        let text = "[camera]\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\n\
                    [materials.glass]\ntransparency = 1\nior = 1.5\n\
                    [[objects]]\ntype = \"rectangle\"\ncorner = [-10, -1, 10]\nedge_u = [20, 0, 0]\nedge_v = [0, 0, -20]\nmaterial = \"glass\"\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"glass\"\n\
                    [[objects]]\ntype = \"box\"\nmin = [3, -1, -1]\nmax = [4, 0, 0]\nmaterial = \"glass\"\n\
                    [[objects]]\ntype = \"box\"\nmin = [-6, 2, -1]\nmax = [-3, 5, 2]\nmaterial = \"glass\"\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [-4.5, 3.5, 0.5]\nradius = 0.5\nmaterial = \"glass\"\n";
        let scene = load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap();
        let alone: Vec<bool> = (0..5).map(|i| scene.is_alone_inside(i)).collect();
        // The box on the floor touches the floor's box: not alone.
        assert_eq!(alone, [false, true, false, false, false]);
        let mut rng = Rng::new(3);
        let mut checked = 0;
        for _ in 0..20_000 {
            let p = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
            if p.length() >= 0.999 {
                continue;
            }
            let d = (Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5)
                .normalize_or(Vec3A::X);
            let ray = crate::math::Ray::new(p, d);
            let got = scene.hit_from_inside(1, &ray);
            let want = scene.closest_hit(&ray, f32::INFINITY);
            assert_eq!(format!("{got:?}"), format!("{want:?}"), "{ray:?}");
            checked += 1;
        }
        assert!(checked > 10_000, "{checked}");
    }
}
