//! What the scene's JSON Schema says beyond the types it is generated from: the ranges of
//! numbers, the keys that must be given, and the keys that exclude or need one another, as
//! the scene builder checks them, so that an editor marks what `snell check` refuses. What a
//! schema cannot say (a name that names nothing, a file that cannot be read, a box whose
//! `max` is below its `min`) stays the builder's alone; tests/integration/schema/verdicts.rs lists
//! each such case of tests/bad/ and fails on any other disagreement.

use serde_json::{Map, Value, json};

/// The largest magnitude of a number in a scene (the builder's `MAX_MAGNITUDE`).
const MAX: f64 = 1e15;

/// Adds the constraints to `schema`, a draft-07 schema of [`super::SceneFile`].
pub(super) fn constrain(schema: &mut Value) {
    let Some(defs) = schema.get_mut("definitions").and_then(Value::as_object_mut) else {
        return;
    };
    let positive = json!({ "exclusiveMinimum": 0, "maximum": MAX });
    let non_negative = json!({ "minimum": 0, "maximum": MAX });
    let unit = json!({ "minimum": 0, "maximum": 1 });
    let angle = json!({ "exclusiveMinimum": 0, "exclusiveMaximum": 180 });
    let ranges: [(&str, Option<&str>, &str, &Value); 38] = [
        (
            "ImageDef",
            None,
            "width",
            &json!({ "minimum": 1, "maximum": 65536 }),
        ),
        (
            "ImageDef",
            None,
            "height",
            &json!({ "minimum": 1, "maximum": 65536 }),
        ),
        ("ImageDef", None, "samples", &json!({ "minimum": 1 })),
        (
            "ImageDef",
            None,
            "max_depth",
            &json!({ "minimum": 1, "maximum": 64 }),
        ),
        (
            "ImageDef",
            None,
            "exposure",
            &json!({ "minimum": -20, "maximum": 20 }),
        ),
        ("IntegratorDef", None, "clamp", &positive),
        ("CameraDef", None, "fov", &angle),
        ("CameraDef", None, "aperture", &non_negative),
        ("CameraDef", None, "focus_distance", &positive),
        ("CameraDef", None, "height", &positive),
        ("CameraKeyDef", None, "fov", &angle),
        ("CameraKeyDef", None, "focus_distance", &positive),
        (
            "AnimationDef",
            None,
            "frames",
            &json!({ "minimum": 1, "maximum": 1_000_000 }),
        ),
        ("AnimationDef", None, "fps", &positive),
        ("LightKeyDef", None, "intensity", &non_negative),
        ("LightDef", Some("point"), "intensity", &non_negative),
        ("LightDef", Some("directional"), "intensity", &non_negative),
        ("LightDef", Some("spot"), "intensity", &non_negative),
        ("LightDef", Some("spot"), "angle", &angle),
        ("FogDef", None, "start", &non_negative),
        ("FogDef", None, "density", &positive),
        (
            "EnvironmentDef",
            Some("sky"),
            "sun_elevation",
            &json!({ "minimum": 0, "maximum": 90 }),
        ),
        (
            "EnvironmentDef",
            Some("sky"),
            "latitude",
            &json!({ "minimum": -90, "maximum": 90 }),
        ),
        (
            "EnvironmentDef",
            Some("sky"),
            "longitude",
            &json!({ "minimum": -180, "maximum": 180 }),
        ),
        (
            "EnvironmentDef",
            Some("sky"),
            "day",
            &json!({ "minimum": 1, "maximum": 366 }),
        ),
        (
            "EnvironmentDef",
            Some("sky"),
            "hour",
            &json!({ "minimum": 0, "maximum": 24 }),
        ),
        ("MaterialDef", None, "ior", &positive),
        ("MaterialDef", None, "transparency", &unit),
        ("MaterialDef", None, "reflectivity", &unit),
        ("MaterialDef", None, "metallic", &unit),
        ("MaterialDef", None, "roughness", &unit),
        ("ObjectDef", Some("sphere"), "radius", &positive),
        ("ObjectDef", Some("cylinder"), "radius", &positive),
        ("ObjectDef", Some("cylinder"), "height", &positive),
        ("ObjectDef", Some("cone"), "radius", &positive),
        ("ObjectDef", Some("cone"), "height", &positive),
        ("ObjectDef", Some("torus"), "major_radius", &positive),
        ("ObjectDef", Some("disk"), "radius", &positive),
    ];
    for (def, variant, key, range) in ranges {
        add_to_property(defs, def, variant, key, range);
    }
    add_to_property(defs, "ObjectDef", Some("torus"), "minor_radius", &positive);
    add_to_property(
        defs,
        "ObjectDef",
        Some("csg"),
        "shapes",
        &json!({ "minItems": 2 }),
    );

    let rules: [(&str, Option<&str>, Value); 14] = [
        // The camera: placed by `look_at` or by a glTF file, not both; an orthographic
        // one by the height of its view, a perspective one by its field of view.
        ("CameraDef", None, one_of_keys(&["look_at", "gltf"])),
        ("CameraDef", None, needs("gltf_camera", "gltf")),
        (
            "CameraDef",
            None,
            json!({
                "if": { "properties": { "type": { "const": "orthographic" } }, "required": ["type"] },
                "then": { "allOf": [given("height"), { "not": given("fov") }] },
                "else": { "not": given("height") }
            }),
        ),
        (
            "LightDef",
            Some("spot"),
            one_of_keys(&["look_at", "direction"]),
        ),
        (
            "FogDef",
            None,
            json!({
                "if": { "properties": { "mode": { "const": "linear" } } },
                "then": given("end"),
                "else": given("density")
            }),
        ),
        (
            "EnvironmentDef",
            Some("sky"),
            json!({ "oneOf": [
                given("sun_direction"),
                given("sun_elevation"),
                { "allOf": [given("latitude"), given("day"), given("hour")] }
            ]}),
        ),
        ("MaterialDef", None, not_both("color", "texture")),
        ("MaterialDef", None, not_both("normal_map", "bump")),
        ("MaterialDef", None, needs("normal_scale", "normal_map")),
        (
            "MaterialDef",
            None,
            json!({
                "if": { "not": { "properties": { "type": { "const": "metallic" } }, "required": ["type"] } },
                "then": { "not": given("metallic") }
            }),
        ),
        ("ObjectDef", Some("mesh"), one_of_keys(&["file", "mesh"])),
        (
            "ObjectDef",
            Some("mesh"),
            json!({ "if": given("mesh"), "then": { "not": given("smooth") } }),
        ),
        ("ObjectDef", Some("mesh"), needs("lights", "file")),
        ("CameraKeyDef", None, one_of_keys(&["frame", "time"])),
    ];
    for (def, variant, rule) in rules {
        add_rule(defs, def, variant, rule);
    }
    for def in ["ObjectKeyDef", "LightKeyDef"] {
        add_rule(defs, def, None, one_of_keys(&["frame", "time"]));
    }
    // Colours are never negative (a texture's name, where one may stand, is left alone).
    for def in ["Color", "ColorOrTexture"] {
        if let Some(color) = defs.get_mut(def) {
            let old = color.take();
            *color = json!({ "allOf": [old, {
                "minimum": 0,
                "items": { "minimum": 0 }
            }]});
        }
    }
    magnitudes(schema);
}

