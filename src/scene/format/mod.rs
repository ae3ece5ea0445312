//! The scene file, one to one: serde types for TOML and JSON. Every table rejects keys it
//! does not know. Defaults live here, checks of values live in `load`. docs/scene-format.md
//! documents every key. The same types give the scene's JSON Schema ([`schema`]): field docs
//! become its descriptions, serde defaults its defaults (shown where the default's type is
//! `Serialize`, which is why a few of these derive it).

mod animation;
mod constraints;
mod environment;
mod integrator;
mod ior;
mod material;
mod object;
mod texture;
mod values;

pub use animation::{
    AnimationDef, CameraKeyDef, InterpolationDef, KeyTimeDef, Keyed, LightKeyDef, ObjectKeyDef,
};
pub use environment::EnvironmentDef;
pub use integrator::{IntegratorDef, IntegratorKind, MisHeuristic, SamplerDef};
pub use ior::{DispersionDef, IorDef};
pub use material::{MaterialDef, MaterialKind};
pub use object::*;
pub use texture::{ColorSpaceDef, MappingDef, TextureDef, WrapDef};
pub use values::{ColorDef, ColorParamDef, ScalarDef, ScaleDef, UvScaleDef};

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A point or vector `[x, y, z]` in scene units.
pub type V3 = [f32; 3];

/// A whole scene file.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(
    title = "snell scene",
    description = "A scene for the snell ray tracer, in TOML or JSON. docs/scene-format.md \
                   documents every key."
)]
pub struct SceneFile {
    /// Where this file's JSON Schema is, for editors (`snell schema` writes one); snell
    /// itself ignores it.
    #[serde(rename = "$schema")]
    pub schema: Option<String>,
    /// Picture size, sampling and limits.
    #[serde(default)]
    pub image: ImageDef,
    /// How light is computed: the Whitted ray tracer or the path tracer, and its settings.
    #[serde(default)]
    pub integrator: IntegratorDef,
    /// The camera.
    pub camera: CameraDef,
    /// Light everywhere.
    #[serde(default)]
    pub world: WorldDef,
    /// Optional fog.
    pub fog: Option<FogDef>,
    /// Light from every direction, far away: an image or one colour (the path tracer's
    /// light; the picture's background).
    pub environment: Option<EnvironmentDef>,
    /// Named textures.
    #[serde(default)]
    pub textures: BTreeMap<String, TextureDef>,
    /// Named materials.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDef>,
    /// Light sources.
    #[serde(default)]
    pub lights: Vec<LightDef>,
    /// Meshes defined once and placed by objects of type `mesh` (instancing).
    #[serde(default)]
    pub meshes: BTreeMap<String, MeshDef>,
    /// The scene's objects: shapes, meshes and placed groups, each with its material.
    #[serde(default)]
    pub objects: Vec<ObjectDef>,
    /// Groups of objects defined once and placed by objects of type `group` (instancing).
    #[serde(default)]
    pub groups: BTreeMap<String, GroupDef>,
    /// Frames and keyframes: the camera, objects and lights moving over time (without it
    /// the scene is one frame, 0).
    pub animation: Option<AnimationDef>,
}

/// `[meshes.NAME]`: a mesh file, loaded once however many objects place it.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshDef {
    /// OBJ, PLY or glTF (.gltf, .glb) file, relative to the scene file.
    pub file: String,
    /// Vertex normals: `true` computes area-weighted ones when the file has none, `false`
    /// ignores the file's (flat shading); by default the file's are used when it has them.
    pub smooth: Option<bool>,
}

/// `[groups.NAME]`: objects placed together, as many times as objects of type `group`
/// name it.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GroupDef {
    /// The group's objects, in its own space (any type but `group`).
    pub objects: Vec<ObjectDef>,
}

/// `[image]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ImageDef {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Samples per pixel, a square number (n x n stratified).
    pub samples: u32,
    /// Reconstruction filter.
    pub filter: FilterDef,
    /// Colour of rays that hit nothing.
    pub background: ColorDef,
    /// Longest chain of rays (camera ray included).
    pub max_depth: u32,
    /// Seed of the sample jitter.
    pub seed: u64,
    /// Exposure of 8-bit outputs (PNG), in stops: values are multiplied by 2^exposure
    /// before the tone curve. EXR keeps the linear values.
    pub exposure: f32,
    /// Tone curve of 8-bit outputs: `clamp` (cut at 1, the default), `reinhard` or `aces`.
    pub tonemap: crate::output::tone::ToneCurve,
    /// Whether textures are read over the patch of surface each pixel sees (MIP-mapped
    /// images, filtered checker and stripes), as they should be; `false` reads them at a
    /// point, which aliases (moire on a far checker), to show the difference.
    pub filter_textures: bool,
    /// Light path expressions rendered beside the picture (path tracer): each an image of
    /// the light that came by the paths it matches (docs/lpe.md).
    pub lpe: Vec<LpeDef>,
    /// Adaptive sampling (path tracer): pixels stop taking samples once their estimated
    /// relative error is below this (0.01 is 1 %), `samples` the most they take.
    pub noise: Option<f32>,
}

