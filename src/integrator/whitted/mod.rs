//! Whitted-style recursive ray tracing, the seed report's model made correct: Phong direct
//! light with shadow rays (lighter, tinted shadows behind transparent objects), mirror
//! reflection, and refraction by Snell's law with exact Fresnel weights and total internal
//! reflection, through solids of any shape, with Beer-Lambert absorption inside them.

mod phong;
mod shadow;

use super::explain::{
    FresnelRecord, HitRecord, LightRecord, MaterialTerms, NoRecord, RayKind, Recorder, uv2,
};
use super::{BatchStart, Integrator, RayStats};
use crate::light::{Falloff, Light};
use crate::math::{
    Color, Ray, Vec3A, Wavelength, fresnel_refract, offset_ray_origin, reflect, refract,
};
use crate::scene::{Hit, RayDifferentials, Scene, Skip};
use phong::phong_lobe;

/// [`Segment::inside`] of a ray in open air.
const NOT_INSIDE: u32 = u32::MAX;

/// The Whitted integrator.
#[derive(Clone, Copy, Debug, Default)]
pub struct Whitted;

/// A surface that returns less than this fraction of a light's radiance (a third of the
/// darkest 8-bit sRGB step for a light of radiance 1) is not worth a shadow ray. Relative to
/// the light, so dim lights in scenes meant for EXR output are never dropped.
const MIN_RESPONSE: f32 = 1e-4;

impl Integrator for Whitted {
    fn radiance(&self, scene: &Scene, ray: &Ray, rays: &mut RayStats) -> Color {
        self.trace(scene, ray, 1, None, rays)
    }

    /// A camera ray that meets nothing sees the background (through the fog, if any),
    /// unless the scene shows an environment, which changes with direction: as
    /// `Whitted::trace_found` colours such a ray.
    fn camera_miss(&self, scene: &Scene) -> Option<Color> {
        match (scene.fog, scene.environment()) {
            (Some(fog), _) => Some(fog.apply(scene.background, f32::INFINITY)),
            (None, Some(env)) if env.visible => None,
            _ => Some(scene.background),
        }
    }

    /// The first hits of the whole batch as packets ([`Scene::closest_hits`]), then each
    /// ray's shading and the rest of its tree, in order. In a scene with dispersive glass,
    /// sample `k` of a pixel follows the wavelength of `k` in a sequence spread evenly over
    /// the visible range (see `wavelength_number`).
    fn radiance_batch(
        &self,
        scene: &Scene,
        batch: &[Ray],
        first: BatchStart,
        out: &mut [Color],
        rays: &mut RayStats,
    ) {
        const N: usize = 16;
        let mut index = first.index;
        // Only where the scene disperses: asked inside the loop, the pixel's hash was hoisted
        // out of it and made for every batch (0.5 % of the seed's time).
        let start = if scene.disperses() {
            wavelength_start(first.x, first.y)
        } else {
            0.0
        };
        for (batch, out) in batch.chunks(N).zip(out.chunks_mut(N)) {
            let mut found: [Option<Hit>; N] = [None; N];
            let found = &mut found[..batch.len()];
            scene.closest_hits(batch, found, first.reach);
            for ((ray, f), o) in batch.iter().zip(found.iter()).zip(out.iter_mut()) {
                let u = if scene.disperses() {
                    wavelength_number(start, index)
                } else {
                    0.0
                };
                let seg = Segment::camera(scene, ray, u);
                index += 1;
                seg.begin(ray, rays, &mut NoRecord);
                *o = self.trace_found(scene, ray, f, &seg, rays, &mut NoRecord);
            }
        }
    }
}