/// A key given, and not as `null` (which JSON allows and the parser reads as absent).
fn given(key: &str) -> Value {
    json!({ "required": [key], "properties": { key: { "not": { "type": "null" } } } })
}

/// Exactly one of `keys`.
fn one_of_keys(keys: &[&str]) -> Value {
    json!({ "oneOf": keys.iter().map(|k| given(k)).collect::<Vec<_>>() })
}

fn not_both(a: &str, b: &str) -> Value {
    json!({ "not": { "allOf": [given(a), given(b)] } })
}

/// `key`, where given, needs `other`.
fn needs(key: &str, other: &str) -> Value {
    json!({ "if": given(key), "then": given(other) })
}

/// The table `def` describes, or its branch whose `type` is `variant`.
fn table<'a>(
    defs: &'a mut Map<String, Value>,
    def: &str,
    variant: Option<&str>,
) -> Option<&'a mut Map<String, Value>> {
    let d = defs.get_mut(def)?;
    let d = match variant {
        None => d,
        Some(v) => d.get_mut("oneOf")?.as_array_mut()?.iter_mut().find(|b| {
            let t = &b["properties"]["type"];
            t["const"] == v || t["enum"] == json!([v])
        })?,
    };
    d.as_object_mut()
}

/// Adds `extra` to what property `key` of the table takes (beside its type, which numeric
/// keywords leave alone where the value is a texture's name).
fn add_to_property(
    defs: &mut Map<String, Value>,
    def: &str,
    variant: Option<&str>,
    key: &str,
    extra: &Value,
) {
    let p = table(defs, def, variant)
        .and_then(|t| t.get_mut("properties"))
        .and_then(|p| p.get_mut(key));
    match p {
        Some(p) => {
            let old = p.take();
            *p = json!({ "allOf": [old, extra] });
        }
        None => panic!("the schema has no property `{key}` in {def} {variant:?}"),
    }
}

fn add_rule(defs: &mut Map<String, Value>, def: &str, variant: Option<&str>, rule: Value) {
    let t = table(defs, def, variant)
        .unwrap_or_else(|| panic!("the schema has no table {def} {variant:?}"));
    match t.get_mut("allOf").and_then(Value::as_array_mut) {
        Some(all) => all.push(rule),
        None => {
            t.insert("allOf".into(), json!([rule]));
        }
    }
}

/// Every 3-vector's numbers within the largest magnitude a scene takes.
fn magnitudes(v: &mut Value) {
    match v {
        Value::Object(o) => {
            let vector = o.get("minItems") == Some(&json!(3))
                && o.get("maxItems") == Some(&json!(3))
                && o.get("items")
                    .is_some_and(|i| i.get("type") == Some(&json!("number")));
            if vector && let Some(items) = o.get_mut("items").and_then(Value::as_object_mut) {
                items.insert("minimum".into(), json!(-MAX));
                items.insert("maximum".into(), json!(MAX));
            }
            for x in o.values_mut() {
                magnitudes(x);
            }
        }
        Value::Array(a) => a.iter_mut().for_each(magnitudes),
        _ => {}
    }
}
