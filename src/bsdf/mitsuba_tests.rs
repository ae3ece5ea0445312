//! snell's BSDFs against Mitsuba 3's own numbers: tests/data/mitsuba/bsdf.json, printed by
//! Mitsuba's `eval`, `pdf` and `sample` (bsdf_fixture.py beside it) for every material that
//! names a Mitsuba counterpart, over a grid of directions and parameters. Each value must
//! agree within 1 %.

use super::microfacet::Ggx;
use super::{Bsdf, Conductor, ConductorFresnel, Dielectric, Lambert, MetallicMix, ThinDielectric};
use super::{Plastic, metals};
use crate::math::{Color, Vec2, Vec3A};
use serde::Deserialize;

#[derive(Deserialize)]
struct Fixture {
    mitsuba: String,
    cases: Vec<Case>,
}

/// One BSDF: its parameters as snell's scene file gives them, and Mitsuba's rows.
#[derive(Deserialize)]
struct Case {
    snell: Params,
    /// `wo`, `wi`, Mitsuba's `eval` (RGB) and `pdf`.
    eval: Vec<[f32; 10]>,
    /// `wo`, the sample numbers (`uc`, `u`), then what Mitsuba drew: `wi`, `f |cos wi|`
    /// (RGB) and the pdf there (for a delta lobe, the weight times the lobe's chance, and
    /// that chance), and 1 for a delta lobe.
    #[serde(default)]
    sample: Vec<[f32; 14]>,
}

#[derive(Deserialize, Debug)]
struct Params {
    r#type: String,
    color: Option<[f32; 3]>,
    metal: Option<String>,
    tint: Option<[f32; 3]>,
    roughness: Option<f32>,
    ior: Option<f32>,
    metallic: Option<f32>,
}

impl Params {
    fn color(&self, key: Option<[f32; 3]>) -> Color {
        key.map_or(Color::ONE, Color::from)
    }

    fn bsdf(&self) -> Bsdf {
        let distribution = Ggx::isotropic(self.roughness.unwrap_or(0.0));
        let ior = self.ior.unwrap_or(1.5);
        let base = self.color(self.color);
        let plastic = || Plastic::new(base, ior, distribution);
        match self.r#type.as_str() {
            "diffuse" => Bsdf::Lambert(Lambert { r: base }),
            "conductor" => {
                let fresnel = match self.metal.as_deref() {
                    Some("none") => ConductorFresnel::One,
                    Some(name) => {
                        let (eta, k) = metals::named(name).expect("a metal snell names");
                        ConductorFresnel::Complex { eta, k }
                    }
                    None => panic!("a conductor without a metal: {self:?}"),
                };
                Bsdf::Conductor(Conductor {
                    fresnel,
                    distribution,
                    tint: self.color(self.tint),
                })
            }
            "dielectric" => Bsdf::Dielectric(Dielectric {
                eta: ior,
                distribution,
            }),
            "thin" => Bsdf::ThinDielectric(ThinDielectric { eta: ior }),
            "plastic" => Bsdf::Plastic(plastic()),
            "metallic" => Bsdf::Metallic(MetallicMix {
                metal: Conductor {
                    fresnel: ConductorFresnel::One,
                    distribution,
                    tint: base,
                },
                dielectric: plastic(),
                metallic: self.metallic.expect("metallic's share"),
            }),
            other => panic!("no snell BSDF for {other}"),
        }
    }
}

/// Within 1 % of Mitsuba's value, or within `1e-5` of it where both are about 0.
fn close(snell: f32, mitsuba: f32) -> bool {
    (snell - mitsuba).abs() <= 0.01 * mitsuba.abs().max(snell.abs()) + 1e-5
}

fn v3(a: &[f32]) -> Vec3A {
    Vec3A::new(a[0], a[1], a[2])
}

