//! The sampling lab (`snell lab`): a material's BSDF sampled from one direction (or a scene's
//! lights from one point), its samples' histogram over the sphere beside the histogram its
//! density predicts, and the chi-square test between them, as Nori's warptest shows them to
//! a class. The BSDF is the one a render
//! would use: the material is built by the scene loader from its keys, so every check and
//! message is the scene file's.

use crate::Scene;
use crate::bsdf::Bsdf;
use crate::film::Image;
use crate::light::{Falloff, Light};
use crate::math::chi2::{self, Chi2, SphereBins};
use crate::math::{Color, Ray, Vec3A, hash_seed};
use crate::scene::format::MaterialKind;
use std::path::Path;

/// The bins every experiment of the lab uses: 40 bands of 4.5 degrees by 80 sectors.
pub const BINS: SphereBins = SphereBins { theta: 40, phi: 80 };

/// A material's BSDF, as a render builds it at a point facing the viewer.
#[derive(Clone, Debug)]
pub struct LabBsdf {
    /// How the material was given: `plastic (roughness = 0.3)`.
    pub title: String,
    /// Its BSDF at the point.
    pub bsdf: Bsdf,
}

/// Why a material could not be built: each problem in the words of the scene loader, named
/// by its key.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LabError(pub Vec<String>);

impl std::fmt::Display for LabError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0.join("\n"))
    }
}

impl std::error::Error for LabError {}

/// The material of `kind` (a scene file's `type`) with `params`, each a key and a value in
/// the scene file's syntax (`("roughness", "0.3")`, `("eta", "[0.2, 0.4, 1.4]")`).
pub fn material_bsdf(kind: &str, params: &[(String, String)]) -> Result<LabBsdf, LabError> {
    if !MaterialKind::ALL.iter().any(|k| k.name() == kind) {
        let names: Vec<&str> = MaterialKind::ALL.iter().map(|k| k.name()).collect();
        let hint = crate::scene::did_you_mean(kind, names.iter().copied())
            .map(|n| format!(" (did you mean `{n}`?)"))
            .unwrap_or_default();
        return Err(LabError(vec![format!(
            "no material type `{kind}`{hint}; the types are {}",
            names.join(", ")
        )]));
    }
    let mut table = format!("type = \"{kind}\"\n");
    for (key, value) in params {
        if key.is_empty() || !key.chars().all(|c| c.is_ascii_lowercase() || c == '_') {
            return Err(LabError(vec![format!(
                "`{key}` is not a material key (keys are lowercase words joined by _)"
            )]));
        }
        if value.contains(['\n', '\r']) {
            return Err(LabError(vec![format!("the value of `{key}` spans lines")]));
        }
        table += &format!("{key} = {value}\n");
    }
    // A sphere under a camera straight above it: the ray through the pixel meets it at the
    // origin, its normal toward the camera.
    let text = format!(
        "[image]\nwidth = 1\nheight = 1\n[camera]\nposition = [0, 0, 2]\nlook_at = [0, 0, 0]\n\
         [materials.lab]\n{table}[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -1]\n\
         radius = 1\nmaterial = \"lab\"\n"
    );
    let scene = crate::scene::load_str(
        &text,
        Path::new("lab"),
        Path::new("."),
        crate::scene::Format::Toml,
    )
    .map_err(|e| {
        LabError(
            e.diagnostics
                .iter()
                .map(|d| {
                    let m = d.message().replace("materials.lab.", "");
                    match d.help() {
                        Some(h) => format!("{m} ({h})"),
                        None => m,
                    }
                })
                .collect(),
        )
    })?;
    let ray = Ray::new(Vec3A::new(0.0, 0.0, 2.0), -Vec3A::Z);
    let hit = scene
        .closest_hit(&ray, f32::INFINITY)
        .expect("the lab's ray meets its sphere");
    let m = scene.material_at(&hit);
    let base = scene.base_color(&hit, &hit.tex);
    let shown: Vec<String> = params.iter().map(|(k, v)| format!("{k} = {v}")).collect();
    let title = match shown.is_empty() {
        true => kind.to_string(),
        false => format!("{kind} ({})", shown.join(", ")),
    };
    Ok(LabBsdf {
        title,
        bsdf: m.bsdf(&scene.textures, &hit.tex, base),
    })
}

