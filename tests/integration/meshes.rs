//! Meshes in scenes: a triangle mesh must render as the analytic shape it approximates
//! (opaque and glass), instances must share one copy, MTL materials must colour their faces,
//! and OBJ and PLY must give the same picture.

use super::scratch;
use snell::film::Image;
use snell::integrator::Whitted;
use snell::math::Color;
use snell::scene::{Format, Scene, load_str};
use std::path::Path;

/// A unit cube from (0,0,0) to (1,1,1) as 8 vertices and 6 quads (outward winding).
const CUBE_OBJ: &str = "# a unit cube\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 1 1 0\r\n\
v 0 0 1\r\nv 1 0 1\r\nv 0 1 1\r\nv 1 1 1\r\n\
f 1 3 4 2\r\nf 5 6 8 7\r\nf 1 2 6 5\r\nf 3 7 8 4\r\nf 1 5 7 3\r\nf 2 4 8 6\r\n";

/// The same cube as ASCII PLY, with an extra per-vertex property to skip.
const CUBE_PLY: &str = "ply\nformat ascii 1.0\ncomment exported by hand\nelement vertex 8\n\
property float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face 6\n\
property list uchar int vertex_indices\nend_header\n\
0 0 0 9\n1 0 0 9\n0 1 0 9\n1 1 0 9\n0 0 1 9\n1 0 1 9\n0 1 1 9\n1 1 1 9\n\
4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";

/// A scene around one object (`object` is its TOML body), lit, seen from a corner.
fn scene_with(dir: &Path, materials: &str, object: &str) -> Scene {
    let text = format!(
        "[image]\nwidth = 48\nheight = 40\nsamples = 1\nbackground = [0.2, 0.3, 0.4]\nmax_depth = 6\n\
         [camera]\nposition = [2.2, 1.7, 3.0]\nlook_at = [0.5, 0.4, 0.5]\nfov = 40\n\
         [world]\nambient = 0.2\n\
         [[lights]]\ntype = \"point\"\nposition = [3, 5, 4]\n\
         [textures.check]\ntype = \"checker\"\neven = 0.9\nodd = 0.1\nsize = 0.25\n\
         mapping = {{ type = \"planar\", origin = [0, 0, 0], u = [1, 0, 0], v = [0, 0, 1] }}\n\
         [materials.floor]\ntexture = \"check\"\n\
         {materials}\n\
         [[objects]]\ntype = \"plane\"\npoint = [0, -0.3, 0]\nmaterial = \"floor\"\n\
         [[objects]]\n{object}\n"
    );
    load_str(&text, &dir.join("t.toml"), dir, Format::Toml).unwrap_or_else(|e| panic!("{e}"))
}

fn render(scene: &Scene) -> Image {
    snell::render::render(scene, &Whitted, Some(2), &|_| {})
        .unwrap()
        .image
}

/// Largest channel difference, and the fraction of pixels differing by more than `tol`.
fn compare(a: &Image, b: &Image, tol: f32) -> (f32, f64) {
    let mut worst = 0.0f32;
    let mut off = 0;
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        let d = (*p - *q).abs().max_element();
        worst = worst.max(d);
        if d > tol {
            off += 1;
        }
    }
    (worst, off as f64 / a.pixels.len() as f64)
}

#[test]
fn a_mesh_cube_renders_like_the_box_shape_opaque_and_glass() {
    let dir = scratch("mesh-cube");
    std::fs::write(dir.join("cube.obj"), CUBE_OBJ).unwrap();
    for material in [
        "[materials.m]\ncolor = [0.8, 0.3, 0.2]\nspecular = 0.5\nshininess = 30",
        "[materials.m]\ncolor = 1\nambient = 0\ndiffuse = 0\nspecular = 1\ntransparency = 1\n\
         ior = 1.5\nabsorption = [0.5, 0.2, 0.1]",
    ] {
        let box_scene = scene_with(
            &dir,
            material,
            "type = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nmaterial = \"m\"",
        );
        let mesh_scene = scene_with(
            &dir,
            material,
            "type = \"mesh\"\nfile = \"cube.obj\"\nmaterial = \"m\"",
        );
        let (a, b) = (render(&box_scene), render(&mesh_scene));
        // The cube fills the middle of the picture: neither floor nor sky there.
        let centre = a.pixels[(20 * 48 + 24) as usize];
        assert!(
            (centre - Color::new(0.2, 0.3, 0.4)).abs().max_element() > 0.05,
            "the cube is in view: {centre}"
        );
        let (worst, off) = compare(&a, &b, 1e-3);
        // Only a pixel whose ray grazes an edge may tell a box from its triangles.
        assert!(
            off < 0.01,
            "{:.1} % of pixels differ (worst {worst}) for {material}",
            off * 100.0
        );
    }
}

