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

/// A dispersive `ior`'s mistakes, each at the key: a glass name that names none (with the
/// nearest), a formula with the wrong number of coefficients, one whose index drops below 1
/// or meets a resonance in 360-830 nm, and an unknown formula.
#[test]
fn dispersive_indices_are_checked_at_their_key() {
    let glass = |ior: &str| {
        errors(&format!(
            "[camera]\nlook_at = [0, 0, -1]\n[materials.g]\ntype = \"dielectric\"\nior = {ior}\n"
        ))
    };
    let cases = [
        (
            "\"diamnd\"",
            "t.toml:5:7: materials.g.ior: no glass named `diamnd`",
            "did you mean `diamond`?",
        ),
        (
            "\"crystal\"",
            "no glass named `crystal`",
            "BK7, fused silica, SF11, diamond, water",
        ),
        (
            "{ cauchy = [1.5] }",
            "t.toml:5:7: materials.g.ior: a Cauchy index takes 2 coefficients",
            "[a, b] (in micrometres squared where they have units): 1 given",
        ),
        (
            "{ sellmeier = [1, 2, 3] }",
            "a Sellmeier index takes 6 coefficients",
            "[B1, B2, B3, C1, C2, C3] (in micrometres squared where they have units): 3 given",
        ),
        (
            "{ cauchy = [0.9, 0.01] }",
            "this index is 0.97",
            "at least 1 everywhere from 360 to 830 nm",
        ),
        (
            "{ sellmeier = [1, 0, 0, 0.25, 0, 0] }",
            "is not a real number (a resonance",
            "micrometres",
        ),
        (
            "{ abbe = [1.5, 60] }",
            "unknown formula `abbe`",
            "sellmeier",
        ),
    ];
    for (ior, message, help) in cases {
        let e = glass(ior);
        assert!(e.contains(message) && e.contains(help), "{ior}: {e}");
    }
    assert_eq!(cases.len(), 7);
    // Named glasses, formulas and numbers load; plastic takes a glass's index at 587.6 nm
    // without dispersing.
    let ok = |ior: &str, kind: &str| {
        load_str(
            &format!(
                "[camera]\nlook_at = [0, 0, -1]\n[materials.g]\ntype = \"{kind}\"\nior = {ior}\n"
            ),
            Path::new("t.toml"),
            Path::new("."),
            Format::Toml,
        )
        .unwrap_or_else(|e| panic!("{ior}: {e}"))
    };
    let s = ok("\"BK7\"", "dielectric");
    assert!(s.disperses() && (s.materials[0].ior - 1.5168).abs() < 1e-3);
    assert!(ok("{ sellmeier = [1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653] }", "phong").disperses());
    assert!(!ok("1.5", "dielectric").disperses());
    let p = ok("\"SF11\"", "plastic");
    assert!(!p.disperses() && (p.materials[0].ior - 1.7847).abs() < 1e-3);
}
