//! The whole schema (with the loader's ranges and rules) against `snell check`'s verdict and
//! place, on every broken and every shipped scene, and the scenes no schema can judge.

use super::*;

/// The broken scenes of tests/bad/ that the schema takes, each with why no JSON Schema can
/// refuse it: `snell check` finds the fault only by reading a file the scene names, by
/// looking up a name, by comparing values with one another, or by working something out.
pub(super) const BEYOND_THE_SCHEMA: [(&str, &str); 65] = [
    (
        "102-sky-sun-two-ways.toml",
        "the sun's place given by an elevation beside an hour of a partial date",
    ),
    (
        "104-sky-sun-at-night.toml",
        "the sun's elevation worked out from the date",
    ),
    (
        "106-sky-sun-direction-below.toml",
        "a direction below the horizon",
    ),
    ("108-gltf-bad-accessor.toml", "the glTF file"),
    ("109-gltf-bad-index.toml", "the glTF file"),
    ("110-gltf-missing-buffer.toml", "the glTF file"),
    ("111-gltf-needs-draco.toml", "the glTF file"),
    ("112-gltf-not-json.toml", "the glTF file"),
    (
        "115-csg-open-cylinder.toml",
        "a shape of a combination that is not closed",
    ),
    (
        "116-csg-plane.toml",
        "a shape of a combination that is not a solid",
    ),
    ("117-csg-unknown-material.toml", "a name"),
    ("120-gltf-position-past-the-accessors.toml", "the glTF file"),
    ("121-gltf-glb-length-under-its-header.toml", "the glTF file"),
    (
        "122-gltf-uv-accessor-of-the-wrong-type.toml",
        "the glTF file",
    ),
    ("125-bump-unknown-texture.toml", "a name"),
    ("126-bump-height-nan.toml", "NaN, which JSON cannot write"),
    (
        "127-lights-on-obj.toml",
        "the mesh file's kind, by its name",
    ),
    ("130-gltf-camera-type.toml", "the glTF file"),
    ("131-gltf-accessor-of-no-elements.toml", "the glTF file"),
    ("132-animation-keys-unsorted.toml", "the order of keys"),
    (
        "133-animation-key-out-of-range.toml",
        "a key's frame against the animation's length",
    ),
    ("134-animation-unknown-object.toml", "a name"),
    (
        "136-animation-directional-position.toml",
        "the kind of the light a key names",
    ),
    ("139-csg-open-mesh.toml", "the mesh file"),
    ("140-group-unknown.toml", "a name"),
    ("141-group-in-group.toml", "a group inside a group"),
    (
        "142-group-member-without-material.toml",
        "a member's material against its mesh file's",
    ),
    (
        "143-gltf-second-uv-accessor-of-the-wrong-type.toml",
        "the glTF file",
    ),
    ("24-camera-looks-at-itself.toml", "two points compared"),
    ("25-camera-up-parallel.toml", "two directions compared"),
    (
        "29-non-square-samples.toml",
        "a square number, for the integrator the scene chooses",
    ),
    ("32-zero-length-axis.toml", "a vector's length"),
    ("34-inverted-box.toml", "two points compared"),
    ("35-flat-rectangle.toml", "two edges compared"),
    ("36-degenerate-triangle.toml", "three corners compared"),
    ("37-zero-normal-plane.toml", "a vector's length"),
    ("38-zero-scale.toml", "a scale's components"),
    ("39-missing-material.toml", "a name"),
    ("40-missing-texture-name.toml", "a name"),
    ("45-missing-texture-file.toml", "the texture file"),
    ("46-texture-not-an-image.toml", "the texture file"),
    ("50-fog-end-before-start.toml", "two values compared"),
    ("52-planar-mapping-parallel-axes.toml", "two axes compared"),
    ("63-too-many-pixels.toml", "width times height"),
    ("66-mesh-missing-file.toml", "the mesh file"),
    ("67-mesh-bad-index.toml", "the mesh file"),
    ("68-mesh-nan-vertex.toml", "the mesh file"),
    ("69-mesh-truncated-ply.toml", "the mesh file"),
    ("70-mesh-no-material.toml", "the mesh file's materials"),
    ("72-mesh-unknown-name.toml", "a name"),
    ("75-mesh-unknown-format.toml", "the mesh file"),
    ("76-mesh-all-degenerate.toml", "the mesh file"),
    ("77-mesh-mtl-not-found.toml", "the mesh file's MTL file"),
    ("77-mesh-ply-bad-header.toml", "the mesh file"),
    ("78-mesh-huge-vertex.toml", "the mesh file"),
    ("79-mesh-short-face.toml", "the mesh file"),
    ("80-mesh-missing-map-kd.toml", "the mesh file's texture"),
    ("85-mesh-path-is-a-folder.toml", "the mesh file"),
    ("86-unicode-texture-missing.toml", "the texture file"),
    ("87-unicode-mesh-bad-index.toml", "the mesh file"),
    ("88-texture-not-an-image.toml", "the texture file"),
    ("89-texture-truncated-png.toml", "the texture file"),
    ("90-texture-decoder-panics.toml", "the texture file"),
    ("91-texture-is-a-device.toml", "the texture file"),
    ("92-environment-missing-file.toml", "the environment's file"),
];

