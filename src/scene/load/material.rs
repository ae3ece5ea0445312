//! `[materials.NAME]` to a [`Material`]: the keys its type reads, checked, with a clear error
//! for a key that another type reads; colours and roughness constant or from textures.

use super::Builder;
use crate::bsdf::{ConductorFresnel, metals};
use crate::material::detail::SurfaceDetail;
use crate::material::{self, ColorParam, Emission, Material, Scalar, TexturedTerms};
use crate::math::Color;
use crate::scene::diag::{DocPath, did_you_mean, name_help};
use crate::scene::format::{ColorParamDef, MaterialDef, MaterialKind, ScalarDef};
use crate::texture::Texture;
use std::collections::BTreeMap;

/// The textures a material may name, and which have been named.
pub(crate) struct MaterialTextures<'a> {
    /// Every texture (a material's constant colour is added as a solid one).
    pub textures: &'a mut Vec<Texture>,
    /// The named textures, by name.
    pub names: &'a BTreeMap<String, usize>,
    /// Per named texture, whether some material uses it.
    pub used: &'a mut [bool],
}

impl MaterialTextures<'_> {
    /// A new solid texture of colour `c`.
    fn solid(&mut self, c: Color) -> usize {
        self.textures.push(Texture::solid(c));
        self.textures.len() - 1
    }
}

const DEFAULT_IOR: f32 = 1.5;

