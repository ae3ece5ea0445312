//! A material's `ior`: a number, a named glass, or a formula in wavelength, with its
//! hand-written deserializer and schema.

use crate::material::dispersion::{Dispersion, NAMED};
use crate::scene::diag::name_help;
use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::fmt;

/// The index of refraction: `1.5`, `"BK7"`, `{ cauchy = [a, b] }` or
/// `{ sellmeier = [B1, B2, B3, C1, C2, C3] }` (b and C in µm²).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum IorDef {
    /// The same index at every wavelength.
    Value(f32),
    /// A named glass (`crate::material::dispersion::NAMED`).
    Named(String),
    /// A formula in wavelength.
    Formula(DispersionDef),
}

/// An index that changes with wavelength, by its coefficients (counted by the parser).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum DispersionDef {
    /// `n = a + b / λ²`: `[a, b]`, b in µm².
    Cauchy([f32; 2]),
    /// `n² = 1 + Σ Bᵢ λ² / (λ² - Cᵢ)`: `[B1, B2, B3, C1, C2, C3]`, C in µm².
    Sellmeier([f32; 6]),
}

const FORMULAS: &str = "{ cauchy = [a, b] } or { sellmeier = [B1, B2, B3, C1, C2, C3] } (b and C in square micrometres)";

impl<'de> Deserialize<'de> for IorDef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = IorDef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(
                    f,
                    "an index of refraction: a number, the name of a glass (\"BK7\", \"diamond\", \"water\"...), or {FORMULAS}"
                )
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<IorDef, E> {
                Ok(IorDef::Value(v as f32))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<IorDef, E> {
                Ok(IorDef::Value(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<IorDef, E> {
                Ok(IorDef::Value(v as f32))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<IorDef, E> {
                // Glass names are a closed set, as the schema says: an unknown one is refused
                // here, with the nearest.
                if Dispersion::named(v).is_some() {
                    return Ok(IorDef::Named(v.to_string()));
                }
                let names = NAMED.iter().map(|(n, _)| *n);
                Err(de::Error::custom(format!(
                    "no glass named `{v}`: {}",
                    name_help(v, names, "the named glasses", "")
                )))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<IorDef, A::Error> {
                let Some(key) = map.next_key::<String>()? else {
                    return Err(de::Error::custom(format!(
                        "an empty table: give {FORMULAS}"
                    )));
                };
                let (name, want, form) = match key.as_str() {
                    "cauchy" => ("Cauchy", 2, "[a, b]"),
                    "sellmeier" => ("Sellmeier", 6, "[B1, B2, B3, C1, C2, C3]"),
                    other => {
                        return Err(de::Error::custom(format!(
                            "unknown formula `{other}`: give {FORMULAS}"
                        )));
                    }
                };
                let c: Vec<f32> = map.next_value()?;
                if c.len() != want {
                    return Err(de::Error::custom(format!(
                        "a {name} index takes {want} coefficients, {form} (in micrometres squared where they have units): {} given",
                        c.len()
                    )));
                }
                let formula = match want {
                    2 => DispersionDef::Cauchy([c[0], c[1]]),
                    _ => DispersionDef::Sellmeier([c[0], c[1], c[2], c[3], c[4], c[5]]),
                };
                if let Some(more) = map.next_key::<String>()? {
                    return Err(de::Error::custom(format!(
                        "one formula per index (`{key}` and `{more}` given)"
                    )));
                }
                Ok(IorDef::Formula(formula))
            }
        }
        d.deserialize_any(V)
    }
}

impl JsonSchema for IorDef {
    fn schema_name() -> Cow<'static, str> {
        "Ior".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        let names: Vec<&str> = crate::material::dispersion::NAMED
            .iter()
            .map(|(n, _)| *n)
            .collect();
        let numbers = |n: usize| {
            json_schema!({
                "type": "array", "items": { "type": "number" }, "minItems": n, "maxItems": n
            })
        };
        json_schema!({
            "description": "The index of refraction: a number, a named glass, or a formula in wavelength (Cauchy [a, b] or Sellmeier [B1, B2, B3, C1, C2, C3], b and C in square micrometres).",
            "anyOf": [
                { "type": "number" },
                { "type": "string", "enum": names },
                {
                    "type": "object",
                    "properties": { "cauchy": numbers(2), "sellmeier": numbers(6) },
                    "additionalProperties": false,
                    "minProperties": 1,
                    "maxProperties": 1
                }
            ]
        })
    }
}
