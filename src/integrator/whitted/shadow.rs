//! Whitted's shadow rays: whether a light reaches a point, and how much of it gets through
//! the transparent objects on the way (tinted by the colour of each solid entered, dimmed by
//! Fresnel at each crossing and by Beer-Lambert absorption inside).

use super::{Whitted, beer_lambert};
use crate::integrator::RayStats;
use crate::integrator::explain::{Crossing, NoRecord, Recorder, ShadowRecord};
use crate::math::{Color, Ray, Vec3A, fresnel_dielectric, offset_ray_origin};
use crate::scene::{Scene, Skip};

/// Longest run of transparent surfaces a shadow ray passes through before giving up.
const MAX_SHADOW_CROSSINGS: usize = 64;

impl Whitted {
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
        self.shadow_recorded::<NoRecord>(scene, origin, dir, distance, Skip::NONE, rays)
            .0
    }

    /// [`Whitted::shadow`], leaving out `skip` (the surface the ray leaves, which it cannot
    /// meet again), with what the shadow ray met when `R` records. Out of line: inlined into
    /// the shading, it pushed the object walk it calls out of line instead (docs/perf-log.md).
    #[inline(never)]
    pub(super) fn shadow_recorded<R: Recorder>(
        &self,
        scene: &Scene,
        origin: Vec3A,
        dir: Vec3A,
        distance: f32,
        skip: Skip,
        rays: &mut RayStats,
    ) -> (Color, Option<ShadowRecord>) {
        let ray = Ray::new(origin, dir);
        rays.shadow += 1;
        let mut record = R::ACTIVE.then(ShadowRecord::default);
        let finish = |c: Color, mut record: Option<ShadowRecord>| {
            if let Some(r) = &mut record {
                r.transmitted = c.to_array();
            }
            (c, record)
        };
        // One walk finds an opaque blocker and says whether any glass's bounds lie on the
        // way; only then is the glass looked for (in the seed scene, most shadow rays pass
        // nowhere near the diamond).
        let (blocker, glass_near) = scene.opaque_blocker_seeing_glass(&ray, distance, skip);
        if let Some(b) = blocker {
            if let Some(r) = &mut record {
                r.blocked_by = Some(scene.objects[b].name.clone());
            }
            return finish(Color::ZERO, record);
        }
        if !glass_near {
            return finish(Color::ONE, record);
        }
        let mut visible = Color::ONE;
        let mut ray = ray;
        let mut remaining = distance;
        // Where the ray went into the solid it is in (its start, if it starts inside).
        let mut entered_at = origin;
        for _ in 0..MAX_SHADOW_CROSSINGS {
            rays.shadow += 1;
            let Some(h) = scene.closest_transparent_hit(&ray, remaining) else {
                return finish(visible, record);
            };
            let m = scene.material_at(&h);
            let entering = dir.dot(h.normal) < 0.0;
            let n = if entering { h.normal } else { -h.normal };
            // A shadow ray goes straight through instead of bending, so its way out is not the
            // refracted ray's: weigh both crossings as seen from outside (Fresnel is the same
            // both ways along a real refracted path), which can never be total reflection.
            let cos = dir.dot(n).abs();
            let transparency = m.terms_at(&scene.textures, &h.tex).transparency;
            let mut f = Color::splat(transparency * (1.0 - fresnel_dielectric(cos, 1.0 / m.ior)));
            if entering {
                f *= scene.base_color(&h, &h.tex);
                entered_at = h.point;
            } else {
                f *= beer_lambert(m.absorption, (h.point - entered_at).length());
            }
            if let Some(r) = &mut record {
                r.crossings.push(Crossing {
                    object: scene.objects[h.object].name.clone(),
                    way: if entering { "entering" } else { "leaving" },
                    fraction: f.to_array(),
                });
            }
            visible *= f;
            if visible.max_element() < 1e-4 {
                return finish(Color::ZERO, record);
            }
            ray = Ray::new(offset_ray_origin(h.point, -n), dir);
            remaining -= h.t;
        }
        finish(Color::ZERO, record)
    }
}
