//! The object BVH's walks against testing every object, in both of its layouts.

use super::*;
use crate::geometry::{Shape, Sphere};
use crate::math::Rng;

fn spheres(n: usize, rng: &mut Rng) -> Vec<Object> {
    (0..n)
        .map(|i| {
            // Crowded, so that rays cross several boxes and the order of visits matters.
            let center = Vec3A::new(
                rng.next_f32() * 8.0 - 4.0,
                rng.next_f32() * 8.0 - 4.0,
                rng.next_f32() * 8.0 - 4.0,
            );
            let shape = Shape::Sphere(Sphere {
                center,
                radius: 0.3 + rng.next_f32() * 2.0,
            });
            Object {
                name: format!("sphere {i}"),
                world_bounds: shape.bounds(),
                shape,
                transform: None,
                material: 0,
                slot_materials: vec![],
                center,
                uv_scale: crate::math::Vec2::ONE,
            }
        })
        .collect()
}

/// Both layouts, the flat one of small scenes and the tree, give what testing every
/// object gives: the same nearest hit, a blocker exactly when there is one, and word of
/// the other objects whenever one of them is hit; with an object left out, as if it
/// were not there.
#[test]
fn flat_and_tree_layouts_agree_with_testing_every_object() {
    let mut rng = Rng::new(11);
    // Rays whose nearest hit the layouts were compared on, flat and tree.
    let (mut flat_hits, mut tree_hits) = (0, 0);
    for n in [1, 2, 5, FLAT - 1, FLAT, FLAT + 1, 13, 40] {
        let objects = spheres(n, &mut rng);
        let bvh = Bvh::build(&objects);
        assert_eq!(bvh.flat.is_some(), n <= FLAT);
        for _ in 0..2000 {
            let origin = Vec3A::new(
                rng.next_f32() * 16.0 - 8.0,
                rng.next_f32() * 16.0 - 8.0,
                rng.next_f32() * 16.0 - 8.0,
            );
            let dir = Vec3A::new(
                rng.next_f32() - 0.5,
                rng.next_f32() - 0.5,
                rng.next_f32() - 0.5,
            )
            .normalize();
            let ray = Ray::new(origin, dir);
            let t_max = if rng.next_f32() < 0.5 {
                8.0
            } else {
                f32::INFINITY
            };
            // Half the rays leave one object out (which need not be near them).
            let left_out = (rng.next_f32() < 0.5).then(|| (rng.next_f32() * n as f32) as usize);
            let skip = left_out.map_or(Skip::NONE, Skip::object);
            let kept = || {
                objects
                    .iter()
                    .enumerate()
                    .filter(|(i, _)| Some(*i) != left_out)
            };
            let brute = kept()
                .filter_map(|(i, o)| o.intersect(&ray, t_max).map(|h| (i, h.t)))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let found = bvh
                .closest_hit(&objects, &ray, t_max, skip)
                .map(|(i, h)| (i, h.t));
            assert_eq!(found, brute, "{n} objects, {ray:?}, {skip:?}");
            let hit = usize::from(brute.is_some());
            if n <= FLAT {
                flat_hits += hit;
            } else {
                tree_hits += hit;
            }
            let odd = |i: usize| i % 2 == 1;
            let blocked = kept().any(|(i, o)| odd(i) && o.intersect(&ray, t_max).is_some());
            assert_eq!(bvh.any_hit(&objects, &ray, t_max, skip, odd), blocked);
            // Without a blocker, "met no other object's bounds" must mean no other
            // object is hit: shadow rays skip the glass on its word.
            let (blocker, others) = bvh.first_blocker_and_others(&objects, &ray, t_max, skip, odd);
            assert_eq!(blocker.is_some(), blocked);
            assert!(
                left_out.is_none() || blocker != left_out,
                "blocked by the object left out"
            );
            let other_hit = kept().any(|(i, o)| !odd(i) && o.intersect(&ray, t_max).is_some());
            assert!(blocked || others || !other_hit, "{n} objects, {ray:?}");
        }
    }
    // Replaying the generator: about 590 of the flat layouts' 10,000 rays hit a sphere
    // (few of them with one or two spheres) and about 1,090 of the tree's 6,000.
    assert!(flat_hits > 250, "{flat_hits} hits in the flat layout");
    assert!(tree_hits > 500, "{tree_hits} hits in the tree");
}