/// A BSDF's sampling from one direction against its density.
#[derive(Clone, Debug)]
pub struct WarpTest {
    /// The bins of the sphere (`theta` from the normal, `phi` about it).
    pub bins: SphereBins,
    /// Samples drawn.
    pub samples: usize,
    /// Of them, those that took a mirror or smooth-glass lobe (a delta, which no histogram
    /// of a density can show: left out of both).
    pub specular: usize,
    /// Of them, those the BSDF absorbed (no direction).
    pub absorbed: usize,
    /// Samples in each bin, band by band.
    pub observed: Vec<f64>,
    /// What the density predicts in each bin.
    pub expected: Vec<f64>,
    /// The test between the two.
    pub chi2: Chi2,
    /// A sample whose value or density disagreed with the BSDF's own `f` and `pdf` for its
    /// direction (the first one), if any.
    pub inconsistent: Option<String>,
}

/// Samples `bsdf` `samples` times for light leaving along `wo` (local frame, `z` the normal)
/// and tests where the samples go against its density.
pub fn warp_test(
    bsdf: &Bsdf,
    wo: Vec3A,
    samples: usize,
    bins: SphereBins,
) -> Result<WarpTest, String> {
    let (mut specular, mut absorbed) = (0, 0);
    let mut inconsistent = None;
    // The lobe choice from a hash of the sample's number, not a second PCG stream: streams
    // of one generator can be correlated, and a correlated choice biases the directions it
    // keeps.
    let mut k = 0u64;
    let observed = chi2::sphere_histogram(bins, samples, |u| {
        k += 1;
        let uc = (hash_seed(&[k, 0x10be]) >> 40) as f32 / (1u64 << 24) as f32;
        let Some(s) = bsdf.sample(wo, u, uc) else {
            absorbed += 1;
            return None;
        };
        if s.lobe.is_specular() {
            specular += 1;
            return None;
        }
        let (f, pdf) = (bsdf.f(wo, s.wi), bsdf.pdf(wo, s.wi));
        let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * a.abs().max(b.abs()).max(1e-3);
        if inconsistent.is_none() && !(close(s.pdf, pdf) && (0..3).all(|i| close(s.f[i], f[i]))) {
            inconsistent = Some(format!(
                "a sample toward {} has f = {} and pdf = {}, but the BSDF gives f = {f} and pdf = {pdf} there",
                s.wi, s.f, s.pdf
            ));
        }
        Some(s.wi)
    })?;
    let expected = chi2::sphere_expected(bins, samples, |wi| bsdf.pdf(wo, wi));
    Ok(WarpTest::new(
        bins,
        samples,
        (specular, absorbed),
        observed,
        expected,
        inconsistent,
    ))
}

/// A scene's light sampling seen from the point `from`: where next-event estimation's
/// samples (a light chosen by power, a point of it) lie, against the density it reports
/// for each direction, the sum over the lights of each one's chance times its density there,
/// which MIS weighs the BSDF's samples by. Directions are binned with `theta` from straight
/// up (`+y`); point, spot and directional lights are deltas, counted apart.
pub fn light_test(
    scene: &Scene,
    from: Vec3A,
    samples: usize,
    bins: SphereBins,
) -> Result<WarpTest, String> {
    // Up (+y) as the bins' pole, by a rotation (x, y, z) -> (z, x, y).
    let to_bins = |d: Vec3A| Vec3A::new(d.z, d.x, d.y);
    let from_bins = |d: Vec3A| Vec3A::new(d.y, d.z, d.x);
    let pdf = |dir: Vec3A| light_pdf(scene, from, dir);
    let (mut specular, mut absorbed) = (0, 0);
    // A sample on the very rim of a light (a ray grazing a sphere) may miss it when traced
    // back: a few in ten thousand disagreeing are rounding, more are a fault.
    let (mut disagree, mut first_disagreement) = (0usize, None);
    let mut k = 0u64;
    let observed = chi2::sphere_histogram(bins, samples, |u| {
        k += 1;
        let uc = (hash_seed(&[k, 0x11a6]) >> 40) as f32 / (1u64 << 24) as f32;
        let Some(c) =
            scene
                .light_sampler
                .sample(&scene.lights, from, uc, u, Falloff::InverseSquare)
        else {
            absorbed += 1;
            return None;
        };
        if c.delta {
            specular += 1;
            return None;
        }
        let p = pdf(c.to_light);
        if (c.pdf - p).abs() > 1e-3 * c.pdf.max(p) {
            disagree += 1;
            first_disagreement.get_or_insert_with(|| {
                format!(
                    "a sample toward {} has density {}, but the lights give {p} there",
                    c.to_light, c.pdf
                )
            });
        }
        Some(to_bins(c.to_light))
    })?;
    let expected = chi2::sphere_expected(bins, samples, |d| pdf(from_bins(d)));
    let inconsistent = (disagree * 10_000 > samples).then(|| {
        format!(
            "{disagree} samples disagree; {}",
            first_disagreement.unwrap_or_default()
        )
    });
    Ok(WarpTest::new(
        bins,
        samples,
        (specular, absorbed),
        observed,
        expected,
        inconsistent,
    ))
}