/// Where a ray is going and what it carries, for one call of the recursion.
struct Segment {
    kind: RayKind,
    /// The surface point it really leaves from (its origin is offset off it).
    from: Vec3A,
    depth: u32,
    /// Absorption coefficient of the solid it travels in; `None` in open air.
    medium: Option<Color>,
    /// What the parent multiplies its colour by (for the record).
    weight: Color,
    /// The object whose surface the ray leaves, when it cannot meet it again.
    skip: Skip,
    /// The solid the ray travels inside ([`NOT_INSIDE`] in open air), for a solid that
    /// nothing else reaches into: then the ray can only meet it.
    inside: u32,
    /// How the ray changes to the next pixels, while it has only met mirrors and glass.
    diff: RayDifferentials,
    /// The wavelength (nm) the tree follows below a surface whose index depends on it; 0
    /// where it follows none (a number, not an `Option` of a [`Wavelength`]: every ray
    /// carries it, and a larger segment cost Whitted's rays time).
    nm: f32,
    /// The camera ray's number for that wavelength, drawn where the tree first meets such a
    /// surface (from the camera ray itself: Whitted's samples are fixed strata).
    u_wavelength: f32,
}

impl Segment {
    /// A camera ray's segment, `u_wavelength` its number for a wavelength (unread where the
    /// scene has no dispersive glass).
    fn camera(scene: &Scene, ray: &Ray, u_wavelength: f32) -> Self {
        Segment {
            kind: RayKind::Camera,
            from: ray.origin,
            depth: 1,
            medium: None,
            weight: Color::ONE,
            skip: Skip::NONE,
            inside: NOT_INSIDE,
            diff: RayDifferentials::camera(scene),
            nm: 0.0,
            u_wavelength,
        }
    }

    /// Counts `ray`, the ray of this segment, and reports it to `rec`.
    #[inline(always)]
    fn begin<R: Recorder>(&self, ray: &Ray, rays: &mut RayStats, rec: &mut R) {
        if self.depth == 1 {
            rays.camera += 1;
        } else {
            rays.secondary += 1;
        }
        rays.deepest = rays.deepest.max(self.depth);
        rec.begin_ray(self.kind, ray, self.depth, self.weight);
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
        let kind = if depth == 1 {
            RayKind::Camera
        } else {
            RayKind::Reflection
        };
        let seg = Segment {
            kind,
            from: ray.origin,
            depth,
            medium,
            weight: Color::ONE,
            skip: Skip::NONE,
            inside: NOT_INSIDE,
            diff: if depth == 1 {
                RayDifferentials::camera(scene)
            } else {
                RayDifferentials::None
            },
            nm: 0.0,
            u_wavelength: if scene.disperses() {
                ray_wavelength_number(ray)
            } else {
                0.0
            },
        };
        self.trace_from(scene, ray, &seg, rays, &mut NoRecord)
    }

    /// The colour along a camera ray, reporting every ray of its tree to `rec`.
    pub fn explain(
        &self,
        scene: &Scene,
        ray: &Ray,
        rays: &mut RayStats,
        rec: &mut impl Recorder,
    ) -> Color {
        self.explain_sample(scene, ray, None, rays, rec)
    }

    /// [`Whitted::explain`] for a camera ray that is sample `k` of pixel `(x, y)`
    /// (`sample`: `((x, y), k)`), which then follows the wavelength the render gives that
    /// sample in a scene with dispersive glass; `None` for a ray that is no sample (one
    /// through a pixel's centre).
    pub fn explain_sample(
        &self,
        scene: &Scene,
        ray: &Ray,
        sample: Option<((u32, u32), u32)>,
        rays: &mut RayStats,
        rec: &mut impl Recorder,
    ) -> Color {
        let u = match sample {
            _ if !scene.disperses() => 0.0,
            Some(((x, y), k)) => wavelength_number(wavelength_start(x, y), k),
            None => ray_wavelength_number(ray),
        };
        self.trace_from(scene, ray, &Segment::camera(scene, ray, u), rays, rec)
    }

