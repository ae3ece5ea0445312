//! glTF files placed by a scene (tests/data/gltf, written by its make.py as Blender's
//! exporter lays files out): each node that shows a mesh becomes an object, the mesh stored
//! once; the node hierarchy's transforms place them; materials and their base-colour images
//! come through with glTF's texture orientation; a .glb is the same scene as the .gltf; a
//! scene's transform applies after the file's (what a file holds and snell does not read:
//! gltf_unread.rs).

use super::repo;
use snell::math::{Color, Ray, Vec3A};
use snell::render::render;
use snell::scene::{Format, Scene, Skip, load_str};
use std::sync::Arc;

pub(super) fn scene_with(file: &str, extra: &str) -> Scene {
    let dir = repo("tests/data/gltf");
    let text = format!(
        "[image]\nwidth = 24\nheight = 16\nsamples = 1\n\
         [camera]\nposition = [0, 0, 6]\nlook_at = [0, 0, -3]\n\
         [[lights]]\ntype = \"point\"\nposition = [0, 4, 6]\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"{file}\"\n{extra}\n"
    );
    load_str(&text, &dir.join("t.toml"), &dir, Format::Toml).unwrap_or_else(|e| panic!("{e}"))
}

fn hit(scene: &Scene, from: [f32; 3], dir: [f32; 3]) -> snell::scene::Hit {
    let ray = Ray::new(Vec3A::from(from), Vec3A::from(dir).normalize());
    scene
        .closest_hit_with_uv(&ray, f32::INFINITY, Skip::NONE)
        .expect("a hit")
}

