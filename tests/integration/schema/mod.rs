//! The scene format's JSON Schema (`snell schema`) against the parser: every scene we ship
//! validates, a mistake fails at the place it was made, and the schema and the parser agree
//! on thousands of small edits of real scenes (an unknown key, a key removed, a value of
//! another type), so editors flag exactly what `snell check` would refuse before building.

mod edits;
mod every_key;
mod verdicts;

use super::repo;
use jsonschema::error::ValidationErrorKind;
use jsonschema::{ValidationError, Validator};
use serde_json::{Value, json};
use snell::scene::Format;
use snell::scene::format::SceneFile;
use std::path::{Path, PathBuf};
use std::sync::LazyLock;
use verdicts::within;

static SCHEMA: LazyLock<Validator> = LazyLock::new(|| {
    // Building the validator also checks the schema against the draft 7 meta-schema.
    jsonschema::draft7::new(&snell::scene::schema()).expect("the schema is valid draft 7")
});

/// The schema of the types alone, before the builder's ranges and rules between keys: what
/// the parser (serde) reads.
static TYPES: LazyLock<Validator> = LazyLock::new(|| {
    jsonschema::draft7::new(&snell::scene::schema_of_types()).expect("valid draft 7")
});

/// A scene file as the JSON value an editor validates (TOML through `toml::Value`).
fn scene_value(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap();
    if path.extension().is_some_and(|e| e == "json") {
        serde_json::from_str(&text).unwrap()
    } else {
        toml_value(&text)
    }
}

fn toml_value(text: &str) -> Value {
    serde_json::to_value(toml::from_str::<toml::Value>(text).unwrap()).unwrap()
}

/// What the parser (serde, before any check of values) says about a scene, read as a JSON
/// file is. (Not `from_value`: a `Value` lets a tag be a variant's index, `type = 0`.)
fn parses(scene: &Value) -> Result<(), String> {
    serde_json::from_str::<SceneFile>(&scene.to_string())
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// Where and why a scene fails the schema, as `(path, message)` with paths written as snell
/// writes them (`objects[0].radius`). Inside a `oneOf` of tagged tables (or the `anyOf` of
/// an optional table and null) it follows the one branch that fits, as editors do, so the
/// place is the key or value at fault rather than the whole table.
fn problems(scene: &Value) -> Vec<(String, String)> {
    problems_in(&SCHEMA, scene)
}

/// [`problems`] against the schema of the types alone.
fn type_problems(scene: &Value) -> Vec<(String, String)> {
    problems_in(&TYPES, scene)
}

fn problems_in(schema: &Validator, scene: &Value) -> Vec<(String, String)> {
    let mut out = vec![];
    for e in schema.iter_errors(scene) {
        explain(&e, &mut out);
    }
    out
}

fn explain(e: &ValidationError, out: &mut Vec<(String, String)>) {
    let at = e.instance_path().as_str();
    let branches = match e.kind() {
        ValidationErrorKind::OneOfNotValid { context } | ValidationErrorKind::AnyOf { context } => {
            Some(context)
        }
        _ => None,
    };
    if let Some(branches) = branches {
        // A branch for another `type` fails on the tag; one for another JSON type (null)
        // fails on the value's type, at the value itself.
        let tag = format!("{at}/type");
        let fits: Vec<_> = branches
            .iter()
            .filter(|errors| {
                !errors.iter().any(|b| {
                    let p = b.instance_path().as_str();
                    (matches!(b.kind(), ValidationErrorKind::Constant { .. }) && p == tag)
                        || (matches!(b.kind(), ValidationErrorKind::Type { .. }) && p == at)
                })
            })
            .collect();
        if let [only] = fits[..] {
            for b in only {
                explain(b, out);
            }
            return;
        }
        // No branch takes the tag: the tag is the mistake.
        if matches!(e.kind(), ValidationErrorKind::OneOfNotValid { .. })
            && branches.iter().all(|errors| {
                errors.iter().any(|b| {
                    matches!(b.kind(), ValidationErrorKind::Constant { .. })
                        && b.instance_path().as_str() == tag
                })
            })
        {
            out.push((
                doc_path(&tag),
                format!("unknown type {}", e.instance()["type"]),
            ));
            return;
        }
    }
    let path = doc_path(at);
    match e.kind() {
        ValidationErrorKind::AdditionalProperties { unexpected } => {
            for key in unexpected {
                let path = if path.is_empty() {
                    key.clone()
                } else {
                    format!("{path}.{key}")
                };
                out.push((path, e.to_string()));
            }
        }
        _ => out.push((path, e.to_string())),
    }
}

/// A JSON Pointer (`/objects/0/radius`) as snell writes the path (`objects[0].radius`).
fn doc_path(pointer: &str) -> String {
    let mut out = String::new();
    for seg in pointer.split('/').skip(1) {
        let seg = seg.replace("~1", "/").replace("~0", "~");
        if seg.parse::<usize>().is_ok() {
            out.push_str(&format!("[{seg}]"));
        } else {
            if !out.is_empty() {
                out.push('.');
            }
            out.push_str(&seg);
        }
    }
    out
}

/// Every scene we ship: under scenes/ (subfolders too) and tests/scenes/.
fn shipped_scenes() -> Vec<PathBuf> {
    fn walk(dir: &Path, files: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, files);
            } else if path.extension().is_some_and(|e| e == "toml" || e == "json") {
                files.push(path);
            }
        }
    }
    let mut files = vec![];
    walk(&repo("scenes"), &mut files);
    walk(&repo("tests/scenes"), &mut files);
    files.sort();
    files
}