#[test]
fn instances_share_one_mesh_in_memory() {
    let dir = scratch("mesh-instances");
    std::fs::write(dir.join("cube.obj"), CUBE_OBJ).unwrap();
    let mut objects = String::from("type = \"mesh\"\nmesh = \"cube\"\nmaterial = \"m\"\n");
    for i in 1..4 {
        objects.push_str(&format!(
            "[[objects]]\ntype = \"mesh\"\nmesh = \"cube\"\nmaterial = \"m\"\n\
             transform = {{ translate = [{i}.5, 0, 0], rotate = [0, {}, 0] }}\n",
            i * 30
        ));
    }
    // The same file placed directly shares the same copy too.
    objects.push_str("[[objects]]\ntype = \"mesh\"\nfile = \"cube.obj\"\nmaterial = \"m\"\n");
    let scene = scene_with(
        &dir,
        "[materials.m]\ncolor = 0.7\n[meshes.cube]\nfile = \"cube.obj\"",
        &objects,
    );
    let s = &scene.stats;
    assert_eq!(s.meshes, 1, "one mesh in memory");
    assert_eq!(s.unique_triangles, 12);
    assert_eq!(s.instanced_triangles, 5 * 12);
    assert_eq!(s.objects, 6, "five cubes and the floor");
}

#[test]
fn mtl_materials_colour_their_own_faces() {
    let dir = scratch("mesh-mtl");
    // Two triangles side by side facing +z, one red and one green, from the MTL file.
    std::fs::write(
        dir.join("two.mtl"),
        "newmtl red\nKd 1 0 0\nillum 1\n\nnewmtl green\nKd 0 1 0\nillum 1\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("two.obj"),
        "mtllib two.mtl\nv -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 1 -1 0\nv 1 1 0\n\
         usemtl red\nf 1 2 3 4\nusemtl green\nf 2 5 6 3\n",
    )
    .unwrap();
    let text = "[image]\nwidth = 20\nheight = 10\n\
        [camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov = 60\n\
        [[lights]]\ntype = \"directional\"\ndirection = [0, 0, -1]\n\
        [[objects]]\ntype = \"mesh\"\nfile = \"two.obj\"\n";
    let scene = load_str(text, &dir.join("t.toml"), &dir, Format::Toml).unwrap();
    let img = render(&scene);
    let left = img.pixels[(5 * 20 + 7) as usize];
    let right = img.pixels[(5 * 20 + 12) as usize];
    assert!(left.x > 0.5 && left.y < 0.05, "left half is red: {left}");
    assert!(
        right.y > 0.5 && right.x < 0.05,
        "right half is green: {right}"
    );
}

