//! The tangent frame against the shapes' documented uv, and normal and bump maps against
//! surfaces worked out by hand.
use crate::math::{Ray, Vec3A};
use crate::scene::{Format, Scene, load_str};
use crate::texture::{ColorSpace, ImageData, Pattern};
use std::path::Path;
use std::sync::Arc;

/// A scene of one object of material `m`, whose keys `material` gives, with a texture `t`
/// of colour `color` everywhere (a checker of one colour) through `mapping`.
fn scene(object: &str, material: &str, color: [f32; 3], mapping: &str) -> Scene {
    let text = format!(
        "[camera]\nlook_at = [0, 0, -1]\n\
         [textures.t]\ntype = \"checker\"\neven = {color:?}\nodd = {color:?}\n{mapping}\n\
         [materials.m]\ncolor = 1\n{material}\n\
         [[objects]]\nmaterial = \"m\"\n{object}\n"
    );
    load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap()
}

/// The shading normal where a ray from `from` toward `to` meets the scene.
fn shading_normal(s: &Scene, from: Vec3A, to: Vec3A) -> Vec3A {
    let mut hit = s
        .closest_hit(&Ray::new(from, (to - from).normalize()), f32::INFINITY)
        .expect("the ray meets the object");
    let tex = hit.tex;
    s.with_detail(&mut hit, &tex);
    hit.shading_normal
}

fn close(a: Vec3A, b: Vec3A, tol: f32) -> bool {
    (a - b).length() < tol
}

/// A normal map's texel tilted 45 degrees toward +u, and one tilted toward up the image.
const H: f32 = 0.853_553_4; // 0.5 + 0.5 / sqrt 2
const TOWARD_U: [f32; 3] = [H, 0.5, H];
const TOWARD_UP: [f32; 3] = [0.5, H, H];

#[test]
fn a_plane_reads_its_normal_map_along_its_mapping() {
    // u along +x, v (down the image) along +z: up the image is -z.
    let plane = "type = \"plane\"\npoint = [0, -1, 0]\nnormal = [0, 1, 0]";
    let mapping = "[textures.t.mapping]\ntype = \"planar\"\nu = [1, 0, 0]\nv = [0, 0, 1]";
    let (from, to) = (Vec3A::new(0.3, 2.0, 0.2), Vec3A::new(0.1, -1.0, -0.4));
    let s = scene(plane, "normal_map = \"t\"", TOWARD_U, mapping);
    let n = shading_normal(&s, from, to);
    assert!(close(n, Vec3A::new(1.0, 1.0, 0.0).normalize(), 1e-3), "{n}");
    let s = scene(plane, "normal_map = \"t\"", TOWARD_UP, mapping);
    let n = shading_normal(&s, from, to);
    assert!(
        close(n, Vec3A::new(0.0, 1.0, -1.0).normalize(), 1e-3),
        "{n}"
    );
    // A scale of 0 flattens the map; a flat texel leaves the normal.
    let s = scene(
        plane,
        "normal_map = \"t\"\nnormal_scale = 0",
        TOWARD_U,
        mapping,
    );
    assert!(close(shading_normal(&s, from, to), Vec3A::Y, 1e-5));
    let s = scene(plane, "normal_map = \"t\"", [0.5, 0.5, 1.0], mapping);
    assert!(close(shading_normal(&s, from, to), Vec3A::Y, 1e-5));
    // A transform carries the frame: the plane turned 90 degrees about z lies at x = 1
    // facing -x, and its u axis (+x in object space) now points along +y.
    let turned = format!("{plane}\ntransform = {{ rotate = [0, 0, 90] }}");
    let s = scene(&turned, "normal_map = \"t\"", TOWARD_U, mapping);
    let n = shading_normal(&s, Vec3A::new(-3.0, 0.2, 0.1), Vec3A::new(1.0, 0.3, 0.0));
    assert!(
        close(n, Vec3A::new(-1.0, 1.0, 0.0).normalize(), 1e-3),
        "{n}"
    );
}

