//! Whitted-style recursive ray tracing, the seed report's model made correct: Phong direct
//! light with shadow rays (lighter, tinted shadows behind transparent objects), mirror
//! reflection, and refraction by Snell's law with exact Fresnel weights and total internal
//! reflection, through solids of any shape, with Beer-Lambert absorption inside them.

use super::{Integrator, RayStats};
use crate::math::{Color, Ray, Vec3A, fresnel_dielectric, offset_ray_origin, reflect, refract};
use crate::scene::{Hit, Scene};

/// The Whitted integrator.
#[derive(Clone, Copy, Debug, Default)]
pub struct Whitted;

/// Longest run of transparent surfaces a shadow ray passes through before giving up.
const MAX_SHADOW_CROSSINGS: usize = 64;

/// A surface that returns less than this fraction of a light's radiance (a third of the
/// darkest 8-bit sRGB step for a light of radiance 1) is not worth a shadow ray. Relative to
/// the light, so dim lights in scenes meant for EXR output are never dropped.
const MIN_RESPONSE: f32 = 1e-4;

impl Integrator for Whitted {
    fn radiance(&self, scene: &Scene, ray: &Ray, rays: &mut RayStats) -> Color {
        self.trace(scene, ray, 1, None, rays)
    }
}

impl Whitted {
    /// Colour along `ray`, which is the `depth`-th segment of its path (camera rays are 1).
    /// `medium` is the absorption coefficient of the solid the ray travels inside, `None`
    /// in open air (where fog applies instead).
    pub fn trace(
        &self,
        scene: &Scene,
        ray: &Ray,
        depth: u32,
        medium: Option<Color>,
        rays: &mut RayStats,
    ) -> Color {
        self.trace_from(scene, ray, ray.origin, depth, medium, rays)
    }

    /// As [`Whitted::trace`], for a ray that really leaves from the surface point `from`
    /// (its origin is offset off the surface): absorption and fog are measured from there, so
    /// the offset never shortens a path through thin glass.
    fn trace_from(
        &self,
        scene: &Scene,
        ray: &Ray,
        from: Vec3A,
        depth: u32,
        medium: Option<Color>,
        rays: &mut RayStats,
    ) -> Color {
        if depth == 1 {
            rays.camera += 1;
        } else {
            rays.secondary += 1;
        }
        let Some(hit) = scene.closest_hit(ray, f32::INFINITY) else {
            return match (medium, scene.fog) {
                (Some(sigma), _) if sigma != Color::ZERO => Color::ZERO,
                (None, Some(fog)) => fog.apply(scene.background, f32::INFINITY),
                _ => scene.background,
            };
        };
        let c = self.shade(scene, ray, &hit, depth, medium, rays);
        match (medium, scene.fog) {
            (Some(sigma), _) => c * beer_lambert(sigma, (hit.point - from).length()),
            (None, Some(fog)) => fog.apply(c, (hit.point - from).length()),
            (None, None) => c,
        }
    }