    /// The colour along `ray`; absorption and fog are measured from `seg.from`, so the
    /// origin's offset never shortens a path through thin glass.
    fn trace_from<R: Recorder>(
        &self,
        scene: &Scene,
        ray: &Ray,
        seg: &Segment,
        rays: &mut RayStats,
        rec: &mut R,
    ) -> Color {
        seg.begin(ray, rays, rec);
        // A record shows the uv even where no texture needs it.
        let found = if R::ACTIVE {
            scene.closest_hit_with_uv(ray, f32::INFINITY, seg.skip)
        } else if seg.inside != NOT_INSIDE && scene.is_alone_inside(seg.inside as usize) {
            scene.hit_from_inside(seg.inside as usize, ray)
        } else {
            scene.closest_hit_skipping(ray, f32::INFINITY, seg.skip)
        };
        self.trace_found(scene, ray, &found, seg, rays, rec)
    }

    /// The rest of [`Whitted::trace_from`], once the ray's closest hit is `found`.
    fn trace_found<R: Recorder>(
        &self,
        scene: &Scene,
        ray: &Ray,
        found: &Option<Hit>,
        seg: &Segment,
        rays: &mut RayStats,
        rec: &mut R,
    ) -> Color {
        // `found` is borrowed: moving the hit out of it copied it in 32-byte loads from the
        // narrower stores `closest_hit` had just made, which a processor cannot forward, and
        // every ray waited for those stores to reach the cache.
        let Some(hit) = found else {
            let c = match (seg.medium, scene.fog) {
                (Some(sigma), _) if sigma != Color::ZERO => {
                    if R::ACTIVE {
                        rec.note("leaves the scene from inside an absorbing solid: black".into());
                    }
                    Color::ZERO
                }
                (None, Some(fog)) => {
                    if R::ACTIVE {
                        rec.note("sees the background through infinite fog".into());
                    }
                    fog.apply(scene.background, f32::INFINITY)
                }
                _ => match scene.environment() {
                    // The environment as the background (hidden from camera rays when it
                    // says so); Whitted does not light surfaces with it.
                    Some(env) if env.visible || seg.depth > 1 => {
                        if R::ACTIVE {
                            rec.note("sees the environment".into());
                        }
                        env.radiance(ray.dir)
                    }
                    _ => {
                        if R::ACTIVE {
                            rec.note("sees the background".into());
                        }
                        scene.background
                    }
                },
            };
            rec.end_ray(c);
            return c;
        };
        let c = self.shade(scene, ray, hit, seg, rays, rec);
        // Only absorption and fog need the distance (a square root on every ray).
        let distance = || (hit.point - seg.from).length();
        let c = match (seg.medium, scene.fog) {
            (Some(sigma), _) if sigma != Color::ZERO || R::ACTIVE => {
                let distance = distance();
                let kept = beer_lambert(sigma, distance);
                if R::ACTIVE && sigma != Color::ZERO {
                    rec.note(format!(
                        "absorption over {distance} inside: exp(-sigma d) = {kept}"
                    ));
                }
                c * kept
            }
            (None, Some(fog)) => {
                let distance = distance();
                if R::ACTIVE {
                    rec.note(format!("fog over {distance}"));
                }
                fog.apply(c, distance)
            }
            _ => c,
        };
        rec.end_ray(c);
        c
    }

