//! `[groups.NAME]` placed by objects of type `group`: each placement adds the group's
//! objects, each placed by its own transform and then the placement's, named under the
//! placement, with the placement's material where they name none; a group can be animated
//! as one object.

use super::scratch;
use snell::math::{Ray, Vec3A};
use snell::scene::{Format, Scene, Skip, load_str_frame};

const TREES: &str = r#"
[camera]
position = [0, 2, 10]
look_at = [0, 1, 0]
[materials.bark]
color = [0.4, 0.25, 0.1]
[materials.leaf]
color = [0.1, 0.6, 0.1]
[materials.autumn]
color = [0.8, 0.3, 0.1]
[[lights]]
type = "point"
position = [0, 8, 8]

[groups.tree]
objects = [
  { type = "cylinder", name = "trunk", radius = 0.1, height = 1, material = "bark" },
  { type = "sphere", name = "crown", center = [0, 1.5, 0], radius = 0.5 },
]
[groups.unused]
objects = [{ type = "sphere", radius = 1, material = "bark" }]

[[objects]]
type = "group"
group = "tree"
material = "leaf"

[[objects]]
type = "group"
name = "big"
group = "tree"
material = "autumn"
transform = { scale = 2, translate = [4, 0, 0] }
"#;

fn load(text: &str, frame: u32) -> Scene {
    let dir = scratch("groups");
    load_str_frame(text, &dir.join("t.toml"), &dir, Format::Toml, frame)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn down(scene: &Scene, x: f32) -> Option<(f32, String, String)> {
    let ray = Ray::new(Vec3A::new(x, 10.0, 0.0), -Vec3A::Y);
    let h = scene.closest_hit_with_uv(&ray, f32::INFINITY, Skip::NONE)?;
    Some((
        h.t,
        scene.objects[h.object].name.clone(),
        scene.material_names[h.material].clone(),
    ))
}

#[test]
fn each_placement_adds_the_groups_objects_placed_and_named_under_it() {
    let scene = load(TREES, 0);
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(
        names,
        ["tree #0/trunk", "tree #0/crown", "big/trunk", "big/crown"]
    );
    // The crown's top: at 2 in the group, at 4 in the placement scaled by 2.
    let (t, name, material) = down(&scene, 0.0).unwrap();
    assert!((t - 8.0).abs() < 1e-4, "{t}");
    assert_eq!(
        (name.as_str(), material.as_str()),
        ("tree #0/crown", "leaf")
    );
    let (t, name, material) = down(&scene, 4.0).unwrap();
    assert!((t - 6.0).abs() < 1e-4, "{t}");
    assert_eq!((name.as_str(), material.as_str()), ("big/crown", "autumn"));
    // A member's own material stays its own: the trunk, under the big crown's edge.
    let b = scene.objects[2].world_bounds.unwrap();
    assert!(
        (b.min - Vec3A::new(3.8, 0.0, -0.2)).abs().max_element() < 1e-4,
        "{b:?}"
    );
    assert!(
        (b.max - Vec3A::new(4.2, 2.0, 0.2)).abs().max_element() < 1e-4,
        "{b:?}"
    );
    assert_eq!(scene.material_names[scene.objects[2].material], "bark");
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("group `unused` is defined but no object places it")),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn a_placed_group_is_animated_as_one_object() {
    let text = format!(
        "{TREES}\n[animation]\nframes = 3\ninterpolation = \"linear\"\n\
         [[animation.objects]]\nobject = \"big\"\nframe = 0\ntranslate = [4, 0, 0]\n\
         [[animation.objects]]\nobject = \"big\"\nframe = 2\ntranslate = [4, 0, -6]\n"
    );
    let (t, name, _) = down(&load(&text, 0), 4.0).expect("the big crown at frame 0");
    assert!((t - 6.0).abs() < 1e-4);
    assert_eq!(name, "big/crown");
    // Frame 1: the whole tree 3 back, trunk and crown together.
    let moved = load(&text, 1);
    assert!(down(&moved, 4.0).is_none());
    let ray = Ray::new(Vec3A::new(4.0, 10.0, -3.0), -Vec3A::Y);
    let h = moved
        .closest_hit_with_uv(&ray, f32::INFINITY, Skip::NONE)
        .expect("the moved crown");
    assert!((h.t - 6.0).abs() < 1e-4);
    assert_eq!(moved.objects[h.object].name, "big/crown");
    let trunk = moved.objects[2].world_bounds.unwrap();
    assert!((trunk.center().z + 3.0).abs() < 1e-4, "{trunk:?}");
}