#[test]
fn every_shipped_scene_validates_against_the_schema() {
    let files = shipped_scenes();
    // The 22 scenes shipped today: more may come, none may go.
    assert!(
        files.len() >= 22 && files.iter().any(|f| f.ends_with("small.json")),
        "{} scenes: {files:?}",
        files.len()
    );
    for path in &files {
        let scene = scene_value(path);
        assert_eq!(problems(&scene), vec![], "{}", path.display());
        assert_eq!(parses(&scene), Ok(()), "{}", path.display());
    }
}

/// A small valid scene, for the mistakes below.
const SCENE: &str = r#"
[image]
width = 64
height = 48
samples = 4
filter = { type = "mitchell" }
[camera]
position = [0, 1, 4]
look_at = [0, 0, 0]
[materials.red]
color = [0.8, 0.1, 0.1]
[textures.grid]
type = "checker"
mapping = { type = "planar", u = [1, 0, 0], v = [0, 0, 1] }
[materials.floor]
texture = "grid"
[[lights]]
type = "spot"
position = [0, 5, 0]
look_at = [0, 0, 0]
[[objects]]
type = "sphere"
radius = 1
material = "red"
transform = { scale = 2, translate = [0, 1, 0] }
[[objects]]
type = "plane"
material = "floor"
"#;

#[test]
fn the_test_scene_is_valid() {
    let scene = toml_value(SCENE);
    assert_eq!(problems(&scene), vec![]);
    assert_eq!(parses(&scene), Ok(()));
    snell::scene::load_str(SCENE, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap();
}

#[test]
fn a_typo_fails_the_schema_where_snell_check_points() {
    let cases = [
        // (replace this, with this, where the schema and snell say the mistake is)
        ("radius = 1", "radus = 1", "objects[0].radus"),
        ("[camera]", "[camra]\nfov = 30\n[camera]", "camra"),
        ("radius = 1", "radius = \"big\"", "objects[0].radius"),
        ("scale = 2", "scal = 2", "objects[0].transform.scal"),
        ("samples = 4", "samples = \"many\"", "image.samples"),
        ("samples = 4", "sample = 4", "image.sample"),
        (
            "color = [0.8, 0.1, 0.1]",
            "color = [0.8, 0.1]",
            "materials.red.color",
        ),
        (
            "color = [0.8, 0.1, 0.1]",
            "colour = 0.5",
            "materials.red.colour",
        ),
        (
            "u = [1, 0, 0]",
            "u = [1, 0, 0], w = 1",
            "textures.grid.mapping.w",
        ),
        (
            "look_at = [0, 0, 0]\n[[o",
            "look_at = [0, 0]\n[[o",
            "lights[0].look_at",
        ),
        (
            "type = \"mitchell\"",
            "type = \"mitchel\"",
            "image.filter.type",
        ),
        (
            "type = \"plane\"",
            "type = \"plane\"\nnormal = true",
            "objects[1].normal",
        ),
        ("type = \"sphere\"", "type = \"spere\"", "objects[0].type"),
        ("type = \"spot\"", "type = \"spotlight\"", "lights[0].type"),
        (
            "[camera]",
            "[fog]\nmode = \"liner\"\nend = 10\n[camera]",
            "fog.mode",
        ),
        (
            "[camera]",
            "[meshes.statue]\nfile = \"statue.obj\"\nsmoth = true\n[camera]",
            "meshes.statue.smoth",
        ),
        (
            "type = \"plane\"",
            "type = \"mesh\"\nfiles = \"statue.obj\"",
            "objects[1].files",
        ),
    ];
    for (from, to, place) in cases {
        assert!(SCENE.contains(from), "{from}");
        let text = SCENE.replacen(from, to, 1);
        // `radus` for `radius` is also a missing `radius`: a second problem, at the table.
        let found = problems(&toml_value(&text));
        assert!(
            found.iter().any(|(p, _)| p == place) && found.iter().all(|(p, _)| within(place, p)),
            "{to}: the schema should fail at {place} (or its table), not {found:?}"
        );
        let err = snell::scene::load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml)
            .err()
            .unwrap_or_else(|| panic!("{to}: snell accepted it"));
        let said = err.diagnostics[0].message();
        assert!(
            said.starts_with(&format!("{place}: ")),
            "{to}: snell says `{said}`, the schema {place}"
        );
    }
}

#[test]
fn a_mistake_in_a_json_scene_fails_at_its_place() {
    let mut scene: Value = scene_value(&repo("tests/scenes/small.json"));
    scene["objects"][0]["radus"] = json!(1);
    scene["image"]["width"] = json!("wide");
    // What a plain validator says: the value, and the object (a `oneOf` of object types).
    let mut raw: Vec<_> = SCHEMA
        .iter_errors(&scene)
        .map(|e| e.instance_path().as_str().to_string())
        .collect();
    raw.sort();
    assert_eq!(raw, ["/image/width", "/objects/0"]);
    // Following the sphere branch, as editors do: the key itself.
    let mut found: Vec<_> = problems(&scene).into_iter().map(|(p, _)| p).collect();
    found.sort();
    assert_eq!(found, ["image.width", "objects[0].radus"]);
}

#[test]
fn a_scene_may_name_its_schema() {
    let json = r#"{"$schema": "./snell.schema.json", "camera": {"look_at": [0, 0, -1]}}"#;
    let toml = "\"$schema\" = \"./snell.schema.json\"\n[camera]\nlook_at = [0, 0, -1]\n";
    for (text, format) in [(json, Format::Json), (toml, Format::Toml)] {
        snell::scene::load_str(text, Path::new("s"), Path::new("."), format).unwrap();
    }
    assert_eq!(problems(&serde_json::from_str(json).unwrap()), vec![]);
}
