//! The area lights of a scene: each object whose material emits, in world space. Shapes the
//! path tracer cannot sample (boxes, cylinders, cones, planes, meshes, and disks and spheres
//! stretched unevenly by a transform) still emit where a path meets them, found by BSDF
//! sampling alone, and the scene warns that they light it noisily.

use crate::geometry::{Disk, Rect, Shape, Sphere, Triangle};
use crate::light::{AreaLight, Emitter};
use crate::material::Material;
use crate::math::{Transform, Vec3A};
use crate::scene::Object;

/// The area lights, and per object the index of its light (`None` for objects that do not
/// emit, or that light sampling cannot reach).
pub(super) fn area_lights(
    objects: &[Object],
    materials: &[Material],
    warnings: &mut Vec<String>,
) -> (Vec<AreaLight>, Vec<Option<u32>>) {
    let mut lights = vec![];
    let mut of_object = vec![None; objects.len()];
    for (i, o) in objects.iter().enumerate() {
        let emitting = |m: usize| {
            materials[m]
                .emission
                .filter(|e| e.radiance.max_element() > 0.0)
        };
        let any_slot = o.slot_materials.iter().any(|&m| emitting(m).is_some());
        let Some(e) = (if o.slot_materials.is_empty() {
            emitting(o.material)
        } else {
            None
        }) else {
            if any_slot {
                warnings.push(unsampled(o, "its mesh file's emitting materials"));
            }
            continue;
        };
        match emitter(&o.shape, o.transform.as_ref()) {
            Some(emitter) => {
                of_object[i] = Some(lights.len() as u32);
                lights.push(AreaLight {
                    emitter,
                    radiance: e.radiance,
                    two_sided: e.two_sided,
                    object: i,
                });
            }
            None => warnings.push(unsampled(o, "its emission")),
        }
    }
    (lights, of_object)
}

fn unsampled(o: &Object, what: &str) -> String {
    format!(
        "object `{}`: the path tracer finds {what} only where paths happen to hit it, which is noisy; light sampling covers rectangles, disks, triangles and spheres (disks and spheres scaled evenly)",
        o.name
    )
}

/// The shape in world space, where it is one that lights can be sampled on.
fn emitter(shape: &Shape, t: Option<&Transform>) -> Option<Emitter> {
    let point = |p: Vec3A| t.map_or(p, |t| t.point_to_world(p));
    let vector = |v: Vec3A| t.map_or(v, |t| t.vector_to_world(v));
    let normal = |n: Vec3A| t.map_or(n, |t| t.normal_to_world(n));
    // Edges carried to world space, swapped where a mirroring transform would turn the
    // front side (hits take theirs from the normal carried out, which a mirror keeps).
    let edges = |corner: Vec3A, a: Vec3A, b: Vec3A| {
        let (a2, b2) = (vector(a), vector(b));
        if a2.cross(b2).dot(normal(a.cross(b))) < 0.0 {
            (point(corner), b2, a2)
        } else {
            (point(corner), a2, b2)
        }
    };
    match shape {
        Shape::Rect(r) => {
            let (c, a, b) = r.corner_and_edges();
            let (c, a, b) = edges(c, a, b);
            Rect::new(c, a, b).map(Emitter::Rect)
        }
        Shape::Triangle(tri) => {
            let (c, a, b) = tri.corner_and_edges();
            let (c, a, b) = edges(c, a, b);
            Triangle::new(c, c + a, c + b).map(Emitter::Triangle)
        }
        Shape::Disk(d) => {
            let scale = even_scale(t, d.frame.u, d.frame.v)?;
            Some(Emitter::Disk(Disk::new(
                point(d.center),
                normal(d.frame.w),
                d.radius * scale,
            )))
        }
        Shape::Sphere(s) => {
            let scale = even_scale(t, Vec3A::X, Vec3A::Y)?;
            let scale_z = even_scale(t, Vec3A::Y, Vec3A::Z)?;
            ((scale - scale_z).abs() <= 1e-5 * scale).then(|| {
                Emitter::Sphere(Sphere {
                    center: point(s.center),
                    radius: s.radius * scale,
                })
            })
        }
        _ => None,
    }
}

/// The factor by which `t` scales lengths in the plane of the unit, perpendicular `a` and
/// `b`, if it scales them evenly there (1 without a transform).
fn even_scale(t: Option<&Transform>, a: Vec3A, b: Vec3A) -> Option<f32> {
    let Some(t) = t else { return Some(1.0) };
    let (a, b) = (t.vector_to_world(a), t.vector_to_world(b));
    let (la, lb) = (a.length(), b.length());
    let even = (la - lb).abs() <= 1e-5 * la.max(lb) && a.dot(b).abs() <= 1e-5 * la * lb;
    even.then_some(la)
}