#[test]
fn obj_and_ply_give_the_same_picture() {
    let dir = scratch("mesh-ply");
    std::fs::write(dir.join("cube.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.join("cube.ply"), CUBE_PLY).unwrap();
    let m = "[materials.m]\ncolor = [0.3, 0.5, 0.9]\nspecular = 0.4\nshininess = 20";
    let obj = scene_with(
        &dir,
        m,
        "type = \"mesh\"\nfile = \"cube.obj\"\nmaterial = \"m\"",
    );
    let ply = scene_with(
        &dir,
        m,
        "type = \"mesh\"\nfile = \"cube.ply\"\nmaterial = \"m\"",
    );
    assert!(render(&obj) == render(&ply));
}

/// 3ds Max (and the pymeshlab bunny's MTL) write `Ks 0.9` with `Ns 0`. Read as a Phong
/// exponent of 0, that is a highlight of 0.9 over the whole lit side; read as Blender's
/// importer reads it, `Ns 0` is fully rough and shows no highlight.
#[test]
fn mtl_ns_0_is_fully_rough_not_a_sheen_over_everything() {
    let dir = scratch("mesh-ns");
    let picture = |material: &str| {
        std::fs::write(
            dir.join("q.mtl"),
            format!("newmtl m\nKd 0.5 0.5 0.5\n{material}"),
        )
        .unwrap();
        std::fs::write(
            dir.join("q.obj"),
            "mtllib q.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl m\nf 1 2 3 4\n",
        )
        .unwrap();
        let text = "[image]\nwidth = 16\nheight = 16\n\
            [camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov = 30\n\
            [[lights]]\ntype = \"directional\"\ndirection = [0, 0, -1]\n\
            [[objects]]\ntype = \"mesh\"\nfile = \"q.obj\"\n";
        render(&load_str(text, &dir.join("t.toml"), &dir, Format::Toml).unwrap())
    };
    let matte = picture("Ks 0 0 0\nillum 2\n");
    assert!(matte == picture("Ks 0.9 0.9 0.9\nNs 0\nillum 2\n"));
    // A polished one (Ns 1000) does show its highlight where the light mirrors into the eye.
    let shiny = picture("Ks 0.9 0.9 0.9\nNs 1000\nillum 2\n");
    let centre = (8 * 16 + 8) as usize;
    assert!(
        shiny.pixels[centre].x > matte.pixels[centre].x + 0.5,
        "{} against {}",
        shiny.pixels[centre],
        matte.pixels[centre]
    );
}

/// MTL materials become the path tracer's types where the file says enough: `Pm` a metal
/// tinted by `Kd`, `illum 7` with `d` below 1 glass of index `Ni`, `illum 4` a thin pane,
/// `illum 5` or `Pr` a coated plastic, `Ke` emission; others stay Phong.
#[test]
fn mtl_materials_map_onto_the_physically_based_types() {
    use snell::material::Surface;
    let dir = scratch("mesh-mtl-types");
    std::fs::write(
        dir.join("kinds.mtl"),
        "newmtl gold\nKd 1 0.8 0.3\nPm 1\nPr 0.5\n\
         newmtl glass\nNi 1.33\nd 0.1\nillum 7\n\
         newmtl pane\nd 0.2\nillum 4\n\
         newmtl coat\nKd 0.2 0.3 0.8\nillum 5\nNs 1000\n\
         newmtl rough\nKd 0.5 0.5 0.5\nPr 0.3\n\
         newmtl lamp\nKd 1 1 1\nKe 4 4 2\n",
    )
    .unwrap();
    let mut obj = String::from("mtllib kinds.mtl\n");
    for (k, name) in ["gold", "glass", "pane", "coat", "rough", "lamp"]
        .iter()
        .enumerate()
    {
        let x = k as f32 * 2.0;
        obj += &format!(
            "v {x} 0 0\nv {} 0 0\nv {x} 1 0\nusemtl {name}\nf -3 -2 -1\n",
            x + 1.0
        );
    }
    std::fs::write(dir.join("kinds.obj"), obj).unwrap();
    let text = "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\n\
        [[objects]]\ntype = \"mesh\"\nfile = \"kinds.obj\"\n";
    let scene = load_str(text, &dir.join("t.toml"), &dir, Format::Toml).unwrap();
    let m = |name: &str| {
        let i = scene
            .material_names
            .iter()
            .position(|n| n == &format!("kinds.obj:{name}"))
            .unwrap_or_else(|| panic!("{name} in {:?}", scene.material_names));
        &scene.materials[i]
    };
    match m("gold").surface {
        Surface::Conductor(c) => {
            assert_eq!(c.roughness, snell::material::Scalar::Value(0.25), "Pr²")
        }
        other => panic!("gold: {other:?}"),
    }
    assert!(matches!(m("glass").surface, Surface::Dielectric(_)));
    assert_eq!(m("glass").ior, 1.33);
    assert_eq!(m("glass").terms.transparency, 1.0);
    assert!(matches!(m("pane").surface, Surface::Thin(_)));
    assert!(matches!(m("coat").surface, Surface::Plastic(_)));
    assert!(matches!(m("rough").surface, Surface::Plastic(_)));
    let lamp = m("lamp");
    assert_eq!(lamp.surface, Surface::Phong);
    assert_eq!(
        lamp.emission.map(|e| (e.radiance, e.two_sided)),
        Some((
            snell::material::ColorParam::Value(Color::new(4.0, 4.0, 2.0)),
            false
        ))
    );
    // The lamp's triangle is a light the path tracer samples.
    assert_eq!(scene.area_lights().count(), 1);
}