/// The density per unit solid angle with which next-event estimation from `from` picks
/// direction `dir`: over the area lights the ray meets and the environment, each light's
/// chance times its own density.
fn light_pdf(scene: &Scene, from: Vec3A, dir: Vec3A) -> f32 {
    let ray = Ray::new(from, dir);
    let mut total = 0.0;
    for (i, light) in scene.lights.iter().enumerate() {
        let chance = scene.light_sampler.probability(i);
        if chance <= 0.0 {
            continue;
        }
        total += chance
            * match light {
                // A one-sided light is never sampled from behind.
                Light::Area(a) => match a.emitter.intersect(&ray) {
                    Some((point, normal)) if a.two_sided || normal.dot(from - point) > 0.0 => {
                        a.pdf(from, point, normal)
                    }
                    _ => 0.0,
                },
                Light::Environment(e) => e.pdf(dir),
                _ => 0.0,
            };
    }
    total
}

/// The direction light leaves along at `degrees` from the normal, in the local frame.
pub fn leaving_at(degrees: f32) -> Vec3A {
    let (s, c) = degrees.to_radians().sin_cos();
    Vec3A::new(s, 0.0, c)
}

impl WarpTest {
    /// The test of `observed` counts against `expected` ones, the chi-square worked out.
    fn new(
        bins: SphereBins,
        samples: usize,
        (specular, absorbed): (usize, usize),
        observed: Vec<f64>,
        expected: Vec<f64>,
        inconsistent: Option<String>,
    ) -> Self {
        WarpTest {
            bins,
            samples,
            specular,
            absorbed,
            chi2: chi2::compare(&observed, &expected),
            observed,
            expected,
            inconsistent,
        }
    }

    /// Whether the samples follow the density and agree with the BSDF's values.
    pub fn passed(&self) -> bool {
        self.chi2.passed() && self.inconsistent.is_none()
    }