#[test]
fn a_spheres_tangent_points_east_and_its_bitangent_north() {
    // At +x on the equator, the sphere's u (longitude, east) grows toward -z, and up the
    // image is the north pole, +y (docs/scene-format.md, the sphere's uv).
    let sphere = "type = \"sphere\"\ncenter = [0, 0, 0]\nradius = 2";
    let (from, to) = (Vec3A::new(5.0, 0.0, 0.0), Vec3A::ZERO);
    let s = scene(sphere, "normal_map = \"t\"", TOWARD_U, "");
    let n = shading_normal(&s, from, to);
    assert!(
        close(n, Vec3A::new(1.0, 0.0, -1.0).normalize(), 1e-2),
        "{n}"
    );
    let s = scene(sphere, "normal_map = \"t\"", TOWARD_UP, "");
    let n = shading_normal(&s, from, to);
    assert!(close(n, Vec3A::new(1.0, 1.0, 0.0).normalize(), 1e-2), "{n}");
}

#[test]
fn a_bump_ramp_tilts_the_normal_by_its_slope() {
    // A texture whose value grows linearly with u (a ramp of 256 texels, texel i holding
    // i / 255), on a plane where u is x: height 0.5 u is the surface y = 0.5 x (per unit
    // of u, 256 / 255 of value), whose normal is (-0.5, 1, 0) normalised.
    let plane = "type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]";
    let mapping = "[textures.t.mapping]\ntype = \"planar\"\nu = [1, 0, 0]\nv = [0, 0, 1]";
    let mut s = scene(
        plane,
        "bump = \"t\"\nbump_height = 0.498046875",
        [0.0; 3],
        mapping,
    );
    let ramp = image::GrayImage::from_fn(256, 4, |x, _| image::Luma([x as u8]));
    let texture = s.materials[0].detail.unwrap().texture();
    s.textures[texture].pattern = Pattern::Image(Arc::new(ImageData::from_owned(
        image::DynamicImage::ImageLuma8(ramp),
        ColorSpace::Linear,
    )));
    let n = shading_normal(&s, Vec3A::new(0.5, 2.0, 0.3), Vec3A::new(0.5, 0.0, 0.4));
    assert!(
        close(n, Vec3A::new(-0.5, 1.0, 0.0).normalize(), 2e-3),
        "{n}"
    );
}

#[test]
fn a_normal_pointing_below_the_surface_is_kept_above_it() {
    // A texel pointing almost straight along +u, below the surface once scaled up.
    let plane = "type = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]";
    let mapping = "[textures.t.mapping]\ntype = \"planar\"\nu = [1, 0, 0]\nv = [0, 0, 1]";
    let s = scene(
        plane,
        "normal_map = \"t\"\nnormal_scale = -40",
        [1.0, 0.5, 0.52],
        mapping,
    );
    let n = shading_normal(&s, Vec3A::new(0.0, 1.0, 0.0), Vec3A::new(0.1, 0.0, 0.0));
    assert!(n.y > 0.0 && n.y < 0.02 && n.x < -0.99, "{n}");
}

#[test]
fn a_flat_bump_map_keeps_a_smooth_meshs_normals() {
    // The teapot, smooth: a bump map of one value everywhere changes nothing, where the
    // geometric plane's frame would give the facets back.
    let text = "[camera]\nlook_at = [0, 0, -1]\n\
        [textures.t]\ntype = \"checker\"\neven = 0.5\nodd = 0.5\n\
        [materials.m]\ncolor = 1\nbump = \"t\"\nbump_height = 0.1\n\
        [[objects]]\ntype = \"mesh\"\nfile = \"assets/models/teapot.obj\"\nsmooth = true\nmaterial = \"m\"\n";
    let s = load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap();
    let mut checked = 0;
    for k in 0..40 {
        let a = k as f32 * 0.157;
        let from = Vec3A::new(6.0 * a.cos(), 1.0 + 0.05 * k as f32, 6.0 * a.sin());
        let Some(mut hit) = s.closest_hit(&Ray::new(from, (-from).normalize()), f32::INFINITY)
        else {
            continue;
        };
        let smooth = hit.shading_normal;
        let tex = hit.tex;
        s.with_detail(&mut hit, &tex);
        assert!(
            close(hit.shading_normal, smooth, 1e-4),
            "{smooth} became {}",
            hit.shading_normal
        );
        checked += (smooth.dot(hit.normal) < 0.9999) as usize;
    }
    assert!(
        checked > 10,
        "too few hits where the smooth normal is not the face's"
    );
}