    fn shade<R: Recorder>(
        &self,
        scene: &Scene,
        ray: &Ray,
        hit: &Hit,
        seg: &Segment,
        rays: &mut RayStats,
        rec: &mut R,
    ) -> Color {
        let m = scene.material_at(hit);
        // Glass whose index depends on wavelength: the tree below follows one, the first
        // such surface drawing it, and its light is weighed by that wavelength there.
        let (ior, nm, drawn) = match &m.dispersion {
            None => (m.ior, seg.nm, None),
            Some(d) if seg.nm > 0.0 => (d.ior(seg.nm), seg.nm, None),
            Some(d) => {
                let w = Wavelength::sample(seg.u_wavelength);
                (d.ior(w.nm), w.nm, Some(w.weight))
            }
        };
        let d = ray.dir;
        // The patch of surface the pixel sees, where a texture reads it (and then the hit's
        // texture point reads over its footprint) or a mirror or glass passes the
        // differentials on.
        let patch = match seg.diff {
            RayDifferentials::None => None,
            _ if !scene.reads_textures(hit) => None,
            d => {
                // The normal's change too where rays may go on from here.
                let on = m.terms.reflectivity > 0.0
                    || m.terms.transparency > 0.0
                    || m.textured.is_some();
                let deeper = on && seg.depth < scene.settings.max_depth;
                if !deeper && scene.footprint_is_flat(ray, hit, &d) {
                    None
                } else {
                    d.of(scene, ray)
                        .and_then(|diff| scene.patch(hit, ray, &diff, deeper))
                }
            }
        };
        let tex = crate::texture::TexturePoint {
            footprint: patch.as_ref().map(|p| &p.footprint),
            ..hit.tex
        };
        let tex = &tex;
        // A copy of the hit only where a normal or bump map bends its normal.
        let detailed;
        let hit = if m.detail.is_some() {
            let mut h = *hit;
            scene.with_detail(&mut h, tex);
            detailed = h;
            &detailed
        } else {
            hit
        };
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
        // What the reflected and refracted rays' differentials start from: the ray's, the
        // patch's offsets, and its normal's changes turned with `ns` (they are the outward
        // normal's). Worked out once, for whichever child asks first; a patch made for the
        // textures has the normal's change wherever rays go on.
        let side = if entering { 1.0 } else { -1.0 };
        let passed = std::cell::OnceCell::new();
        let passed_on = || {
            *passed.get_or_init(|| {
                let diff = seg.diff.of(scene, ray)?;
                let p = patch.or_else(|| scene.patch(hit, ray, &diff, true))?;
                Some((diff, p.dp, p.dn.map(|v| v * side)))
            })
        };
        let base = scene.base_color(hit, tex);
        let above = offset_ray_origin(hit.point, n);
        // Rays from `above` leave through the outside exactly when the ray came from there.
        let skip_above = scene.leaving(hit, entering);
        if R::ACTIVE {
            rec.hit(hit_record(scene, hit, entering, base));
        }

        let terms = m.terms_at(&scene.textures, tex);
        let t = terms.transparency;
        let mut out = scene.ambient * base * (terms.ambient * (1.0 - t));
        if R::ACTIVE {
            rec.ambient(out);
        }
        if let Some(e) = &m.emission {
            let emitted = e.emitted(entering, &scene.textures, tex);
            out += emitted;
            if R::ACTIVE && emitted != Color::ZERO {
                rec.note(format!("emits {:?}", emitted.to_array()));
            }
        }
        let view = -d;
        // Whitted lights by the point, spot and directional lights, which come first.
        for (index, light) in scene.lights.iter().take_while(|l| l.is_delta()).enumerate() {
            let Some(ls) = light.sample_delta(above, Falloff::None) else {
                if R::ACTIVE {
                    rec.light(light_record(
                        index,
                        light,
                        Vec3A::ZERO,
                        None,
                        0.0,
                        Some("the point is outside the light's cone (or at the light)"),
                    ));
                }
                continue;
            };
            let cos = ns.dot(ls.to_light);
            if cos <= 0.0 || n.dot(ls.to_light) <= 0.0 {
                if R::ACTIVE {
                    rec.light(light_record(
                        index,
                        light,
                        ls.to_light,
                        Some(ls.distance),
                        cos,
                        Some("the light is behind the surface"),
                    ));
                }
                continue;
            }
            // What this light would add if nothing were in the way: diffuse (weighed by the
            // opaque part) and the Phong highlight.
            let diffuse = base * (terms.diffuse * cos * (1.0 - t));
            let mut specular = Color::ZERO;
            if terms.specular != Color::ZERO {
                let r = reflect(-ls.to_light, ns);
                specular = terms.specular * phong_lobe(r.dot(view), terms.shininess);
            }
            let direct = diffuse + specular;
            // A shadow ray cannot change what is too faint to see (clear glass away from its
            // highlight adds nothing here).
            if direct.max_element() < MIN_RESPONSE {
                if R::ACTIVE {
                    let mut l = light_record(
                        index,
                        light,
                        ls.to_light,
                        Some(ls.distance),
                        cos,
                        Some("the surface returns too little of this light to need a shadow ray"),
                    );
                    l.diffuse = diffuse.to_array();
                    l.specular = specular.to_array();
                    rec.light(l);
                }
                continue;
            }
            let (seen, shadow) =
                self.shadow_recorded::<R>(scene, above, ls.to_light, ls.distance, skip_above, rays);
            let adds = ls.radiance * direct * seen;
            out += adds;
            if R::ACTIVE {
                let mut l = light_record(index, light, ls.to_light, Some(ls.distance), cos, None);
                l.radiance = ls.radiance.to_array();
                l.diffuse = diffuse.to_array();
                l.specular = specular.to_array();
                l.shadow = shadow;
                l.contribution = adds.to_array();
                rec.light(l);
            }
        }
        if seg.depth >= scene.settings.max_depth {
            if R::ACTIVE && (t > 0.0 || terms.reflectivity > 0.0) {
                rec.note(format!(
                    "no reflected or refracted rays: max_depth {} reached",
                    scene.settings.max_depth
                ));
            }
            return drawn.map_or(out, |w| out * w);
        }
        // The mirror's share in its tint (white but for metals), glass's by Fresnel.
        let mut reflect_weight = Color::splat((1.0 - t) * terms.reflectivity) * m.mirror_tint;
        if t > 0.0 {
            let eta = if entering { 1.0 / ior } else { ior };
            let cos_i = view.dot(ns);
            let (fresnel, through) = fresnel_refract(d, ns, cos_i, eta);
            reflect_weight += Color::splat(t * fresnel);
            // A shading normal can bend a ray back out of the surface; the true normal
            // cannot. (Not needed under total internal reflection.)
            let refracted = || {
                through
                    .filter(|r| r.dot(n) < 0.0)
                    .or_else(|| refract(d, n, eta))
            };
            if R::ACTIVE {
                let c = cos_i.clamp(0.0, 1.0);
                let sin_i = (1.0 - c * c).max(0.0).sqrt();
                let tir = eta * sin_i >= 1.0;
                rec.fresnel(FresnelRecord {
                    cos_i,
                    sin_i,
                    eta,
                    sin_t: (!tir).then_some(eta * sin_i),
                    reflectance: fresnel,
                    total_internal_reflection: tir,
                });
            }
            if fresnel < 1.0
                && let Some(dir) = refracted()
            {
                let below = offset_ray_origin(hit.point, -n);
                // Inside a solid there is absorption (maybe none) and never fog.
                let (inside, filter) = if entering {
                    (Some(m.absorption), base)
                } else {
                    (None, Color::ONE)
                };
                let weight = filter * (t * (1.0 - fresnel));
                let child = Segment {
                    kind: RayKind::Refraction,
                    from: hit.point,
                    depth: seg.depth + 1,
                    medium: inside,
                    weight,
                    skip: scene.leaving(hit, !entering),
                    inside: if entering {
                        hit.object as u32
                    } else {
                        NOT_INSIDE
                    },
                    nm,
                    u_wavelength: seg.u_wavelength,
                    diff: passed_on().map_or(RayDifferentials::None, |(diff, dp, dn)| {
                        RayDifferentials::Known(diff.refracted(ray, dir, dp, dn, ns, eta))
                    }),
                };
                out += self.trace_from(scene, &Ray::new(below, dir), &child, rays, rec) * weight;
            }
        }
        if reflect_weight.max_element() > 0.0 {
            // Unit already (see `reflect`): normalising it took 1.4 % of the seed scene's time.
            let mut dir = reflect(d, ns);
            if dir.dot(n) <= 0.0 {
                dir = reflect(d, n);
            }
            let r = Ray::new(above, dir);
            let child = Segment {
                kind: RayKind::Reflection,
                from: hit.point,
                depth: seg.depth + 1,
                medium: seg.medium,
                weight: reflect_weight,
                skip: skip_above,
                // Reflected off the inside, a ray stays in the solid.
                inside: if entering {
                    seg.inside
                } else {
                    hit.object as u32
                },
                nm,
                u_wavelength: seg.u_wavelength,
                diff: passed_on().map_or(RayDifferentials::None, |(diff, dp, dn)| {
                    RayDifferentials::Known(diff.reflected(ray, dp, dn, ns))
                }),
            };
            out += self.trace_from(scene, &r, &child, rays, rec) * reflect_weight;
        }
        drawn.map_or(out, |w| out * w)
    }
}

