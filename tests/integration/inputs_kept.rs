//! A render never writes over a file it reads: an output (the picture, its partial picture,
//! a view, a checkpoint, a merge's result) that names the scene file, a texture, a mesh or
//! the environment map, however it is spelt, is refused with exit 2 before any work, and
//! the file is left as it was.

use super::cli::{expect, stderr};
use super::{repo, scratch};
use std::path::Path;

/// A scene in `dir` reading `tex.png` (a texture), `env.hdr` (the environment) and
/// `mesh.obj`.
fn scene_reading_files(dir: &Path) -> String {
    std::fs::copy(repo("assets/maps/tiles-height.png"), dir.join("tex.png")).unwrap();
    std::fs::copy(repo("assets/env/studio.hdr"), dir.join("env.hdr")).unwrap();
    std::fs::write(dir.join("mesh.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let scene = "[image]\nwidth = 8\nheight = 6\n[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\n\
                 [environment]\ntype = \"image\"\nfile = \"env.hdr\"\n\
                 [textures.t]\ntype = \"image\"\nfile = \"tex.png\"\n\
                 [materials.m]\ntexture = \"t\"\n\
                 [meshes.tri]\nfile = \"mesh.obj\"\n\
                 [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n\
                 [[objects]]\ntype = \"mesh\"\nmesh = \"tri\"\nmaterial = \"m\"\n";
    std::fs::write(dir.join("s.toml"), scene).unwrap();
    "s.toml".into()
}

#[test]
fn an_output_that_names_an_input_is_refused_and_the_input_kept() {
    let dir = scratch("inputs-kept");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let scene = scene_reading_files(&dir);
    let before: Vec<Vec<u8>> = ["tex.png", "env.hdr", "mesh.obj", "s.toml"]
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect();
    // Each way of naming an input as an output.
    let cases: [&[&str]; 9] = [
        &["-o", "tex.png"],
        &["-o", "./tex.png"],
        &["-o", "sub/../tex.png"],
        &["-o", "env.hdr"],
        &["-o", "mesh.obj"],
        &["-o", "s.toml"],
        &["-o", "tex.png", "--aov", "normal"],
        &["-o", "out.png", "--checkpoint", "tex.png"],
        &["-o", "tex.png", "--integrator", "path", "--time", "1s"],
    ];
    let mut refused = 0;
    for extra in cases {
        let mut args = vec!["render", scene.as_str()];
        args.extend_from_slice(extra);
        let o = expect(&args, &dir, 2);
        let err = stderr(&o);
        assert!(
            err.contains("which this render reads") && err.contains("name another output"),
            "{extra:?}: {err}"
        );
        refused += 1;
    }
    assert_eq!(refused, 9);
    // From another folder, with the scene named through it.
    let o = expect(
        &["render", "../s.toml", "-o", "../tex.png"],
        &dir.join("sub"),
        2,
    );
    assert!(stderr(&o).contains("tex.png"), "{}", stderr(&o));
    // A view's own PNG (x.normal.png beside x.png) that is the scene's texture.
    std::fs::copy(dir.join("tex.png"), dir.join("x.normal.png")).unwrap();
    let text = std::fs::read_to_string(dir.join(&scene)).unwrap();
    std::fs::write(dir.join("v.toml"), text.replace("tex.png", "x.normal.png")).unwrap();
    let o = expect(
        &["render", "v.toml", "-o", "x.png", "--aov", "normal"],
        &dir,
        2,
    );
    assert!(stderr(&o).contains("x.normal.png"), "{}", stderr(&o));
    assert!(!dir.join("x.png").exists());
    let after: Vec<Vec<u8>> = ["tex.png", "env.hdr", "mesh.obj", "s.toml"]
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect();
    assert!(before == after, "an input changed");
    assert!(!dir.join("out.png").exists(), "nothing was rendered");
    // Elsewhere, the same render is fine.
    expect(&["render", &scene, "-o", "out.png"], &dir, 0);
}

#[test]
fn merge_refuses_to_write_over_a_region_file() {
    let dir = scratch("merge-kept");
    std::fs::write(dir.join("a.exr"), b"not really an exr").unwrap();
    let o = expect(&["merge", "a.exr", "-o", "./a.exr"], &dir, 2);
    assert!(stderr(&o).contains("is the region file"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(dir.join("a.exr")).unwrap(),
        b"not really an exr"
    );
}