    /// The two histograms and their difference side by side, each `theta` down (the normal
    /// at the top, the plane across the middle) by `phi` across, `scale` pixels a bin: the
    /// samples', the density's (both in grey, white at the fullest bin), and the difference
    /// in standard deviations of the count (red more samples than expected, blue fewer, full
    /// at 4).
    pub fn image(&self, scale: u32) -> Image {
        let (nt, np) = (self.bins.theta as u32, self.bins.phi as u32);
        let gap = scale.max(2);
        let (pw, ph) = (np * scale, nt * scale);
        let mut img = Image::new(3 * pw + 2 * gap, ph);
        img.pixels.fill(Color::splat(0.05)); // the gaps between the panels
        let most = self
            .expected
            .iter()
            .chain(&self.observed)
            .fold(1.0f64, |a, &b| a.max(b));
        for y in 0..ph {
            for x in 0..3 * pw + 2 * gap {
                let (panel, px) = (x / (pw + gap), x % (pw + gap));
                if px >= pw {
                    continue; // a gap
                }
                let bin = ((y / scale) * np + px / scale) as usize;
                let (o, e) = (self.observed[bin], self.expected[bin]);
                let c = match panel {
                    0 => Color::splat((o / most) as f32),
                    1 => Color::splat((e / most) as f32),
                    _ => {
                        let z = ((o - e) / e.max(1.0).sqrt() / 4.0).clamp(-1.0, 1.0) as f32;
                        if z >= 0.0 {
                            Color::new(z, 0.0, 0.0)
                        } else {
                            Color::new(0.0, 0.0, -z)
                        }
                    }
                };
                img.pixels[(y * img.width + x) as usize] = c;
            }
        }
        img
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(list: &[(&str, &str)]) -> Vec<(String, String)> {
        list.iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect()
    }

    #[test]
    fn every_material_type_builds_and_its_sampling_passes() {
        let cases = [
            ("diffuse", params(&[])),
            ("plastic", params(&[("roughness", "0.3")])),
            (
                "conductor",
                params(&[("metal", "\"Au\""), ("roughness", "0.2")]),
            ),
            ("dielectric", params(&[("roughness", "0.25")])),
            (
                "metallic",
                params(&[("metallic", "0.5"), ("roughness", "0.4")]),
            ),
            ("thin", params(&[])),
            ("phong", params(&[("specular", "1"), ("shininess", "20")])),
        ];
        let bins = SphereBins::default();
        for (kind, p) in &cases {
            let lab = material_bsdf(kind, p).unwrap_or_else(|e| panic!("{kind}: {e}"));
            let t = warp_test(&lab.bsdf, leaving_at(40.0), 1 << 18, bins).unwrap();
            assert!(
                t.passed(),
                "{}: {:?} {:?}",
                lab.title,
                t.chi2,
                t.inconsistent
            );
            assert_eq!(t.observed.len(), 800);
        }
        assert_eq!(cases.len(), MaterialKind::ALL.len());
    }

    #[test]
    fn smooth_glass_is_all_delta_and_the_histogram_sees_none_of_it() {
        let lab = material_bsdf("dielectric", &[]).unwrap();
        let t = warp_test(&lab.bsdf, leaving_at(30.0), 10_000, SphereBins::default()).unwrap();
        assert_eq!(t.specular + t.absorbed, 10_000);
        assert_eq!(t.observed.iter().sum::<f64>(), 0.0);
    }

    #[test]
    fn a_wrong_density_fails() {
        // Diffuse samples tested against a uniform hemisphere's density.
        let lab = material_bsdf("diffuse", &[]).unwrap();
        let bins = SphereBins::default();
        let n = 1 << 18;
        let observed = chi2::sphere_histogram(bins, n, |u| {
            Some(lab.bsdf.sample(leaving_at(0.0), u, 0.5)?.wi)
        })
        .unwrap();
        let uniform = chi2::sphere_expected(bins, n, |w| {
            if w.z > 0.0 {
                1.0 / (2.0 * std::f32::consts::PI)
            } else {
                0.0
            }
        });
        assert!(!chi2::compare(&observed, &uniform).passed());
    }

    #[test]
    fn bad_materials_are_told_in_the_loaders_words() {
        let e = material_bsdf("plastik", &[]).unwrap_err();
        assert!(e.0[0].contains("did you mean `plastic`"), "{e}");
        let e = material_bsdf("plastic", &params(&[("roughness", "-1")])).unwrap_err();
        assert!(e.0[0].starts_with("roughness"), "{e}");
        let e = material_bsdf("diffuse", &params(&[("ior", "1.5")])).unwrap_err();
        assert!(e.to_string().contains("ior"), "{e}");
        let e = material_bsdf("diffuse", &params(&[("Color", "1")])).unwrap_err();
        assert!(e.0[0].contains("not a material key"), "{e}");
        let e = material_bsdf("diffuse", &params(&[("color", "1\n[x]")])).unwrap_err();
        assert!(e.0[0].contains("spans lines"), "{e}");
    }

    #[test]
    fn the_lights_of_a_scene_are_sampled_as_their_density_says() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let scene = crate::scene::load(&root.join("scenes/cornell.toml")).unwrap();
        let t = light_test(&scene, Vec3A::ZERO, 1 << 18, SphereBins::default()).unwrap();
        assert!(t.passed(), "{:?} {:?}", t.chi2, t.inconsistent);
        assert!(t.observed.iter().sum::<f64>() > 200_000.0);
        // From above the light, which glows downward only: nothing is sampled, nothing
        // expected.
        let t = light_test(
            &scene,
            Vec3A::new(0.0, 1.0, 0.0),
            1 << 16,
            SphereBins::default(),
        )
        .unwrap();
        assert_eq!(t.absorbed, 1 << 16);
        assert!(t.passed() && t.expected.iter().sum::<f64>() == 0.0);
        // An environment map and a sphere light together.
        let text = "[camera]\nlook_at = [0, 0, -1]\n[environment]\ntype = \"image\"\n\
                    file = \"assets/env/studio.hdr\"\n\
                    [materials.glow]\ntype = \"diffuse\"\nemission = 20\n[[objects]]\n\
                    type = \"sphere\"\ncenter = [0, 3, 0]\nradius = 0.5\nmaterial = \"glow\"\n";
        let scene = crate::scene::load_str(
            text,
            std::path::Path::new("t.toml"),
            root,
            crate::scene::Format::Toml,
        )
        .unwrap();
        let t = light_test(&scene, Vec3A::ZERO, 1 << 18, SphereBins::default()).unwrap();
        assert!(t.passed(), "{:?} {:?}", t.chi2, t.inconsistent);
        assert_eq!(t.specular, 0);
    }

    #[test]
    fn the_picture_has_three_panels_of_the_bins() {
        let lab = material_bsdf("diffuse", &[]).unwrap();
        let t = warp_test(&lab.bsdf, leaving_at(0.0), 1 << 16, SphereBins::default()).unwrap();
        let img = t.image(4);
        assert_eq!((img.width, img.height), (3 * 160 + 2 * 4, 80));
        // Below the surface (the lower half) nothing is expected or drawn.
        let at = |x: u32, y: u32| img.pixels[(y * img.width + x) as usize];
        assert_eq!(at(10, 70), Color::ZERO);
        assert_eq!(at(161, 10), Color::splat(0.05), "a gap");
        assert!(at(10, 30).x > 0.0);
    }
}