/// The record of a hit.
fn hit_record(scene: &Scene, hit: &Hit, entering: bool, base: Color) -> HitRecord {
    let m = scene.material_at(hit);
    let terms = m.terms_at(&scene.textures, &hit.tex);
    HitRecord {
        object: scene.objects[hit.object].name.clone(),
        object_index: hit.object,
        t: hit.t,
        point: hit.point.to_array(),
        normal: hit.normal.to_array(),
        shading_normal: hit.shading_normal.to_array(),
        uv: uv2(scene.texture_uv(hit)),
        side: if entering { "outside" } else { "inside" },
        material: scene
            .material_names
            .get(hit.material)
            .cloned()
            .unwrap_or_default(),
        terms: MaterialTerms {
            color: base.to_array(),
            ambient: terms.ambient,
            diffuse: terms.diffuse,
            specular: terms.specular.to_array(),
            shininess: terms.shininess,
            reflectivity: terms.reflectivity,
            transparency: terms.transparency,
            ior: m.ior,
            absorption: m.absorption.to_array(),
        },
    }
}

/// A light's record before its terms are known.
fn light_record(
    index: usize,
    light: &Light,
    to_light: Vec3A,
    distance: Option<f32>,
    cos: f32,
    skipped: Option<&'static str>,
) -> LightRecord {
    LightRecord {
        light: index,
        kind: light.kind_name(),
        to_light: to_light.to_array(),
        distance: distance.filter(|d| d.is_finite()),
        cos,
        radiance: [0.0; 3],
        diffuse: [0.0; 3],
        specular: [0.0; 3],
        shadow: None,
        contribution: [0.0; 3],
        skipped,
    }
}