    fn shade(
        &self,
        scene: &Scene,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        medium: Option<Color>,
        rays: &mut RayStats,
    ) -> Color {
        let m = scene.material_at(hit);
        let d = ray.dir;
        // Entering or leaving is told by the normal: the outward normal faces the ray when
        // the ray comes from outside.
        let entering = d.dot(hit.normal) < 0.0;
        let n = if entering { hit.normal } else { -hit.normal };
        // Shading (smooth meshes' interpolated normals) uses `ns`; which side a ray is on,
        // and where new rays start, follow the true surface `n`.
        let ns = if entering {
            hit.shading_normal
        } else {
            -hit.shading_normal
        };
        let base = scene.textures[m.texture].eval(&hit.tex);
        let above = offset_ray_origin(hit.point, n);

        let t = m.transparency;
        let mut out = scene.ambient * base * (m.ambient * (1.0 - t));
        let view = -d;
        for light in &scene.lights {
            let Some(ls) = light.sample(above) else {
                continue;
            };
            let cos = ns.dot(ls.to_light);
            if cos <= 0.0 || n.dot(ls.to_light) <= 0.0 {
                continue;
            }
            // What this light would add if nothing were in the way: diffuse (weighed by the
            // opaque part) and the Phong highlight.
            let mut direct = base * (m.diffuse * cos * (1.0 - t));
            if m.specular != Color::ZERO {
                let r = reflect(-ls.to_light, ns);
                direct += m.specular * r.dot(view).max(0.0).powf(m.shininess);
            }
            // A shadow ray cannot change what is too faint to see (clear glass away from its
            // highlight adds nothing here).
            if direct.max_element() < MIN_RESPONSE {
                continue;
            }
            out += ls.radiance * direct * self.shadow(scene, above, ls.to_light, ls.distance, rays);
        }
        if depth >= scene.settings.max_depth {
            return out;
        }
        let mut reflect_weight = (1.0 - t) * m.reflectivity;
        if t > 0.0 {
            let eta = if entering { 1.0 / m.ior } else { m.ior };
            let cos_i = view.dot(ns);
            let fresnel = fresnel_dielectric(cos_i, eta);
            reflect_weight += t * fresnel;
            // A shading normal can bend a ray back out of the surface; the true normal
            // cannot.
            let refracted = refract(d, ns, eta)
                .filter(|r| r.dot(n) < 0.0)
                .or_else(|| refract(d, n, eta));
            if fresnel < 1.0
                && let Some(dir) = refracted
            {
                let below = offset_ray_origin(hit.point, -n);
                // Inside a solid there is absorption (maybe none) and never fog.
                let (inside, filter) = if entering {
                    (Some(m.absorption), base)
                } else {
                    (None, Color::ONE)
                };
                let transmitted = self.trace_from(
                    scene,
                    &Ray::new(below, dir),
                    hit.point,
                    depth + 1,
                    inside,
                    rays,
                );
                out += transmitted * filter * (t * (1.0 - fresnel));
            }
        }
        if reflect_weight > 0.0 {
            let mut dir = reflect(d, ns);
            if dir.dot(n) <= 0.0 {
                dir = reflect(d, n);
            }
            let r = Ray::new(above, dir.normalize());
            out += self.trace_from(scene, &r, hit.point, depth + 1, medium, rays) * reflect_weight;
        }
        out
    }

    /// Fraction of light that reaches `origin` from `distance` away along `dir`: 0 behind an
    /// opaque object; behind transparent ones, the product over the surfaces crossed of
    /// `transparency * (1 - Fresnel)`, the surface colour where the ray enters a solid, and
    /// Beer-Lambert absorption over the length inside it.
    pub fn shadow(
        &self,
        scene: &Scene,
        origin: Vec3A,
        dir: Vec3A,
        distance: f32,
        rays: &mut RayStats,
    ) -> Color {
        let ray = Ray::new(origin, dir);
        rays.shadow += 1;
        if scene.opaque_blocked(&ray, distance) {
            return Color::ZERO;
        }
        if !scene.has_transparent() {
            return Color::ONE;
        }
        let mut visible = Color::ONE;
        let mut ray = ray;
        let mut remaining = distance;
        // Where the ray went into the solid it is in (its start, if it starts inside).
        let mut entered_at = origin;
        for _ in 0..MAX_SHADOW_CROSSINGS {
            rays.shadow += 1;
            let Some(h) = scene.closest_transparent_hit(&ray, remaining) else {
                return visible;
            };
            let m = scene.material_at(&h);
            let entering = dir.dot(h.normal) < 0.0;
            let n = if entering { h.normal } else { -h.normal };
            // A shadow ray goes straight through instead of bending, so its way out is not the
            // refracted ray's: weigh both crossings as seen from outside (Fresnel is the same
            // both ways along a real refracted path), which can never be total reflection.
            let cos = dir.dot(n).abs();
            let mut f = Color::splat(m.transparency * (1.0 - fresnel_dielectric(cos, 1.0 / m.ior)));
            if entering {
                f *= scene.textures[m.texture].eval(&h.tex);
                entered_at = h.point;
            } else {
                f *= beer_lambert(m.absorption, (h.point - entered_at).length());
            }
            visible *= f;
            if visible.max_element() < 1e-4 {
                return Color::ZERO;
            }
            ray = Ray::new(offset_ray_origin(h.point, -n), dir);
            remaining -= h.t;
        }
        Color::ZERO
    }
}

/// Transmittance `exp(-sigma * distance)` per channel.
#[inline]
fn beer_lambert(sigma: Color, distance: f32) -> Color {
    if sigma == Color::ZERO {
        return Color::ONE;
    }
    Color::new(
        (-sigma.x * distance).exp(),
        (-sigma.y * distance).exp(),
        (-sigma.z * distance).exp(),
    )
}