#[test]
fn each_node_places_the_one_mesh_where_the_hierarchy_says() {
    let scene = scene_with("two-cubes.gltf", "");
    assert_eq!(scene.objects.len(), 2);
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["mesh #0/CubeA", "mesh #0/CubeB"]);
    match (&scene.objects[0].shape, &scene.objects[1].shape) {
        (snell::geometry::Shape::Mesh(a), snell::geometry::Shape::Mesh(b)) => {
            assert!(Arc::ptr_eq(a, b), "the mesh is stored once")
        }
        _ => panic!("not meshes"),
    }
    // CubeA: the cube (side 2) at the parent's z = -3; CubeB: 2 along x, half the size.
    let bounds = |i: usize| {
        let b = scene.objects[i].world_bounds.unwrap();
        (b.min.to_array(), b.max.to_array())
    };
    let close = |a: [f32; 3], b: [f32; 3]| (Vec3A::from(a) - Vec3A::from(b)).length() < 1e-5;
    let (lo, hi) = bounds(0);
    assert!(
        close(lo, [-1.0, -1.0, -4.0]) && close(hi, [1.0, 1.0, -2.0]),
        "{lo:?} {hi:?}"
    );
    let (lo, hi) = bounds(1);
    assert!(
        close(lo, [1.5, -0.5, -3.5]) && close(hi, [2.5, 0.5, -2.5]),
        "{lo:?} {hi:?}"
    );
    // Rays meet them where they are: CubeA's front face at z = -2, CubeB's at -2.5.
    let h = hit(&scene, [0.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert!(
        (h.t - 7.0).abs() < 1e-4 && h.object == 0,
        "{} {}",
        h.t,
        h.object
    );
    assert!((h.shading_normal - Vec3A::Z).length() < 1e-5);
    let h = hit(&scene, [2.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert!(
        (h.t - 7.5).abs() < 1e-4 && h.object == 1,
        "{} {}",
        h.t,
        h.object
    );
    // The file's materials, by name, on their faces: the front face is `Checker`, the top
    // face `Red`.
    let material = |h: &snell::scene::Hit| scene.material_names[h.material].clone();
    assert_eq!(
        material(&hit(&scene, [0.0, 0.0, 5.0], [0.0, 0.0, -1.0])),
        "two-cubes.gltf:Checker"
    );
    assert_eq!(
        material(&hit(&scene, [0.0, 5.0, -3.0], [0.0, -1.0, 0.0])),
        "two-cubes.gltf:Red"
    );
}

/// The checker's top-left texel (red) shows at the front face's top-left: glTF puts v = 0
/// at the top of the image, as snell does (read upside down, the texel there is white);
/// the base-colour factor multiplies the image.
#[test]
fn base_colour_images_face_the_right_way() {
    let scene = scene_with("two-cubes.gltf", "");
    // uv (1/8, 1/8), the centre of texel (0, 0), is (-0.75, 0.75) on the unit face.
    let h = hit(&scene, [-0.75, 0.75, 5.0], [0.0, 0.0, -1.0]);
    let m = scene.material_at(&h);
    let c = scene.textures[m.texture].eval(&h.tex);
    // sRGB (200, 20, 20) is linear (0.578, 0.007, 0.007); the factor halves green.
    let red = Color::new(0.578, 0.0035, 0.007);
    assert!((c - red).abs().max_element() < 0.005, "{c}");
    // The texel to its right (white, 240) at uv (3/8, 1/8).
    let h = hit(&scene, [-0.25, 0.75, 5.0], [0.0, 0.0, -1.0]);
    let c = scene.textures[scene.material_at(&h).texture].eval(&h.tex);
    let white = Color::new(0.871, 0.436, 0.871);
    assert!((c - white).abs().max_element() < 0.005, "{c}");
}

/// The binary container holds the same scene: the same picture, byte for byte.
#[test]
fn a_glb_is_the_same_scene_as_the_gltf() {
    let a = render(
        &scene_with("two-cubes.gltf", ""),
        &snell::integrator::Whitted,
        Some(1),
        &|_| {},
    )
    .unwrap()
    .image;
    let b = render(
        &scene_with("two-cubes.glb", ""),
        &snell::integrator::Whitted,
        Some(1),
        &|_| {},
    )
    .unwrap()
    .image;
    assert_eq!(a, b);
    assert!(
        a.pixels.iter().any(|p| p.max_element() > 0.05),
        "the cubes show"
    );
}

/// An object's transform moves the whole file, after the nodes' own placement; a material
/// given by the object replaces the file's.
#[test]
fn the_objects_transform_and_material_apply_to_every_part() {
    let scene = scene_with(
        "two-cubes.gltf",
        "transform = { translate = [0, 10, 0] }\nmaterial = \"grey\"\n\
         [materials.grey]\ncolor = 0.5",
    );
    let b = scene.objects[1].world_bounds.unwrap();
    assert!(
        (b.min - Vec3A::new(1.5, 9.5, -3.5)).length() < 1e-5,
        "{}",
        b.min
    );
    // CubeA and CubeB.
    assert_eq!(scene.objects.len(), 2);
    for o in &scene.objects {
        assert!(o.slot_materials.is_empty());
        assert_eq!(scene.material_names[o.material], "grey");
    }
}

/// Every map of a metallic-roughness material (tests/data/gltf/pbr-maps.gltf): the base
/// colour through its KHR_texture_transform, roughness from the green channel, the normal
/// map in MikkTSpace's frame or the file's TANGENT, and the emissive map times its factor and
/// strength.
#[test]
fn every_map_of_a_material_is_read() {
    use snell::material::detail::SurfaceDetail;
    use snell::material::{ColorParam, Scalar, Surface};
    let scene = scene_with("pbr-maps.gltf", "");
    let plain = hit(&scene, [-2.25, 0.1, 5.0], [0.0, 0.0, -1.0]);
    let m = scene.material_at(&plain);
    // u = 0.25 would read the red half; offset by 0.5 it reads the white one.
    let base = scene.textures[m.texture].eval(&plain.tex);
    assert!((base - Color::ONE).abs().max_element() < 1e-3, "{base}");
    // The map's blue (metallic) is 0: a dielectric, though the factor is 1. Its green 128
    // is 0.502 linear: roughness 0.8 x 0.502, alpha its square.
    let Surface::Plastic(p) = &m.surface else {
        panic!("a map of metallic 0 makes plastic: {:?}", m.surface)
    };
    let Scalar::Texture(r) = p.roughness else {
        panic!("roughness is read from the map")
    };
    let alpha = scene.textures[r].eval(&plain.tex).x;
    assert!(
        (alpha - (0.8f32 * 128.0 / 255.0).powi(2)).abs() < 1e-3,
        "{alpha}"
    );
    // Emission: sRGB (51, 102, 204) times [1, 1, 0.5] times 4.
    let e = m.emission.expect("an emitter");
    let ColorParam::Texture(g) = e.radiance else {
        panic!("emission is read from the map")
    };
    let glow = scene.textures[g].eval(&plain.tex);
    let want = Color::new(0.0331, 0.1329, 0.6038) * Color::new(4.0, 4.0, 2.0);
    assert!((glow - want).abs().max_element() < 2e-3, "{glow}");
    // The normal map: one texel tilted 45 degrees toward the map's +x, read as data.
    assert!(matches!(m.detail, Some(SurfaceDetail::Normal { scale, .. }) if scale == 1.0));
    let shaded = |h: &snell::scene::Hit| {
        let mut h = *h;
        let tex = h.tex;
        scene.with_detail(&mut h, &tex);
        h.shading_normal
    };
    // Without tangents, MikkTSpace's follow u: +x.
    let n = shaded(&plain);
    assert!(
        (n - Vec3A::new(1.0, 0.0, 1.0).normalize()).length() < 0.01,
        "{n}"
    );
    // The file's TANGENT says +y: the same texel tilts the normal toward +y.
    let tangent = hit(&scene, [2.1, -0.2, 5.0], [0.0, 0.0, -1.0]);
    let n = shaded(&tangent);
    assert!(
        (n - Vec3A::new(0.0, 1.0, 1.0).normalize()).length() < 0.01,
        "{n}"
    );
    // A negative uv_scale mirrors u: the map's +x now points along -x.
    let mirrored = scene_with("pbr-maps.gltf", "uv_scale = [-1, 1]");
    let mut h = hit(&mirrored, [-2.25, 0.1, 5.0], [0.0, 0.0, -1.0]);
    let tex = h.tex;
    mirrored.with_detail(&mut h, &tex);
    let n = h.shading_normal;
    assert!(
        (n - Vec3A::new(-1.0, 0.0, 1.0).normalize()).length() < 0.01,
        "{n}"
    );
}

/// Alpha modes (tests/data/gltf/cutout.gltf): `MASK` cuts holes where the base colour's
/// alpha is under the cutoff, for camera and shadow rays alike; `BLEND` lets through the
/// fraction of rays that alpha leaves.
#[test]
fn alpha_cuts_holes() {
    let scene = scene_with("cutout.gltf", "");
    let name = |h: &snell::scene::Hit| scene.objects[h.object].name.clone();
    // The leaf's left half (alpha 0) is a hole: the ray goes on to the wall behind it.
    let through = hit(&scene, [-0.25, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert!(name(&through).ends_with("Wall"), "{}", name(&through));
    assert!((through.t - 6.0).abs() < 1e-3, "{}", through.t);
    let leaf = hit(&scene, [0.25, 0.0, 5.0], [0.0, 0.0, -1.0]);
    assert!(name(&leaf).ends_with("Leaf"), "{}", name(&leaf));
    // Shadow rays from the wall toward +z: through the hole, blocked by the leaf.
    let up = |x: f32| Ray::new(Vec3A::new(x, 0.0, -0.999), Vec3A::Z);
    assert!(!scene.occluded(&up(-0.25), 10.0, Skip::NONE));
    assert!(scene.occluded(&up(0.25), 10.0, Skip::NONE));
    // The veil (alpha 0.25) stops about a quarter of the rays that meet it.
    let n = 4000;
    let stopped = (0..n)
        .filter(|k| {
            let x = 2.55 + 0.9 * (*k as f32 + 0.5) / n as f32;
            let y = 0.4 * ((*k as f32 * 0.618_034).fract() - 0.5);
            name(&hit(&scene, [x, y, 5.0], [0.0, 0.0, -1.0])).ends_with("Veil")
        })
        .count() as f32
        / n as f32;
    assert!((stopped - 0.25).abs() < 0.03, "{stopped}");
}

/// A scene with `[camera]` and objects of its own text, read in tests/data/gltf.
pub(super) fn scene_text(text: &str) -> Result<Scene, String> {
    let dir = repo("tests/data/gltf");
    load_str(text, &dir.join("t.toml"), &dir, Format::Toml).map_err(|e| format!("{e:?}"))
}

/// The file's cameras (tests/data/gltf/lit.gltf): `[camera] gltf` takes the first, or the
/// one `gltf_camera` names, placed by its node (glTF cameras look down their local -z).
#[test]
fn a_files_camera_places_the_view() {
    let object = "[[objects]]\ntype = \"mesh\"\nfile = \"lit.gltf\"\n";
    let scene = scene_text(&format!("[camera]\ngltf = \"lit.gltf\"\n{object}")).unwrap();
    let v = scene.camera.view();
    assert!((v.position - Vec3A::new(0.0, 0.0, 5.0)).length() < 1e-5);
    assert!(((v.look_at - v.position).normalize() - Vec3A::NEG_Z).length() < 1e-5);
    assert!((v.fov - 0.5f32.to_degrees()).abs() < 1e-3, "{}", v.fov);
    // The side camera: turned to look down -x, orthographic, twice ymag tall.
    let scene = scene_text(&format!(
        "[camera]\ngltf = \"lit.gltf\"\ngltf_camera = \"Side\"\n{object}"
    ))
    .unwrap();
    let v = scene.camera.view();
    assert!((v.position - Vec3A::new(5.0, 0.0, 0.0)).length() < 1e-5);
    assert!(((v.look_at - v.position).normalize() - Vec3A::NEG_X).length() < 1e-5);
    assert!(matches!(
        v.projection,
        snell::camera::Projection::Orthographic { height } if (height - 4.0).abs() < 1e-5
    ));
    // A name it does not have, and keys the file's camera gives, are errors.
    let e = scene_text(&format!(
        "[camera]\ngltf = \"lit.gltf\"\ngltf_camera = \"Sde\"\n{object}"
    ))
    .unwrap_err();
    assert!(
        e.contains("no camera named `Sde`") && e.contains("did you mean `Side`?"),
        "{e}"
    );
    let e = scene_text(&format!(
        "[camera]\ngltf = \"lit.gltf\"\nfov = 30\n{object}"
    ))
    .unwrap_err();
    assert!(e.contains("`fov` comes from the glTF file's camera"), "{e}");
    let e = scene_text(&format!("[camera]\ngltf = \"two-cubes.gltf\"\n{object}")).unwrap_err();
    assert!(e.contains("two-cubes.gltf has no camera"), "{e}");
}

/// `lights = true` adds the file's KHR_lights_punctual lights, placed by their nodes and
/// the object's transform, their photometric intensities over 683 lm/W.
#[test]
fn a_files_lights_join_the_scene() {
    use snell::light::{DirectionalLight, Falloff, Light, PointLight, SpotLight};
    let scene = scene_text(
        "[camera]\nlook_at = [0, 0, -1]\n[[objects]]\ntype = \"mesh\"\nfile = \"lit.gltf\"\n\
         lights = true\ntransform = { translate = [1, 0, 0] }\n",
    )
    .unwrap();
    assert_eq!(scene.lights.len(), 3, "{:?}", scene.lights);
    let close = |a: Vec3A, b: Vec3A| (a - b).length() < 1e-5;
    match scene.lights[0] {
        Light::Point(PointLight {
            position,
            color,
            falloff,
        }) => {
            assert!(close(position, Vec3A::new(1.0, 2.0, 3.0)), "{position}");
            assert!(close(color, Vec3A::new(1.0, 0.0, 0.0)), "{color}");
            assert_eq!(falloff, Some(Falloff::InverseSquare));
        }
        ref l => panic!("{l:?}"),
    }
    match scene.lights[1] {
        Light::Spot(SpotLight {
            position,
            direction,
            color,
            cos_outer,
            cos_inner,
            ..
        }) => {
            assert!(close(position, Vec3A::new(1.0, 0.0, 4.0)), "{position}");
            assert!(close(direction, Vec3A::NEG_Z), "{direction}");
            assert!(close(color, Vec3A::splat(2.0)), "{color}");
            assert!(
                (cos_outer - 0.4f32.cos()).abs() < 1e-6 && (cos_inner - 0.2f32.cos()).abs() < 1e-6
            );
        }
        ref l => panic!("{l:?}"),
    }
    match scene.lights[2] {
        Light::Directional(DirectionalLight { direction, color }) => {
            assert!(close(direction, Vec3A::NEG_Y), "{direction}");
            assert!(close(color, Vec3A::splat(2.0)), "{color}");
        }
        ref l => panic!("{l:?}"),
    }
    // Without the key the file's lights stay out (on an OBJ the key is an error:
    // tests/bad/127-lights-on-obj.toml).
    let scene = scene_text(
        "[camera]\nlook_at = [0, 0, -1]\n[[objects]]\ntype = \"mesh\"\nfile = \"lit.gltf\"\n",
    )
    .unwrap();
    assert!(scene.lights.is_empty());
}

/// A glTF file's images are held to the texture limit, as every texture is.
#[test]
fn a_glb_image_over_the_texture_limit_is_refused() {
    let dir = super::scratch("gltf-limit");
    let file = repo("tests/data/gltf/pbr-maps.gltf");
    let scene = dir.join("t.toml");
    std::fs::write(
        &scene,
        format!(
            "[camera]\nlook_at = [0, 0, -1]\n[[objects]]\ntype = \"mesh\"\nfile = {:?}\n",
            file.to_string_lossy()
        ),
    )
    .unwrap();
    let limits = snell::scene::Limits {
        max_texture_pixels: 1,
        ..snell::scene::Limits::default()
    };
    let e = format!(
        "{:?}",
        snell::scene::load_with(&scene, &limits).unwrap_err()
    );
    assert!(e.contains("more than the 1 a texture may have"), "{e}");
    assert!(snell::scene::load_with(&scene, &snell::scene::Limits::default()).is_ok());
}

/// COLOR_0 multiplies the base colour, blended between the corners by the point's
/// barycentrics: read as Blender writes it (normalized unsigned shorts), linear.
#[test]
fn vertex_colours_tint_the_base_colour_between_the_corners() {
    let scene = scene_with("vertex-colors.gltf", "");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // The quad lies in z = 0 (the scene's camera is not used): red, green, blue and white
    // at (-x -y), (+x -y), (+x +y), (-x +y); triangles (0, 1, 2) and (0, 2, 3).
    let at = |x: f32, y: f32| {
        let h = hit(&scene, [x, y, 5.0], [0.0, 0.0, -1.0]);
        scene.base_color(&h, &h.tex)
    };
    // (0.25, -0.25) in the first triangle: a quarter red, half green, a quarter blue.
    let c = at(0.25, -0.25);
    assert!(
        (c - Color::new(0.25, 0.5, 0.25)).abs().max_element() < 1e-4,
        "{c}"
    );
    // (-0.25, 0.25) in the second: a quarter red, a quarter blue, half white.
    let c = at(-0.25, 0.25);
    assert!(
        (c - Color::new(0.75, 0.5, 0.75)).abs().max_element() < 1e-4,
        "{c}"
    );
    // Near a corner, that corner's colour.
    let c = at(0.49, 0.49);
    assert!(
        (c - Color::new(0.0, 0.0, 1.0)).abs().max_element() < 0.02,
        "{c}"
    );
}

/// A metallic map of metal and dielectric areas (tests/data/gltf/metallic-map.gltf) is read
/// point by point: the dielectric third is plastic, the metal third metal, and the middle
/// third their blend by the map's 128 / 255. Rendered under a white sky, the pure red metal
/// reflects no green, the dielectric's clear coat reflects white, and the half-metal about
/// half as much.
#[test]
fn a_metallic_map_blends_metal_and_dielectric_point_by_point() {
    use snell::bsdf::Bsdf;
    use snell::integrator::Path as PathTracer;
    use snell::material::Surface;
    let scene = scene_with("metallic-map.gltf", "");
    let bsdf_at = |x: f32| {
        let h = hit(&scene, [x, 0.0, 5.0], [0.0, 0.0, -1.0]);
        let m = scene.material_at(&h);
        assert!(matches!(m.surface, Surface::Metallic(_)), "{:?}", m.surface);
        m.bsdf(&scene.textures, &h.tex, scene.base_color(&h, &h.tex))
    };
    assert!(matches!(bsdf_at(-2.0), Bsdf::Plastic(_)));
    match bsdf_at(0.0) {
        Bsdf::Metallic(b) => assert!((b.metallic - 128.0 / 255.0).abs() < 1e-3, "{b:?}"),
        other => panic!("the middle is a blend: {other:?}"),
    }
    assert!(matches!(bsdf_at(2.0), Bsdf::Conductor(_)));

    // Seen straight on, orthographic: each pixel column is 0.1 wide, x from -3 to 3.
    let scene = scene_text(
        "[image]\nwidth = 60\nheight = 20\nsamples = 64\n\
         [integrator]\ntype = \"path\"\n\
         [environment]\ntype = \"constant\"\ncolor = 1\n\
         [camera]\ntype = \"orthographic\"\nheight = 2\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
         [[objects]]\ntype = \"mesh\"\nfile = \"metallic-map.gltf\"\n",
    )
    .unwrap();
    let img = render(&scene, &PathTracer, Some(2), &|_| {}).unwrap().image;
    // The mean of the columns around x, in the middle rows.
    let mean = |x: f32| {
        let c = ((x + 3.0) / 0.1) as usize;
        let mut sum = Color::ZERO;
        for y in 6..14 {
            for col in c - 3..c + 3 {
                sum += img.pixels[y * 60 + col];
            }
        }
        sum / 48.0
    };
    let (dielectric, half, metal) = (mean(-2.0), mean(0.0), mean(2.0));
    assert_eq!(metal.y, 0.0, "{metal}");
    assert!(metal.x > 0.5, "{metal}");
    assert!(dielectric.y > 0.02, "{dielectric}");
    assert!(
        (half.y / dielectric.y - (1.0 - 128.0 / 255.0)).abs() < 0.15,
        "{half} against {dielectric}"
    );
}

/// TEXCOORD_1 (assets/models/assimp/BoxTexcoords, a cube as Blender's exporter writes it):
/// the material reads its base colour through the first uv set and its metallic-roughness
/// map through the second, which lies elsewhere on the image. Near the corner (1, 1, 1) of
/// the +z face the first set is (0.709, 0.178), where the map's green is about 204, and the
/// second (0.557, 0.297), where it is about 250: the roughness follows the second.
#[test]
fn a_map_on_the_second_uv_set_reads_it() {
    use snell::material::{Scalar, Surface};
    use snell::texture::Mapping;
    let dir = repo("assets/models/assimp/BoxTexcoords");
    let text = "[camera]\nposition = [0, 0, 6]\nlook_at = [0, 0, 0]\n\
                [[objects]]\ntype = \"mesh\"\nfile = \"boxTexcoords.gltf\"\n";
    let scene = load_str(text, &dir.join("t.toml"), &dir, Format::Toml).unwrap();
    assert!(
        !scene.warnings.iter().any(|w| w.contains("TEXCOORD")),
        "{:?}",
        scene.warnings
    );
    let h = hit(&scene, [0.98, 0.98, 5.0], [0.0, 0.0, -1.0]);
    assert!(
        (h.tex.uv - snell::math::Vec2::new(0.709, 0.178)).length() < 0.01,
        "{}",
        h.tex.uv
    );
    assert!(
        (h.tex.uv1 - snell::math::Vec2::new(0.557, 0.297)).length() < 0.01,
        "{}",
        h.tex.uv1
    );
    let m = scene.material_at(&h);
    let Surface::Plastic(p) = &m.surface else {
        panic!("metallic 0 makes plastic: {:?}", m.surface)
    };
    let Scalar::Texture(r) = p.roughness else {
        panic!("roughness is read from the map")
    };
    assert!(matches!(
        scene.textures[r].mapping,
        Mapping::SecondUv { .. }
    ));
    // The map's green, bilinear at a uv (texel centres at (i + 0.5) / 256), squared.
    let map = image::open(dir.join("texture.png")).unwrap().to_rgb8();
    let alpha_at = |uv: snell::math::Vec2| {
        let (x, y) = (uv.x * 256.0 - 0.5, uv.y * 256.0 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let g = |i: f32, j: f32| map.get_pixel(i as u32, j as u32)[1] as f32 / 255.0;
        let (fx, fy) = (x - x0, y - y0);
        let top = g(x0, y0) * (1.0 - fx) + g(x0 + 1.0, y0) * fx;
        let bottom = g(x0, y0 + 1.0) * (1.0 - fx) + g(x0 + 1.0, y0 + 1.0) * fx;
        (top * (1.0 - fy) + bottom * fy).powi(2)
    };
    let alpha = p.roughness.at(&scene.textures, &h.tex);
    let (second, first) = (alpha_at(h.tex.uv1), alpha_at(h.tex.uv));
    assert!(
        (alpha - second).abs() < 1e-3,
        "alpha {alpha}, the second set's {second}"
    );
    assert!(
        (alpha - first).abs() > 0.2,
        "alpha {alpha}, the first set's {first}"
    );
    // The base colour reads the first set: the image's colour there (97, 204, 96, sRGB).
    let base = scene.base_color(&h, &h.tex);
    assert!(base.y > 2.0 * base.x, "{base}");
}