/// `f |cos wi|` and the pdf at every direction pair Mitsuba evaluated, and at every
/// direction Mitsuba's `sample` drew; for a delta lobe, the same lobe chosen by the same
/// number, in the same direction, with the same weight and chance.
#[test]
fn every_bsdf_agrees_with_mitsuba() {
    let fixture: Fixture =
        serde_json::from_str(include_str!("../../tests/data/mitsuba/bsdf.json")).unwrap();
    assert_eq!(fixture.mitsuba, "3.9.1");
    let (mut checked, mut failures) = (0usize, Vec::new());
    for case in &fixture.cases {
        let mut failed = 0;
        let mut fail = |case: &Params, what: String| {
            failed += 1;
            if failed <= 2 {
                failures.push(format!("{case:?}: {what}"));
            }
        };
        let bsdf = case.snell.bsdf();
        for row in &case.eval {
            let (wo, wi) = (v3(&row[0..3]), v3(&row[3..6]));
            let f = bsdf.f(wo, wi) * wi.z.abs();
            let pdf = bsdf.pdf(wo, wi);
            checked += 1;
            if !((0..3).all(|k| close(f[k], row[6 + k])) && close(pdf, row[9])) {
                fail(
                    &case.snell,
                    format!(
                        "wo {wo} wi {wi}: f|cos| {f} pdf {pdf}, Mitsuba {:?} {}",
                        &row[6..9],
                        row[9]
                    ),
                );
            }
        }
        for row in &case.sample {
            let wo = v3(&row[0..3]);
            let (uc, u) = (row[3], Vec2::new(row[4], row[5]));
            let (wi, mitsuba_f, pdf, delta) =
                (v3(&row[6..9]), v3(&row[9..12]), row[12], row[13] == 1.0);
            checked += 1;
            if pdf == 0.0 {
                continue;
            }
            let (f, p) = if delta {
                match bsdf.sample(wo, u, uc) {
                    Some(s) if s.lobe.is_specular() && (s.wi - wi).length() < 1e-4 => {
                        (s.f * s.wi.z.abs(), s.pdf)
                    }
                    other => {
                        fail(
                            &case.snell,
                            format!("wo {wo} uc {uc}: Mitsuba's delta to {wi}, snell {other:?}"),
                        );
                        continue;
                    }
                }
            } else {
                (bsdf.f(wo, wi) * wi.z.abs(), bsdf.pdf(wo, wi))
            };
            if !((0..3).all(|k| close(f[k], mitsuba_f[k])) && close(p, pdf)) {
                fail(
                    &case.snell,
                    format!(
                        "sampled wo {wo} wi {wi}: f|cos| {f} pdf {p}, Mitsuba {mitsuba_f} {pdf}"
                    ),
                );
            }
        }
        if failed > 2 {
            failures.push(format!("{:?}: {} more", case.snell, failed - 2));
        }
    }
    assert_eq!(checked, 6932 + 984);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A white rough plastic of index 1.5 seen and lit along its normal returns what Mitsuba's
/// `roughplastic` does (its sample weights' mean, 200,000 samples, printed by
/// tests/data/mitsuba/plastic_albedo.py): the rougher the coat, the more its microfacets
/// shadow, and the less comes back. snell's mean over a 256 x 256 grid of sample numbers
/// (the lobe chosen by a third, hashed), within 0.01.
#[test]
fn a_white_rough_plastic_returns_what_mitsubas_does() {
    let mut checked = 0;
    for (alpha, mitsuba) in [(0.1, 0.90894), (0.3, 0.69153), (1.0, 0.33567)] {
        let bsdf = Bsdf::Plastic(Plastic::new(Color::ONE, 1.5, Ggx::isotropic(alpha)));
        let (wo, n) = (Vec3A::Z, 256);
        let mut rng = crate::math::Rng::new(3);
        let mut sum = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                if let Some(s) = bsdf.sample(wo, u, rng.next_f32())
                    && s.pdf > 0.0
                {
                    sum += (s.f.x * s.wi.z.abs() / s.pdf) as f64;
                }
            }
        }
        let albedo = sum / (n * n) as f64;
        assert!(
            (albedo - mitsuba).abs() < 0.01,
            "alpha {alpha}: {albedo} against Mitsuba's {mitsuba}"
        );
        checked += 1;
    }
    assert_eq!(checked, 3);
}
