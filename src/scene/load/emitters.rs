//! The area lights of a scene: each object whose material emits, in world space, and each
//! emitting triangle of a mesh (a light of its own, so that lights are chosen by power
//! triangle by triangle). Shapes the path tracer cannot sample (boxes, cylinders, cones,
//! planes, and disks and spheres stretched unevenly by a transform) still emit where a path
//! meets them, found by BSDF sampling alone, and the scene warns that they light it noisily.

use crate::geometry::{Disk, Mesh, Rect, Shape, Sphere, Triangle};
use crate::light::{AreaLight, Emitter, Light, ObjectLights};
use crate::material::{ColorParam, Material};
use crate::math::{Transform, Vec3A};
use crate::scene::Object;

/// The area lights, added to `lights` (after its point, spot and directional lights), and
/// per object which of them it is (indices into `lights`).
pub(super) fn area_lights(
    objects: &[Object],
    materials: &[Material],
    textures: &[crate::texture::Texture],
    warnings: &mut Vec<String>,
    lights: &mut Vec<Light>,
) -> Vec<ObjectLights> {
    let mut of_object = vec![ObjectLights::None; objects.len()];
    // Each emitting material's mean radiance (a texture's over its pattern), which a light's
    // power is taken from, and its texture.
    // Cut-outs are left to the paths that hit them: a light sample would land in their
    // holes too.
    let emitting = |m: usize| {
        if materials[m].cutout.is_some() {
            return None;
        }
        let e = materials[m].emission?;
        let texture = match e.radiance {
            ColorParam::Texture(t) => Some(t),
            ColorParam::Value(_) => None,
        };
        let mean = e.radiance.mean(textures);
        (mean.max_element() > 0.0).then_some(Emitting {
            mean,
            texture,
            two_sided: e.two_sided,
        })
    };
    for (i, o) in objects.iter().enumerate() {
        if let Shape::Mesh(mesh) = &o.shape {
            of_object[i] = mesh_lights(i, o, mesh, &emitting, lights);
            continue;
        }
        let Some(e) = emitting(o.material) else {
            continue;
        };
        match emitter(&o.shape, o.transform.as_ref()) {
            Some(emitter) => {
                of_object[i] = ObjectLights::Whole(lights.len() as u32);
                lights.push(Light::Area(AreaLight::new(
                    emitter,
                    e.mean,
                    e.texture,
                    e.two_sided,
                    i,
                )));
            }
            None => warnings.push(format!(
                "object `{}`: the path tracer finds its emission only where paths happen to hit it, which is noisy; light sampling covers rectangles, disks, triangles, meshes and spheres (disks and spheres scaled evenly)",
                o.name
            )),
        }
    }
    of_object
}

/// What a light takes from an emitting material.
#[derive(Clone, Copy)]
struct Emitting {
    mean: crate::math::Color,
    texture: Option<usize>,
    two_sided: bool,
}

/// The emitting triangles of mesh object `index` as lights, in world space, each facing
/// the side a hit on it calls its front.
fn mesh_lights(
    index: usize,
    o: &Object,
    mesh: &Mesh,
    emitting: &impl Fn(usize) -> Option<Emitting>,
    lights: &mut Vec<Light>,
) -> ObjectLights {
    let material_of = |prim: u32| {
        if o.slot_materials.is_empty() {
            o.material
        } else {
            o.slot_materials
                .get(mesh.slot(prim) as usize)
                .copied()
                .unwrap_or(o.material)
        }
    };
    let any = if o.slot_materials.is_empty() {
        emitting(o.material).is_some()
    } else {
        o.slot_materials.iter().any(|&m| emitting(m).is_some())
    };
    if !any {
        return ObjectLights::None;
    }
    let t = o.transform.as_ref();
    let mut of_lane = vec![u32::MAX; mesh.lanes()];
    for (prim, [a, b, c]) in mesh.triangles() {
        let Some(e) = emitting(material_of(prim)) else {
            continue;
        };
        let (mut wa, mut wb, mut wc) = (a, b, c);
        if let Some(t) = t {
            (wa, wb, wc) = (
                t.point_to_world(a),
                t.point_to_world(b),
                t.point_to_world(c),
            );
            // A mirroring transform turns the winding but not the hit's front normal.
            let front = t.normal_to_world((b - a).cross(c - a));
            if (wb - wa).cross(wc - wa).dot(front) < 0.0 {
                std::mem::swap(&mut wb, &mut wc);
            }
        }
        let Some(triangle) = Triangle::new(wa, wb, wc) else {
            continue;
        };
        of_lane[prim as usize] = lights.len() as u32;
        lights.push(Light::Area(AreaLight::new(
            Emitter::Triangle(triangle),
            e.mean,
            e.texture,
            e.two_sided,
            index,
        )));
    }
    for lane in 0..of_lane.len() {
        of_lane[lane] = of_lane[mesh.own_prim(lane as u32) as usize];
    }
    ObjectLights::Triangles(of_lane.into_boxed_slice())
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