impl Builder<'_> {
    pub(super) fn material(
        &mut self,
        m: &MaterialDef,
        path: &DocPath,
        tex: &mut MaterialTextures,
    ) -> Material {
        for (key, kind) in m.given() {
            if !m.kind.reads(kind) {
                let readers: Vec<&str> = MaterialKind::ALL
                    .iter()
                    .filter(|k| k.reads(kind))
                    .map(|k| k.name())
                    .collect();
                self.error_help(
                    path.key(key),
                    format!(
                        "a `{}` material has no `{key}`: only {} materials read it",
                        m.kind.name(),
                        readers.join(", ")
                    ),
                    "remove it, or set `type` to the kind of material you mean (the default is `phong`)"
                        .to_string(),
                );
            }
        }
        let (texture, color) = self.material_color(m, path, tex);
        let emission = m.emission.as_ref().map(|e| Emission {
            radiance: self.color_param(e, &path.key("emission"), tex),
            two_sided: m.two_sided.unwrap_or(false),
        });
        if m.two_sided.is_some() && m.emission.is_none() {
            self.error_help(
                path.key("two_sided"),
                "`two_sided` says which sides emit, and this material has no `emission`",
                "add `emission = [r, g, b]`, or remove `two_sided`",
            );
        }
        let (ior, dispersion) = m
            .ior
            .as_ref()
            .and_then(|d| self.ior(d, &path.key("ior"), m.kind))
            .unwrap_or((DEFAULT_IOR, None));
        let absorption = m
            .absorption
            .map_or(Color::ZERO, |c| self.color(c, &path.key("absorption")));
        let detail = self.detail(m, path, tex);
        let mut out = self.surface(m, path, tex, (texture, color), emission, ior, absorption);
        out.detail = detail;
        out.dispersion = dispersion;
        out
    }

    /// The material of `m`'s type, from what the keys every type shares gave.
    #[allow(clippy::too_many_arguments)]
    fn surface(
        &mut self,
        m: &MaterialDef,
        path: &DocPath,
        tex: &mut MaterialTextures,
        (texture, color): (usize, Color),
        emission: Option<Emission>,
        ior: f32,
        absorption: Color,
    ) -> Material {
        let (roughness, alpha) = self.roughness(&m.roughness, &path.key("roughness"), tex);
        match m.kind {
            MaterialKind::Phong => {
                let mut out = Material::base(texture, material::Surface::Phong, emission);
                let mut textured = TexturedTerms::default();
                let key = |k: &str| path.key(k);
                let any = |b: &mut Self, x: f32, p: &DocPath| b.non_negative(x, p);
                let unit = |b: &mut Self, x: f32, p: &DocPath| b.in_range(x, 0.0, 1.0, p);
                let mut term =
                    |b: &mut Self, d: &Option<ScalarDef>, name, slot: &mut f32, check| {
                        if let Some(d) = d {
                            match b.scalar(d, &key(name), tex, check) {
                                Scalar::Value(v) => *slot = v,
                                Scalar::Texture(i) => return Some(i),
                            }
                        }
                        None
                    };
                textured.ambient = term(self, &m.ambient, "ambient", &mut out.terms.ambient, &any);
                textured.diffuse = term(self, &m.diffuse, "diffuse", &mut out.terms.diffuse, &any);
                textured.shininess = term(
                    self,
                    &m.shininess,
                    "shininess",
                    &mut out.terms.shininess,
                    &any,
                );
                textured.reflectivity = term(
                    self,
                    &m.reflectivity,
                    "reflectivity",
                    &mut out.terms.reflectivity,
                    &unit,
                );
                textured.transparency = term(
                    self,
                    &m.transparency,
                    "transparency",
                    &mut out.terms.transparency,
                    &unit,
                );
                match m
                    .specular
                    .as_ref()
                    .map(|c| self.color_param(c, &key("specular"), tex))
                {
                    Some(ColorParam::Value(c)) => out.terms.specular = c,
                    Some(ColorParam::Texture(i)) => textured.specular = Some(i),
                    None => {}
                }
                if textured != TexturedTerms::default() {
                    out.textured = Some(Box::new(textured));
                }
                out.ior = ior;
                out.absorption = absorption;
                out
            }
            MaterialKind::Diffuse => material::diffuse::material(texture, emission),
            MaterialKind::Conductor => {
                let (fresnel, index) = self.conductor_fresnel(m, path, tex);
                material::conductor::Conductor {
                    fresnel,
                    index,
                    roughness,
                }
                .material(texture, color, alpha, emission)
            }
            MaterialKind::Dielectric => material::dielectric::Dielectric { roughness }
                .material(texture, ior, absorption, alpha, emission),
            MaterialKind::Thin => material::thin::material(texture, ior, emission),
            MaterialKind::Plastic => material::plastic::Plastic::new(roughness, ior)
                .material(texture, ior, alpha, emission),
            MaterialKind::Metallic => {
                let unit = |b: &mut Self, x: f32, p: &DocPath| b.in_range(x, 0.0, 1.0, p);
                let metallic = m.metallic.as_ref().map_or(Scalar::Value(1.0), |d| {
                    self.scalar(d, &path.key("metallic"), tex, &unit)
                });
                let mean = match metallic {
                    Scalar::Value(v) => v,
                    Scalar::Texture(t) => tex.textures[t].mean().element_sum() / 3.0,
                };
                material::metallic::Metallic {
                    dielectric: material::plastic::Plastic::new(roughness, ior),
                    metallic,
                }
                .material(texture, color, ior, alpha, mean, emission)
            }
        }
    }

    /// The normal or bump map, if the material has one.
    fn detail(
        &mut self,
        m: &MaterialDef,
        path: &DocPath,
        tex: &mut MaterialTextures,
    ) -> Option<SurfaceDetail> {
        let orphan = |b: &mut Self, given: bool, key: &str, needs: &str| {
            if given {
                b.error_help(
                    path.key(key),
                    format!(
                        "`{key}` says how strong `{needs}` is, and this material has no `{needs}`"
                    ),
                    format!("add `{needs} = \"TEXTURE\"`, or remove `{key}`"),
                );
            }
        };
        orphan(
            self,
            m.normal_scale.is_some() && m.normal_map.is_none(),
            "normal_scale",
            "normal_map",
        );
        orphan(
            self,
            m.bump_height.is_some() && m.bump.is_none(),
            "bump_height",
            "bump",
        );
        match (&m.normal_map, &m.bump) {
            (Some(_), Some(_)) => {
                self.error_help(
                    path.key("bump"),
                    "a material takes `normal_map` or `bump`, not both",
                    "remove one of them",
                );
                None
            }
            (Some(name), None) => {
                let texture = self.texture_named(name, &path.key("normal_map"), tex)?;
                let scale = m
                    .normal_scale
                    .map_or(1.0, |x| self.finite(x, &path.key("normal_scale")));
                Some(SurfaceDetail::Normal { texture, scale })
            }
            (None, Some(name)) => {
                let texture = self.texture_named(name, &path.key("bump"), tex)?;
                let height = m
                    .bump_height
                    .map_or(1.0, |x| self.finite(x, &path.key("bump_height")));
                Some(SurfaceDetail::Bump { texture, height })
            }
            (None, None) => None,
        }
    }

    /// The texture giving the material's colour (a new solid one for a constant colour),
    /// and the colour where it is constant (white where a texture gives it).
    fn material_color(
        &mut self,
        m: &MaterialDef,
        path: &DocPath,
        tex: &mut MaterialTextures,
    ) -> (usize, Color) {
        match (&m.color, &m.texture) {
            (Some(_), Some(_)) => {
                self.error_help(
                    path.key("texture"),
                    "a material takes `color` or `texture`, not both",
                    "remove one of them",
                );
                (tex.solid(Color::ONE), Color::ONE)
            }
            (None, Some(t)) => match self.texture_named(t, &path.key("texture"), tex) {
                Some(i) => (i, Color::ONE),
                None => (tex.solid(Color::ONE), Color::ONE),
            },
            (c, None) => {
                let c = c.map_or(Color::ONE, |c| self.color(c, &path.key("color")));
                (tex.solid(c), c)
            }
        }
    }

    /// The named texture's index, marked used, or an error with a suggestion.
    fn texture_named(
        &mut self,
        name: &str,
        path: &DocPath,
        tex: &mut MaterialTextures,
    ) -> Option<usize> {
        if let Some(&i) = tex.names.get(name) {
            tex.used[i] = true;
            return Some(i);
        }
        let help = name_help(
            name,
            tex.names.keys().map(String::as_str),
            "defined textures",
            "define it under [textures.NAME]",
        );
        self.error_help(path.clone(), format!("no texture named `{name}`"), help);
        None
    }

    /// A number or the named texture: a constant checked by `check`, or the texture's index
    /// (marked used; a missing name is an error, and reads as 0).
    fn scalar(
        &mut self,
        d: &ScalarDef,
        path: &DocPath,
        tex: &mut MaterialTextures,
        check: &dyn Fn(&mut Self, f32, &DocPath) -> f32,
    ) -> Scalar {
        match d {
            ScalarDef::Value(v) => Scalar::Value(check(self, *v, path)),
            ScalarDef::Texture(name) => match self.texture_named(name, path, tex) {
                Some(i) => Scalar::Texture(i),
                None => Scalar::Value(0.0),
            },
        }
    }

    /// A colour or the named texture (a missing name is an error, and reads as black).
    fn color_param(
        &mut self,
        d: &ColorParamDef,
        path: &DocPath,
        tex: &mut MaterialTextures,
    ) -> ColorParam {
        match d {
            ColorParamDef::Value(c) => ColorParam::Value(self.color(*c, path)),
            ColorParamDef::Texture(name) => match self.texture_named(name, path, tex) {
                Some(i) => ColorParam::Texture(i),
                None => ColorParam::Value(Color::ZERO),
            },
        }
    }

    /// The roughness and, for the Whitted integrator, its constant value (a texture's is
    /// taken as 0.5 there, a middling highlight).
    fn roughness(
        &mut self,
        r: &Option<ScalarDef>,
        path: &DocPath,
        tex: &mut MaterialTextures,
    ) -> (Scalar, f32) {
        let unit = |b: &mut Self, x: f32, p: &DocPath| b.in_range(x, 0.0, 1.0, p);
        match r.as_ref().map(|r| self.scalar(r, path, tex, &unit)) {
            None => (Scalar::Value(0.0), 0.0),
            Some(Scalar::Value(v)) => (Scalar::Value(v), v),
            Some(t) => (t, 0.5),
        }
    }

    /// A conductor's reflectance: a named metal, `eta` and `k`, or a perfect mirror; and
    /// where `eta` or `k` is a texture, both as read point by point (the reflectance then
    /// holds their means, which Whitted reads).
    fn conductor_fresnel(
        &mut self,
        m: &MaterialDef,
        path: &DocPath,
        tex: &mut MaterialTextures,
    ) -> (ConductorFresnel, Option<[ColorParam; 2]>) {
        let mut index = |b: &mut Self, c: &Option<ColorParamDef>, key: &str| {
            c.as_ref().map(|c| b.color_param(c, &path.key(key), tex))
        };
        let (eta, k) = (index(self, &m.eta, "eta"), index(self, &m.k, "k"));
        if let (None, Some(eta), Some(k)) = (&m.metal, eta, k)
            && (matches!(eta, ColorParam::Texture(_)) || matches!(k, ColorParam::Texture(_)))
        {
            let fresnel = ConductorFresnel::Complex {
                eta: eta.mean(tex.textures),
                k: k.mean(tex.textures),
            };
            return (fresnel, Some([eta, k]));
        }
        let constant = |c: Option<ColorParam>| c.map(|c| c.mean(&[]));
        let fresnel = match (&m.metal, constant(eta), constant(k)) {
            (Some(name), None, None) => match metals::named(name) {
                Some((eta, k)) => ConductorFresnel::Complex { eta, k },
                None => {
                    let known = ["Au", "Ag", "Cu", "Al"];
                    let help = match did_you_mean(name, known) {
                        Some(s) => format!("did you mean `{s}`?"),
                        None => format!("snell knows {}", known.join(", ")),
                    };
                    self.error_help(path.key("metal"), format!("no metal named `{name}`"), help);
                    ConductorFresnel::One
                }
            },
            (Some(_), _, _) => {
                self.error_help(
                    path.key("metal"),
                    "a conductor takes `metal` or `eta` and `k`, not both",
                    "remove `metal`, or `eta` and `k`",
                );
                ConductorFresnel::One
            }
            (None, Some(eta), Some(k)) => ConductorFresnel::Complex { eta, k },
            (None, None, None) => ConductorFresnel::One,
            (None, eta, _) => {
                let missing = if eta.is_some() { "k" } else { "eta" };
                self.error_help(
                    path.key(if eta.is_some() { "eta" } else { "k" }),
                    format!("a conductor's index needs both `eta` and `k`; `{missing}` is missing"),
                    format!("add `{missing} = [r, g, b]`, or name a metal with `metal = \"Au\"`"),
                );
                ConductorFresnel::One
            }
        };
        (fresnel, None)
    }
}
