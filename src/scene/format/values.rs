//! The scene file's values that read in more than one shape: colours and scales, written as
//! one number or as an array, with their hand-written deserializers and schemas.

use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::fmt;

/// A colour: `[r, g, b]` in linear RGB, or one number for grey.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ColorDef(pub [f32; 3]);

impl<'de> Deserialize<'de> for ColorDef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = ColorDef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a colour: [r, g, b] or one number for grey")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<ColorDef, E> {
                Ok(ColorDef([v as f32; 3]))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<ColorDef, E> {
                Ok(ColorDef([v as f32; 3]))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<ColorDef, E> {
                Ok(ColorDef([v as f32; 3]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<ColorDef, A::Error> {
                three(seq, &self).map(ColorDef)
            }
        }
        d.deserialize_any(V)
    }
}

/// A scale: one number for all axes or `[x, y, z]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ScaleDef(pub [f32; 3]);

impl<'de> Deserialize<'de> for ScaleDef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        ColorDef::deserialize(d)
            .map(|c| ScaleDef(c.0))
            .map_err(|e| {
                de::Error::custom(e.to_string().replace(
                    "a colour: [r, g, b] or one number for grey",
                    "a scale: one number or [x, y, z]",
                ))
            })
    }
}

/// The schema of [`ColorDef`] and [`ScaleDef`]: one number, or an array of exactly three.
fn number_or_three(description: &str) -> Schema {
    json_schema!({
        "description": description,
        "type": ["number", "array"],
        "items": { "type": "number" },
        "minItems": 3,
        "maxItems": 3,
    })
}

impl JsonSchema for ColorDef {
    fn schema_name() -> Cow<'static, str> {
        "Color".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        number_or_three("A colour: [r, g, b] in linear RGB, or one number for grey.")
    }
}

impl JsonSchema for ScaleDef {
    fn schema_name() -> Cow<'static, str> {
        "Scale".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        number_or_three("A scale: one number for all axes, or [x, y, z].")
    }
}

/// A uv scale: one number for both directions or `[u, v]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct UvScaleDef(pub [f32; 2]);

impl<'de> Deserialize<'de> for UvScaleDef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = UvScaleDef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a uv scale: one number or [u, v]")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<UvScaleDef, E> {
                Ok(UvScaleDef([v as f32; 2]))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<UvScaleDef, E> {
                Ok(UvScaleDef([v as f32; 2]))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<UvScaleDef, E> {
                Ok(UvScaleDef([v as f32; 2]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<UvScaleDef, A::Error> {
                let mut out = [0.0; 2];
                for (i, slot) in out.iter_mut().enumerate() {
                    *slot = seq
                        .next_element::<f32>()?
                        .ok_or_else(|| de::Error::invalid_length(i, &self))?;
                }
                if seq.next_element::<de::IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(3, &self));
                }
                Ok(UvScaleDef(out))
            }
        }
        d.deserialize_any(V)
    }
}

impl JsonSchema for UvScaleDef {
    fn schema_name() -> Cow<'static, str> {
        "UvScale".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A uv scale: one number for both directions, or [u, v].",
            "type": ["number", "array"],
            "items": { "type": "number" },
            "minItems": 2,
            "maxItems": 2,
        })
    }
}

fn three<'de, A: SeqAccess<'de>>(mut seq: A, exp: &dyn de::Expected) -> Result<[f32; 3], A::Error> {
    let mut out = [0.0; 3];
    for (i, slot) in out.iter_mut().enumerate() {
        *slot = seq
            .next_element::<f32>()?
            .ok_or_else(|| de::Error::invalid_length(i, exp))?;
    }
    if seq.next_element::<de::IgnoredAny>()?.is_some() {
        return Err(de::Error::invalid_length(4, exp));
    }
    Ok(out)
}

/// A material's number: a constant, or the name of a texture whose mean of r, g and b gives
/// it at each point.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum ScalarDef {
    /// The same everywhere.
    Value(f32),
    /// Read from the named texture.
    Texture(String),
}

impl<'de> Deserialize<'de> for ScalarDef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = ScalarDef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number, or the name of a texture")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<ScalarDef, E> {
                Ok(ScalarDef::Value(v as f32))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<ScalarDef, E> {
                Ok(ScalarDef::Value(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<ScalarDef, E> {
                Ok(ScalarDef::Value(v as f32))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<ScalarDef, E> {
                Ok(ScalarDef::Texture(v.to_string()))
            }
        }
        d.deserialize_any(V)
    }
}

impl JsonSchema for ScalarDef {
    fn schema_name() -> Cow<'static, str> {
        "Scalar".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A number, or the name of a texture (its mean of r, g and b at each point).",
            "type": ["number", "string"],
        })
    }
}

/// A material's colour: `[r, g, b]` or one number for grey, or the name of a texture that
/// gives it at each point.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum ColorParamDef {
    /// The same everywhere.
    Value(ColorDef),
    /// Read from the named texture.
    Texture(String),
}

impl<'de> Deserialize<'de> for ColorParamDef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = ColorParamDef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a colour ([r, g, b] or one number for grey), or the name of a texture")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<ColorParamDef, E> {
                Ok(ColorParamDef::Value(ColorDef([v as f32; 3])))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<ColorParamDef, E> {
                Ok(ColorParamDef::Value(ColorDef([v as f32; 3])))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<ColorParamDef, E> {
                Ok(ColorParamDef::Value(ColorDef([v as f32; 3])))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<ColorParamDef, A::Error> {
                three(seq, &self).map(|c| ColorParamDef::Value(ColorDef(c)))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<ColorParamDef, E> {
                Ok(ColorParamDef::Texture(v.to_string()))
            }
        }
        d.deserialize_any(V)
    }
}

impl JsonSchema for ColorParamDef {
    fn schema_name() -> Cow<'static, str> {
        "ColorOrTexture".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A colour ([r, g, b] in linear RGB, or one number for grey), or the name of a texture that gives it.",
            "type": ["number", "array", "string"],
            "items": { "type": "number" },
            "minItems": 3,
            "maxItems": 3,
        })
    }
}