/// `[[image.lpe]]`: an image of the light that came by the paths an expression matches,
/// written beside the picture (a layer `NAME.R`, `NAME.G`, `NAME.B` of an EXR, or
/// `x.NAME.png`). Give `name` and `expr`, or `preset`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LpeDef {
    /// The image's name: letters, digits, `_` and `-`, starting with a letter.
    pub name: Option<String>,
    /// The expression, in OSL's syntax, from the camera to the light: `C<RD>L`.
    pub expr: Option<String>,
    /// A preset instead of `name` and `expr`: `emission`, `direct`, `indirect`,
    /// `specular`, `caustics` or `per-light`.
    pub preset: Option<String>,
}

impl Default for ImageDef {
    fn default() -> Self {
        ImageDef {
            width: 800,
            height: 600,
            samples: 1,
            filter: FilterDef::default(),
            background: ColorDef([0.0; 3]),
            max_depth: 5,
            seed: 0,
            exposure: 0.0,
            tonemap: crate::output::tone::ToneCurve::Clamp,
            filter_textures: true,
            lpe: vec![],
            noise: None,
        }
    }
}

/// `filter = { type = "...", radius = ... }`.
#[derive(Debug, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FilterDef {
    /// Filter shape.
    #[serde(rename = "type")]
    pub kind: FilterKind,
    /// Half-width in pixels; default depends on the type.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f32>,
}

impl Default for FilterDef {
    fn default() -> Self {
        FilterDef {
            kind: FilterKind::Gaussian,
            radius: None,
        }
    }
}

pub use crate::film::FilterKind;
pub use crate::light::Falloff;

/// `[camera]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CameraDef {
    /// Eye position.
    #[serde(default)]
    pub position: V3,
    /// Point looked at (required unless `gltf` places the camera).
    pub look_at: Option<V3>,
    /// A glTF file (.gltf, .glb) whose camera this is: its placement, field of view or
    /// orthographic size stand for `position`, `look_at`, `up`, `fov`, `type` and `height`
    /// (`look_at`, `fov`, `type` and `height` are then errors; `position` and `up` are not
    /// read).
    pub gltf: Option<String>,
    /// Which of the file's cameras, by name (default: the first its nodes place).
    pub gltf_camera: Option<String>,
    /// Which way is up.
    #[serde(default = "y_axis")]
    pub up: V3,
    /// Vertical field of view in degrees, for a perspective camera (default 45).
    pub fov: Option<f32>,
    /// `"perspective"` (rays from the eye) or `"orthographic"` (parallel rays).
    #[serde(default, rename = "type")]
    pub kind: CameraKind,
    /// Orthographic: the height of the view in scene units (required there).
    pub height: Option<f32>,
    /// The lens's radius in scene units: 0 (a pinhole) keeps everything sharp; larger
    /// blurs what is nearer or farther than `focus_distance`.
    #[serde(default)]
    pub aperture: f32,
    /// Distance along the view to the plane in focus [default: the distance to look_at].
    pub focus_distance: Option<f32>,
}

/// `[camera] type`.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum CameraKind {
    /// Rays from the eye through the film.
    #[default]
    Perspective,
    /// Parallel rays along the view.
    Orthographic,
}

/// `[world]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct WorldDef {
    /// Global ambient light.
    pub ambient: ColorDef,
}

impl Default for WorldDef {
    fn default() -> Self {
        WorldDef {
            ambient: ColorDef([0.1; 3]),
        }
    }
}

/// `[fog]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FogDef {
    /// How fog thickens with distance.
    pub mode: FogMode,
    /// Colour far away.
    #[serde(default = "grey_half")]
    pub color: ColorDef,
    /// Linear: distance where fog begins.
    #[serde(default)]
    pub start: f32,
    /// Linear: distance where fog is complete.
    pub end: Option<f32>,
    /// Exponential: density per scene unit.
    pub density: Option<f32>,
}

/// Fog modes.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum FogMode {
    /// Rises linearly from `start` to `end`.
    Linear,
    /// `1 - exp(-density * distance)`.
    Exponential,
}

