//! Whitted-style recursive ray tracing, the seed report's model made correct: Phong direct
//! light with shadow rays (lighter, tinted shadows behind transparent objects), mirror
//! reflection, and refraction by Snell's law with exact Fresnel weights and total internal
//! reflection, through solids of any shape, with Beer-Lambert absorption inside them.

mod shadow;

use super::explain::{
    FresnelRecord, HitRecord, LightRecord, MaterialTerms, NoRecord, RayKind, Recorder, uv2,
};
use super::{BatchStart, Integrator, RayStats};
use crate::light::{Falloff, Light};
use crate::math::{
    Color, Ray, Vec3A, Wavelength, fresnel_dielectric, offset_ray_origin, reflect, refract,
};
use crate::scene::{Hit, RayDifferentials, Scene, Skip};

/// Whether the textures at `hit` are one colour over the footprint of `ray`'s
/// differentials `diff`, from a bound on the footprint that needs no footprint worked out
/// ([`Scene::texture_flat_within`]). A neighbour whose origin is `do` and direction `dd`
/// away meets the hit's tangent plane at
/// `do + (dd c t - d f - dd f - d t e) / (c + e)` from the hit (`c = n . d`, `e = n . dd`,
/// `f = n . do`, `t` the hit's distance along the unit `d`), no further than
/// `|do| + (|dd| t (|c| + 1) + |do| (1 + |dd|)) / (|c| - |dd|)`; a camera ray's neighbours
/// share its origin and turn by at most the camera's spread. Where that is inside one cell
/// of a checker, the texture read at the point is what the footprint's filter gives, and
/// the footprint is not worked out: most of a checker floor, seen or mirrored.
#[inline]
fn footprint_flat(scene: &Scene, ray: &Ray, hit: &Hit, diff: &RayDifferentials) -> bool {
    let c = ray.dir.dot(hit.normal).abs();
    let t = hit.t;
    let reach = |origin: f32, turn: f32| {
        (c > 2.0 * turn)
            .then(|| origin + (turn * t * (c + 1.0) + origin * (1.0 + turn)) / (c - turn))
    };
    let reach = match diff {
        RayDifferentials::None => None,
        RayDifferentials::Camera => scene.camera_spread().and_then(|spread| reach(0.0, spread)),
        RayDifferentials::Known(d) => reach(d.dx_origin.length(), d.dx_dir.length())
            .zip(reach(d.dy_origin.length(), d.dy_dir.length()))
            .map(|(x, y)| x.max(y)),
    };
    // A hundredth more, for the rounding of the footprint's own arithmetic.
    reach.is_some_and(|r| scene.texture_flat_within(hit, r * 1.01))
}

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
        for (batch, out) in batch.chunks(N).zip(out.chunks_mut(N)) {
            let mut found: [Option<Hit>; N] = [None; N];
            let found = &mut found[..batch.len()];
            scene.closest_hits(batch, found, first.reach);
            for ((ray, f), o) in batch.iter().zip(found.iter()).zip(out.iter_mut()) {
                let u = if scene.disperses() {
                    wavelength_number(first.x, first.y, index)
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
        let u = if scene.disperses() {
            ray_wavelength_number(ray)
        } else {
            0.0
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
                if !deeper && footprint_flat(scene, ray, hit, &d) {
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
            let fresnel = fresnel_dielectric(cos_i, eta);
            reflect_weight += Color::splat(t * fresnel);
            // A shading normal can bend a ray back out of the surface; the true normal
            // cannot.
            let refracted = refract(d, ns, eta)
                .filter(|r| r.dot(n) < 0.0)
                .or_else(|| refract(d, n, eta));
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
                && let Some(dir) = refracted
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

/// Phong's highlight, `max(cos, 0)^shininess`. Whole exponents up to 256 (as scene files
/// give them) are raised by repeated squaring, several times cheaper than `powf`'s logarithm
/// and exponential; each squaring doubles the rounding error, which stays under 2e-5 of the
/// value there. From exponent 32 on, a cosine under 1/2 gives under 2^-32 of the light
/// (2.3e-10, nothing a picture can show), taken as 0 without the squarings: most directions
/// are that far from the highlight.
#[inline]
fn phong_lobe(cos: f32, shininess: f32) -> f32 {
    let c = cos.max(0.0);
    if shininess == shininess.trunc() && (0.0..=256.0).contains(&shininess) {
        if shininess >= 32.0 && c < 0.5 {
            return 0.0;
        }
        // `powi`'s own squarings, in its order (the same bits), inline: a variable exponent
        // made `powi` a call into the runtime library.
        let (mut base, mut e, mut product) = (c, shininess as u32, 1.0f32);
        loop {
            if e & 1 != 0 {
                product *= base;
            }
            e >>= 1;
            if e == 0 {
                return product;
            }
            base *= base;
        }
    } else {
        c.powf(shininess)
    }
}

/// A number in `[0, 1)` from a camera ray's bits, for the wavelength its tree follows where
/// the ray is not one of a pixel's samples (`snell explain`'s, [`Whitted::trace`]'s): the
/// same ray always gets the same one.
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
fn wavelength_number(x: u32, y: u32, index: u32) -> f32 {
    let start = crate::math::hash_seed(&[x as u64, y as u64, 0x5eed]);
    let shift = (start >> 40) as f64 / (1u64 << 24) as f64;
    let u = (shift + index as f64 * 0.618_033_988_749_894_9).fract();
    (u as f32).min(1.0 - f32::EPSILON)
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

#[cfg(test)]
mod tests {
    use super::phong_lobe;

    /// Where a camera ray's footprint, or a mirrored ray's, is taken as flat without working
    /// it out, the texture read at the point is what the filter over the footprint gives, to
    /// the bit: a checker and stripes on floors under a tilted camera, at several sample
    /// counts, seen directly and in a mirror ball; and both kinds of hit are found.
    #[test]
    fn a_flat_footprint_reads_what_the_filter_gives() {
        use crate::math::{Rng, Vec3A};
        use crate::scene::{Format, RayDifferentials, load_str};
        use crate::texture::TexturePoint;
        use std::path::Path;
        // Per kind of ray (camera, own differentials): footprints found flat, and not.
        let (mut flat, mut filtered) = ([0; 2], [0; 2]);
        for (spp, texture) in [
            (
                16,
                "type = \"checker\"\neven = [0.9, 0.8, 0.1]\nodd = [0.05, 0.2, 0.6]\nsize = 0.7",
            ),
            (4, "type = \"checker\"\nsize = 0.25"),
            (
                1,
                "type = \"stripes\"\na = [0.3, 0.7, 0.2]\nb = [1, 0.4, 0.9]\nwidth = 0.4",
            ),
        ] {
            let text = format!(
                "[image]\nwidth = 256\nheight = 192\nsamples = {spp}\n\
                 [camera]\nposition = [0, 2, 6]\nlook_at = [1, 0, -10]\nfov = 50\n\
                 [textures.t]\n{texture}\n\
                 mapping = {{ type = \"planar\", origin = [0.3, 0, 0.1], u = [1, 0, 0.2], v = [0, 0, 1.5] }}\n\
                 [materials.m]\ntexture = \"t\"\n\
                 [[objects]]\ntype = \"rectangle\"\ncorner = [-30, -1, 8]\nedge_u = [60, 0, 0]\nedge_v = [0, 0, -80]\nmaterial = \"m\"\n"
            );
            let scene = load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap();
            let camera = scene.camera.raster(256, 192);
            let mut rng = Rng::new(spp as u64);
            let mut random = |scale: f32| {
                Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * (2.0 * scale) - scale
            };
            for k in 0..40_000 {
                // Camera rays, and rays with differentials of their own (as a mirror passes
                // on): from above the floor, down, their neighbours apart and turning.
                let (ray, diff) = if k % 2 == 0 {
                    let (x, y) = (random(128.0).x + 128.0, random(96.0).y + 96.0);
                    let ray = camera.ray(x, y);
                    (ray, RayDifferentials::Camera)
                } else {
                    let origin = random(5.0) + Vec3A::new(0.0, 6.0, -5.0);
                    let dir = (random(1.0) - Vec3A::Y * 1.2).normalize();
                    let d = crate::math::differential::Differentials {
                        dx_origin: random(0.02),
                        dx_dir: random(0.004),
                        dy_origin: random(0.02),
                        dy_dir: random(0.004),
                    };
                    (
                        crate::math::Ray::new(origin, dir),
                        RayDifferentials::Known(d),
                    )
                };
                let Some(hit) = scene.closest_hit(&ray, f32::INFINITY) else {
                    continue;
                };
                let Some(d) = diff.of(&scene, &ray) else {
                    continue;
                };
                let patch = scene.patch(&hit, &ray, &d, false);
                let footprint = patch.as_ref().map(|p| &p.footprint);
                let tex = TexturePoint {
                    footprint,
                    ..hit.tex
                };
                let through = scene.base_color(&hit, &tex);
                if super::footprint_flat(&scene, &ray, &hit, &diff) {
                    let at_point = scene.base_color(&hit, &hit.tex);
                    assert_eq!(
                        at_point.to_array().map(f32::to_bits),
                        through.to_array().map(f32::to_bits),
                        "{spp} spp, {ray:?}"
                    );
                    flat[k % 2] += 1;
                } else {
                    filtered[k % 2] += 1;
                }
                assert!(hit.point.is_finite() && hit.normal != Vec3A::ZERO);
            }
        }
        for kind in 0..2 {
            assert!(
                flat[kind] > 2_000 && filtered[kind] > 500,
                "{flat:?} flat, {filtered:?} filtered"
            );
        }
    }

    #[test]
    fn phong_lobe_is_powf_within_rounding() {
        for shininess in [
            0.0f32, 1.0, 2.0, 7.0, 50.0, 100.0, 256.0, 1000.0, 2.5, 49.9, 5000.0,
        ] {
            for k in 0..=1000 {
                let c = k as f32 / 1000.0;
                let (fast, exact) = (phong_lobe(c, shininess), c.powf(shininess));
                // Relative error, or below 2^-32 where the lobe is cut off.
                assert!(
                    (fast - exact).abs() <= 2e-5 * exact.max(1e-30)
                        || (fast == 0.0 && exact < 2.33e-10),
                    "{c}^{shininess}: {fast} against {exact}"
                );
            }
            assert_eq!(phong_lobe(-0.5, shininess), 0.0f32.powf(shininess));
        }
        // The whole exponents' squarings are `powi`'s, to the bit.
        let mut checked = 0;
        for e in 0..=256u32 {
            for k in 500..=1000 {
                let c = k as f32 / 1000.0;
                assert_eq!(
                    phong_lobe(c, e as f32).to_bits(),
                    c.powi(e as i32).to_bits(),
                    "{c}^{e}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 257 * 501);
    }
}