/// The schema and `snell check` agree on every broken scene of tests/bad/ and every shipped
/// scene: each refused by one is refused by the other, at the same place, but for the
/// scenes whose fault no JSON Schema can see ([`BEYOND_THE_SCHEMA`], a list that must stay
/// exact: a scene the schema learns to refuse is taken off it).
#[test]
fn the_schema_and_check_agree_on_every_bad_and_shipped_scene() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo("tests/bad"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let shipped = shipped_scenes();
    files.extend(shipped.iter().cloned());
    let (mut compared, mut beyond, mut failures) = (0, vec![], vec![]);
    for path in &files {
        let format = match path.extension().and_then(|e| e.to_str()) {
            Some("toml") => Format::Toml,
            Some("json") => Format::Json,
            _ => continue,
        };
        let text = std::fs::read_to_string(path).unwrap();
        // Syntax errors are the editor's own business, before any schema.
        let scene: Value = match format {
            Format::Toml => match toml::from_str::<toml::Value>(&text) {
                Ok(v) => serde_json::to_value(v).unwrap(),
                Err(_) => continue,
            },
            Format::Json => match serde_json::from_str(&text) {
                Ok(v) => v,
                Err(_) => continue,
            },
        };
        compared += 1;
        let found = problems(&scene);
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let checked = snell::scene::load_str(&text, path, path.parent().unwrap(), format);
        match checked {
            Ok(_) if found.is_empty() => {}
            Ok(_) => failures.push(format!("{name}: check takes it, the schema {found:?}")),
            Err(_) if found.is_empty() => {
                if BEYOND_THE_SCHEMA.iter().any(|(f, _)| *f == name) {
                    beyond.push(name);
                } else {
                    failures.push(format!("{name}: the schema takes it, check refuses it"));
                }
            }
            Err(err) => {
                // Some problem snell names is one the schema names: snell writes `path:
                // message`, or just the message at the top level; where it cannot tell which
                // value a message means it names the table, and a value TOML cannot give
                // JSON (inf) is refused deeper by the schema.
                let places: Vec<&str> = err.diagnostics.iter().map(|d| d.message()).collect();
                let agree = places.iter().any(|said| {
                    let at = said.split_once(": ").map_or("", |(p, _)| p);
                    let at = if at.contains([' ', '`']) { "" } else { at };
                    found.iter().any(|(p, _)| within(p, at) || within(at, p))
                });
                if !agree {
                    failures.push(format!(
                        "{name}: snell says {places:?}, the schema {found:?}"
                    ));
                }
            }
        }
    }
    for (f, why) in BEYOND_THE_SCHEMA {
        if !beyond.iter().any(|b| b == f) {
            failures.push(format!(
                "{f} is listed as beyond the schema ({why}), but the schema refuses it or check takes it: take it off the list"
            ));
        }
    }
    // tests/bad's 147 files but the six syntax errors (01 to 04, 55 and 59), and the
    // shipped scenes.
    assert!(
        compared >= 141 + shipped.len(),
        "only {compared} scenes compared"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(beyond.len(), BEYOND_THE_SCHEMA.len());
}

/// Whether `inner` is `outer` or a key or index somewhere below it.
pub(super) fn within(inner: &str, outer: &str) -> bool {
    inner == outer
        || (!outer.is_empty()
            && inner
                .strip_prefix(outer)
                .is_some_and(|rest| rest.starts_with(['.', '['])))
}

/// docs/scene-format.md owns up to this one: JSON Schema's `integer` takes `800.0`, serde's
/// `u32` does not. If this ever fails, the schema got stricter: update the page.
#[test]
fn a_whole_number_written_with_a_point_passes_the_schema_but_not_snell() {
    let scene = json!({ "image": { "width": 800.0 }, "camera": { "look_at": [0, 0, -1] } });
    assert_eq!(problems(&scene), vec![]);
    assert!(parses(&scene).is_err());
}

/// The schema says what `snell check` says of a camera with nothing in it (it was taken).
#[test]
fn a_camera_without_a_view_fails_the_schema_as_it_fails_check() {
    let scene = json!({ "camera": {} });
    assert!(!problems(&scene).is_empty());
    assert!(problems(&json!({ "camera": { "look_at": [0, 0, -1] } })).is_empty());
    let err = snell::scene::load_str(
        &scene.to_string(),
        Path::new("c.json"),
        Path::new("."),
        Format::Json,
    )
    .unwrap_err();
    assert!(err.diagnostics[0].message().contains("look_at"));
}