/// `[[lights]]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum LightDef {
    /// A point light.
    Point {
        /// Name, for messages and `[[animation.lights]]`.
        name: Option<String>,
        /// Where the light is, in the scene's coordinates.
        position: V3,
        /// How its light weakens with distance (default: `none` under the Whitted
        /// integrator, `inverse_square` under the path tracer).
        falloff: Option<Falloff>,
        /// Colour of the light, in linear RGB; `intensity` scales it.
        #[serde(default = "white")]
        color: ColorDef,
        /// Factor on `color`: how strong the light is (at least 0).
        #[serde(default = "one")]
        intensity: f32,
    },
    /// A directional light.
    Directional {
        /// Name, for messages and `[[animation.lights]]`.
        name: Option<String>,
        /// Direction the light travels.
        direction: V3,
        /// Colour of the light, in linear RGB; `intensity` scales it.
        #[serde(default = "white")]
        color: ColorDef,
        /// Factor on `color`: how strong the light is (at least 0).
        #[serde(default = "one")]
        intensity: f32,
    },
    /// A spot light.
    Spot {
        /// Name, for messages and `[[animation.lights]]`.
        name: Option<String>,
        /// Where the light is, in the scene's coordinates.
        position: V3,
        /// How its light weakens with distance (default: `none` under the Whitted
        /// integrator, `inverse_square` under the path tracer).
        falloff: Option<Falloff>,
        /// Point the cone is aimed at (or give `direction`).
        look_at: Option<V3>,
        /// Direction of the cone's axis (or give `look_at`).
        direction: Option<V3>,
        /// Colour of the light, in linear RGB; `intensity` scales it.
        #[serde(default = "white")]
        color: ColorDef,
        /// Factor on `color`: how strong the light is (at least 0).
        #[serde(default = "one")]
        intensity: f32,
        /// Half-angle of the cone, degrees.
        #[serde(default = "default_spot_angle")]
        angle: f32,
        /// Width of the soft edge inside the cone, degrees.
        #[serde(default = "default_soft_edge")]
        soft_edge: f32,
    },
}

impl LightDef {
    /// The light's `name`, if given.
    pub fn name(&self) -> &Option<String> {
        match self {
            LightDef::Point { name, .. }
            | LightDef::Directional { name, .. }
            | LightDef::Spot { name, .. } => name,
        }
    }
}

/// `transform = { ... }`: scale, then rotate (x, y, z, degrees), then translate.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TransformDef {
    /// Scale: a number or `[x, y, z]`.
    #[serde(default = "unit_scale")]
    pub scale: ScaleDef,
    /// Degrees about x, then y, then z.
    #[serde(default)]
    pub rotate: V3,
    /// Offset `[x, y, z]`, added after the scale and the rotation.
    #[serde(default)]
    pub translate: V3,
}

/// The JSON Schema of a scene file: what `snell schema` prints, for editors to complete keys
/// and flag mistakes as one types. Draft 7, which editors (VS Code's JSON support, taplo)
/// understand fully. Generated from these types ([`schema_of_types`]), with the ranges and
/// the rules between keys that the scene builder checks (`constraints.rs`).
pub fn schema() -> serde_json::Value {
    let mut schema = schema_of_types();
    constraints::constrain(&mut schema);
    schema
}

/// The schema of these types alone: what the parser reads before the builder checks any
/// value (tests compare the two).
pub fn schema_of_types() -> serde_json::Value {
    let mut schema = schemars::generate::SchemaSettings::draft07()
        .into_generator()
        .into_root_schema_for::<SceneFile>();
    schema.insert(
        "$comment".into(),
        format!(
            "Generated by `snell schema` (snell {}) from the types its parser reads.",
            env!("CARGO_PKG_VERSION")
        )
        .into(),
    );
    schema.to_value()
}

fn origin() -> V3 {
    [0.0; 3]
}
fn x_axis() -> V3 {
    [1.0, 0.0, 0.0]
}
fn y_axis() -> V3 {
    [0.0, 1.0, 0.0]
}
fn z_axis() -> V3 {
    [0.0, 0.0, 1.0]
}
fn yes() -> bool {
    true
}
fn one() -> f32 {
    1.0
}
fn white() -> ColorDef {
    ColorDef([1.0; 3])
}
fn black() -> ColorDef {
    ColorDef([0.0; 3])
}
fn grey_half() -> ColorDef {
    ColorDef([0.5; 3])
}
fn unit_scale() -> ScaleDef {
    ScaleDef([1.0; 3])
}
fn default_spot_angle() -> f32 {
    30.0
}
fn default_soft_edge() -> f32 {
    5.0
}
