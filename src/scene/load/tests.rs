//! Loading's messages: where a problem is located and what it suggests, for TOML and JSON.

use super::*;

fn errors(text: &str) -> String {
    match load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

const CAMERA: &str = "[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n";

#[test]
fn unknown_key_points_at_the_key_with_a_suggestion() {
    let e = errors(&format!(
        "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"m\"\nradus = 2\n"
    ));
    assert!(
        e.contains("t.toml:8:1: objects[0].radus: unknown key `radus`"),
        "{e}"
    );
    assert!(e.contains("did you mean `radius`?"), "{e}");
}

#[test]
fn impossible_values_are_all_reported() {
    let e = errors(&format!(
        "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"m\"\nradius = -1\n[[objects]]\ntype = \"cylinder\"\nmaterial = \"m\"\naxis = [0, 0, 0]\nradius = 1\nheight = 2\n"
    ));
    assert!(
        e.contains("t.toml:8:10: objects[0].radius: must be greater than 0, not -1"),
        "{e}"
    );
    assert!(
        e.contains("t.toml:12:8: objects[1].axis: must not be the zero vector"),
        "{e}"
    );
}

#[test]
fn missing_material_suggests_a_name() {
    let e = errors(&format!(
        "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"n\"\nradius = 1\n"
    ));
    assert!(
        e.contains("no material named `n`") && e.contains("did you mean `m`?"),
        "{e}"
    );
}

#[test]
fn wrong_type_and_unknown_shape() {
    let e = errors(&format!(
        "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"m\"\nradius = \"big\"\n"
    ));
    assert!(
        e.contains("t.toml:8:10") && e.contains("expected a number"),
        "{e}"
    );
    let e = errors(&format!(
        "{CAMERA}[[objects]]\ntype = \"spere\"\nmaterial = \"m\"\n"
    ));
    assert!(
        e.contains("unknown type `spere`") && e.contains("did you mean `sphere`?"),
        "{e}"
    );
}

#[test]
fn fov_out_of_range_and_toml_syntax() {
    let e = errors("[camera]\nlook_at = [0, 0, -1]\nfov = 180\n");
    assert!(
        e.contains("t.toml:3:7: camera.fov: field of view must be between 0 and 180"),
        "{e}"
    );
    let e = errors("[camera]\nlook_at = [0, 0, -1\n");
    assert!(e.contains("t.toml:2:") && e.contains("TOML syntax"), "{e}");
}

#[test]
fn json_uses_the_same_types_and_locates_errors() {
    let json = "{\n  \"camera\": {\"look_at\": [0, 0, -1]},\n  \"materials\": {\"m\": {\"color\": 1}},\n  \"objects\": [{\"type\": \"sphere\", \"material\": \"m\", \"radius\": 0}]\n}\n";
    let e = load_str(json, Path::new("t.json"), Path::new("."), Format::Json)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("t.json:4:") && e.contains("objects[0].radius: must be greater than 0"),
        "{e}"
    );
    let ok = json.replace("\"radius\": 0", "\"radius\": 2");
    let s = load_str(&ok, Path::new("t.json"), Path::new("."), Format::Json).unwrap();
    assert_eq!(s.objects.len(), 1);
    let e = load_str(
        "{\"camera\": {\"look_at\": [0,0,-1]}, }",
        Path::new("t.json"),
        Path::new("."),
        Format::Json,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("t.json:1:") && e.contains("JSON syntax"), "{e}");
}

/// docs/scene-format.md names the keys where JSON's `null` means "not given" and those
/// (with a default) where it is refused; this holds the parser to that list.
#[test]
fn json_null_is_taken_for_keys_without_a_default_only() {
    let scene = |camera: &str, object: &str| {
        format!(
            "{{\"$schema\": null, \"image\": {{\"width\": 8, \"height\": 6, \"filter\": {{\"type\": \"box\", \"radius\": null}}}}, \"camera\": {{\"look_at\": [0,0,-1]{camera}}}, \"fog\": null, \"materials\": {{\"m\": {{\"color\": null, \"texture\": null}}}}, \"objects\": [{{\"type\": \"sphere\", \"center\": [0,0,-3], \"radius\": 1, \"material\": \"m\", \"name\": null, \"transform\": null{object}}}]}}"
        )
    };
    let load = |text: &str| load_str(text, Path::new("t.json"), Path::new("."), Format::Json);
    assert!(load(&scene("", "")).is_ok());
    let fog = scene("", "").replace(
        "\"fog\": null",
        "\"fog\": {\"mode\": \"exponential\", \"end\": null, \"density\": 0.1}",
    );
    assert!(load(&fog).is_ok(), "{:?}", load(&fog).err());
    for (camera, object, key) in [
        (", \"up\": null", "", "camera.up"),
        (", \"aperture\": null", "", "camera.aperture"),
        (", \"position\": null", "", "camera.position"),
    ] {
        let e = load(&scene(camera, object)).unwrap_err().to_string();
        assert!(
            e.contains(&format!("{key}: invalid type: null")),
            "{key}: {e}"
        );
    }
}
