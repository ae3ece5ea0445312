//! `snell check`: the summary of a scene (meshes and their triangles, the environment, area
//! lights) and its warnings.

use super::*;

#[test]
fn check_counts_each_meshs_triangles_loaded_and_placed() {
    let dir = scratch("check-meshes");
    let field = repo("scenes/field.toml").to_string_lossy().into_owned();
    let out = stdout(&expect(&["check", &field], &dir, 0));
    assert!(
        out.contains("meshes:    2 (75771 triangles loaded, 1212336 placed)")
            && out.contains(
                "stanford-bunny.obj: 69451 triangles, placed 16 times (1111216 triangles)"
            )
            && out.contains("teapot.obj: 6320 triangles, placed 16 times (101120 triangles)"),
        "{out}"
    );
    // A scene without meshes says nothing of them.
    let scene = write_scene(&dir, "s.toml", GOOD);
    assert!(!stdout(&expect(&["check", &scene], &dir, 0)).contains("meshes:"));
}

/// `check` names the environment a scene is lit by (its image, colour or sun) and the share
/// of light samples it gets, and counts emitting objects among the lights.
#[test]
fn check_names_the_environment_and_the_area_lights() {
    let dir = scratch("check-env");
    let hdr = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/env/studio.hdr");
    let only_env = GOOD.replace(
        "[[lights]]\ntype = \"point\"\nposition = [0, 5, 0]\n",
        &format!(
            "[environment]\ntype = \"image\"\nfile = {:?}\n",
            hdr.display().to_string()
        ),
    );
    let out = stdout(&expect(
        &["check", &write_scene(&dir, "e.toml", &only_env)],
        &dir,
        0,
    ));
    assert!(out.contains("lights:    none\n"), "{out}");
    assert!(
        out.contains(&format!(
            "environment: image {}, 512 x 256; 100 % of light samples",
            hdr.display()
        )),
        "{out}"
    );
    let mixed = GOOD.to_string()
        + "[environment]\ntype = \"constant\"\ncolor = 0.5\n\
           [materials.lamp]\ncolor = 0\nemission = 4\n\
           [[objects]]\ntype = \"sphere\"\ncenter = [0, 3, -3]\nradius = 0.5\nmaterial = \"lamp\"\n";
    let out = stdout(&expect(
        &["check", &write_scene(&dir, "m.toml", &mixed)],
        &dir,
        0,
    ));
    assert!(out.contains("lights:    2 (1 area, 1 point)\n"), "{out}");
    assert!(
        out.contains("environment: constant [0.5, 0.5, 0.5]; "),
        "{out}"
    );
    let sky = GOOD.to_string() + "[environment]\ntype = \"sky\"\nsun_elevation = 30\n";
    let out = stdout(&expect(
        &["check", &write_scene(&dir, "s.toml", &sky)],
        &dir,
        0,
    ));
    assert!(
        out.contains("environment: sky, the sun 30.0° above the horizon; "),
        "{out}"
    );
}

#[test]
fn check_prints_a_summary_and_warnings() {
    let dir = scratch("check");
    let inside = GOOD.replace("position = [0, 5, 0]", "position = [0, 0, -3]")
        + "[materials.unused]\ncolor = 0.5\n";
    let scene = write_scene(&dir, "w.toml", &inside);
    let o = expect(&["check", &scene], &dir, 0);
    let out = stdout(&o);
    assert!(
        out.contains("objects:   1 (1 sphere)") && out.contains("lights:    1 (1 point)"),
        "{out}"
    );
    assert!(
        out.contains("warning: light 0") && out.contains("inside object `sphere #0`"),
        "{out}"
    );
    assert!(
        out.contains("warning: material `unused` is defined but no object uses it"),
        "{out}"
    );
    let seed = repo("scenes/seed.toml");
    let out = stdout(&expect(&["check", seed.to_str().unwrap()], &dir, 0));
    assert!(
        out.contains("objects:   8") && out.contains("textures:  2 (checkerboard, earth)"),
        "{out}"
    );
}