/// A number in `[0, 1)` from a camera ray's bits, for the wavelength its tree follows where
/// the ray is not one of a pixel's samples (`snell explain`'s ray through a pixel's centre,
/// [`Whitted::trace`]'s): the same ray always gets the same one.
fn ray_wavelength_number(ray: &Ray) -> f32 {
    let bits = |v: Vec3A| v.to_array().map(|x| x.to_bits() as u64);
    let [a, b, c] = bits(ray.dir);
    let [d, e, f] = bits(ray.origin);
    let h = crate::math::hash_seed(&[a, b, c, d, e, f]);
    (h >> 40) as f32 / (1u64 << 24) as f32
}

/// The number for the wavelength of sample `index` of pixel `(x, y)`: the golden ratio's
/// sequence from a start of the pixel's own, so that a pixel's samples, and any run of them
/// (those of its strata a glass edge covers), spread their wavelengths evenly over the
/// visible range instead of at random: a dispersive glass's fire without the colour noise
/// of independent draws.
/// `shift` is the pixel's start, [`wavelength_start`].
fn wavelength_number(shift: f64, index: u32) -> f32 {
    let u = (shift + index as f64 * 0.618_033_988_749_894_9).fract();
    (u as f32).min(1.0 - f32::EPSILON)
}

/// Where pixel `(x, y)`'s sequence of wavelength numbers starts ([`wavelength_number`]).
fn wavelength_start(x: u32, y: u32) -> f64 {
    let start = crate::math::hash_seed(&[x as u64, y as u64, 0x5eed]);
    (start >> 40) as f64 / (1u64 << 24) as f64
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
