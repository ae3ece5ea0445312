//! `[animation]`: the frame count and rate, and keyframes of the camera, of named objects'
//! transforms and of named lights. Each key gives some properties at one moment; a
//! property's curve runs through the keys that give it.

use super::{ColorDef, ScaleDef, V3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// `[animation]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AnimationDef {
    /// How many frames the animation has: frames 0 to `frames - 1`.
    pub frames: u32,
    /// Frames per second: what a key's `time` (in seconds) is in frames.
    #[serde(default = "default_fps")]
    pub fps: f32,
    /// How values change between keys, unless a key says otherwise: `smooth`
    /// (Catmull-Rom), `linear`, or `step` (held until the next key).
    #[serde(default)]
    pub interpolation: InterpolationDef,
    /// Keys of the camera.
    #[serde(default)]
    pub camera: Vec<CameraKeyDef>,
    /// Keys of named objects' transforms.
    #[serde(default)]
    pub objects: Vec<ObjectKeyDef>,
    /// Keys of named lights.
    #[serde(default)]
    pub lights: Vec<LightKeyDef>,
}

fn default_fps() -> f32 {
    24.0
}

/// How a value goes from one key to the next.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum InterpolationDef {
    /// A Catmull-Rom spline through the keys (flat at a key equal to a neighbour).
    #[default]
    Smooth,
    /// A straight line to the next key.
    Linear,
    /// The key's value held until the next key.
    Step,
}

/// When a key is: `frame` or `time`, and how it goes on to the next.
#[derive(Clone, Copy, Debug)]
pub struct KeyTimeDef {
    /// The frame of this key (may be fractional).
    pub frame: Option<f32>,
    /// The time of this key in seconds (instead of `frame`): frame `time * fps`.
    pub time: Option<f32>,
    /// How the values go from this key to the next (default: the animation's).
    pub interpolation: Option<InterpolationDef>,
}

/// `[[animation.camera]]`: the camera's values at one moment.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CameraKeyDef {
    /// The frame of this key (may be fractional).
    pub frame: Option<f32>,
    /// The time of this key in seconds (instead of `frame`): frame `time * fps`.
    pub time: Option<f32>,
    /// How the values go from this key to the next (default: the animation's).
    pub interpolation: Option<InterpolationDef>,
    /// Eye position.
    pub position: Option<V3>,
    /// Point looked at.
    pub look_at: Option<V3>,
    /// Which way is up.
    pub up: Option<V3>,
    /// Vertical field of view in degrees.
    pub fov: Option<f32>,
    /// Distance to the plane in focus.
    pub focus_distance: Option<f32>,
}

/// `[[animation.objects]]`: a named object's transform at one moment.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObjectKeyDef {
    /// The object's `name`.
    pub object: String,
    /// The frame of this key (may be fractional).
    pub frame: Option<f32>,
    /// The time of this key in seconds (instead of `frame`): frame `time * fps`.
    pub time: Option<f32>,
    /// How the values go from this key to the next (default: the animation's).
    pub interpolation: Option<InterpolationDef>,
    /// The transform's scale: a number or `[x, y, z]`.
    pub scale: Option<ScaleDef>,
    /// The transform's rotation, degrees about x, then y, then z (360 is a whole turn,
    /// not the same as 0: angles are interpolated as numbers).
    pub rotate: Option<V3>,
    /// The transform's offset.
    pub translate: Option<V3>,
}

/// `[[animation.lights]]`: a named light's values at one moment.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LightKeyDef {
    /// The light's `name`.
    pub light: String,
    /// The frame of this key (may be fractional).
    pub frame: Option<f32>,
    /// The time of this key in seconds (instead of `frame`): frame `time * fps`.
    pub time: Option<f32>,
    /// How the values go from this key to the next (default: the animation's).
    pub interpolation: Option<InterpolationDef>,
    /// Position (point and spot lights).
    pub position: Option<V3>,
    /// Direction the light travels (directional lights, and spots aimed by `direction`).
    pub direction: Option<V3>,
    /// Point a spot is aimed at (spots aimed by `look_at`).
    pub look_at: Option<V3>,
    /// The light's `color` at this key, in linear RGB.
    pub color: Option<ColorDef>,
    /// The light's `intensity` at this key: the factor on its colour (at least 0).
    pub intensity: Option<f32>,
}

/// What every key has: when it is and how it goes on.
pub trait Keyed {
    /// The key's `frame`, `time` and `interpolation`.
    fn when(&self) -> KeyTimeDef;
}

macro_rules! keyed {
    ($($t:ty),*) => {$(
        impl Keyed for $t {
            fn when(&self) -> KeyTimeDef {
                KeyTimeDef {
                    frame: self.frame,
                    time: self.time,
                    interpolation: self.interpolation,
                }
            }
        }
    )*};
}
keyed!(CameraKeyDef, ObjectKeyDef, LightKeyDef);
