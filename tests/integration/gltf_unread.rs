//! What a glTF file holds and snell does not read (tests/data/gltf/unread.gltf, written by
//! its make.py): a warning for each, in `snell check` and `snell render`, naming the file
//! and the nodes, animations or materials; what glTF asks for and snell does not need (a
//! POSITION accessor's bounds) is not asked for; and `snell check`'s summary names each
//! glTF mesh by the nodes that place it and counts the images a file's materials read.

use super::gltf::{scene_text, scene_with};
use super::repo;
use snell::math::Vec3A;

/// What a file holds and snell does not read (tests/data/gltf/unread.gltf) is a warning
/// each, naming the file as the scene gives it and the nodes, animations or materials:
/// skins, morph targets, animations, every material extension a used material has that
/// snell leaves out, transmission that is neither 0 nor 1, and the other extensions the file
/// uses. Extensions snell reads, and a material no mesh uses, give none.
#[test]
fn what_is_not_read_is_warned_about_by_name() {
    let scene = scene_with("unread.gltf", "");
    let w = &scene.warnings;
    let has = |text: &str| {
        assert!(
            w.iter()
                .any(|w| w.starts_with("unread.gltf: ") && w.contains(text)),
            "no warning with {text:?} in {w:#?}"
        )
    };
    has("skins are not read (node `Body`)");
    has("bind pose");
    has("morph targets are not read (node `Face`)");
    has("not the blend of targets their weights ask for");
    has("animations are not read (animation `Wave`)");
    has("KHR_materials_clearcoat is not read (material `CarPaint`)");
    has("KHR_materials_pbrSpecularGlossiness is not read (material `OldSchool`)");
    has("KHR_materials_sheen is not read (material `Velvet`)");
    has("KHR_materials_specular is not read (material `Velvet`)");
    has("KHR_materials_volume is not read (material `Frost`)");
    has("KHR_materials_transmission is read as all or nothing (material `Frost`)");
    has("the file uses EXT_mesh_gpu_instancing, which snell does not read");
    assert!(
        !w.iter()
            .any(|w| w.contains("anisotropy") || w.contains("Unused")),
        "a material no mesh uses is not warned about: {w:#?}"
    );
    assert!(!w.iter().any(|w| w.contains("emissive_strength")), "{w:#?}");
    // Each what snell does not read once (a warning for each of the ten above).
    assert_eq!(w.len(), 10, "{w:#?}");
    // A file using only what snell reads (KHR_texture_transform,
    // KHR_materials_emissive_strength) warns about nothing.
    let scene = scene_with("pbr-maps.gltf", "");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

/// `snell check` and `snell render` print those warnings.
#[test]
fn check_and_render_print_what_is_not_read() {
    use super::cli::{expect, stderr, stdout};
    let dir = super::scratch("gltf-unread");
    let file = repo("tests/data/gltf/unread.gltf");
    let scene = dir.join("t.toml");
    std::fs::write(
        &scene,
        format!(
            "[image]\nwidth = 8\nheight = 8\nsamples = 1\n\
             [camera]\nposition = [0, 0, 6]\nlook_at = [0, 0, 0]\n\
             [[lights]]\ntype = \"point\"\nposition = [0, 4, 6]\n\
             [[objects]]\ntype = \"mesh\"\nfile = {:?}\n",
            file.to_string_lossy()
        ),
    )
    .unwrap();
    let scene = scene.to_string_lossy().into_owned();
    let want = format!(
        "warning: {}: skins are not read (node `Body`)",
        file.display()
    );
    let o = expect(&["check", &scene], &dir, 0);
    assert!(stdout(&o).contains(&want), "{}", stdout(&o));
    assert!(
        stdout(&o).contains("KHR_materials_clearcoat is not read (material `CarPaint`)"),
        "{}",
        stdout(&o)
    );
    let out = dir.join("out.png").to_string_lossy().into_owned();
    let o = expect(&["render", &scene, "-o", &out], &dir, 0);
    assert!(stderr(&o).contains(&want), "{}", stderr(&o));
}

/// A POSITION accessor without `min` and `max` (tests/data/gltf/no-bounds.gltf; glTF asks
/// for them, viewers read such files) is read: snell works out its own bounds.
#[test]
fn a_position_accessor_without_bounds_is_read() {
    let scene = scene_with("no-bounds.gltf", "");
    assert_eq!(scene.objects.len(), 2);
    let b = scene.objects[0].world_bounds.unwrap();
    assert!(
        (b.min - Vec3A::new(-1.0, -1.0, -4.0)).length() < 1e-5
            && (b.max - Vec3A::new(1.0, 1.0, -2.0)).length() < 1e-5,
        "{b:?}"
    );
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

/// `snell check`'s summary names each glTF mesh with the nodes that place it, and counts the
/// images a glTF file's materials read among the textures.
#[test]
fn the_summary_names_meshes_by_their_nodes_and_counts_a_files_images() {
    let scene = scene_text(
        "[camera]\nlook_at = [0, 0, -1]\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"two-cubes.gltf\"\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"pbr-maps.gltf\"\n",
    )
    .unwrap();
    let s = scene.summary();
    for line in [
        "textures:  5 (1 image of two-cubes.gltf, 4 images of pbr-maps.gltf)",
        "  two-cubes.gltf: mesh `Cube` (nodes `CubeA`, `CubeB`): 12 triangles, placed 2 times (24 triangles)",
        "  pbr-maps.gltf: mesh `Plain` (node `Plain`): 2 triangles, placed 1 time (2 triangles)",
        "  pbr-maps.gltf: mesh `Tangent` (node `Tangent`): 2 triangles, placed 1 time (2 triangles)",
    ] {
        assert!(s.lines().any(|l| l == line), "no line {line:?} in\n{s}");
    }
}
