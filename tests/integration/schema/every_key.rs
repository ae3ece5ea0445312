//! The scene with every key and every `type` of the format, which the edits start from, and
//! the test that it has them all.

use super::*;

/// Every key and every `type` of the format at least once (what the parser takes, not a
/// scene that builds: no files are read), so that the edits below try each of them.
pub(super) const EVERY_KEY: &str = r#"
"$schema" = "./snell.schema.json"
[image]
width = 320
height = 240
samples = 9
filter = { type = "tent", radius = 1.5 }
background = 0.2
max_depth = 8
seed = 7
exposure = -0.5
tonemap = "aces"
filter_textures = true
noise = 0.02
lpe = [{ name = "walls", expr = "C<RD>L", preset = "direct" }]
[integrator]
type = "path"
sampler = "independent"
rr_depth = 3
clamp = 10
mis = "balance"
[camera]
type = "orthographic"
height = 5
position = [0, 2, 6]
look_at = [0, 0, 0]
up = [0, 1, 0]
fov = 40
aperture = 0.1
focus_distance = 6
gltf = "scene.glb"
gltf_camera = "Main"
[world]
ambient = [0.1, 0.1, 0.2]
[fog]
mode = "linear"
color = 0.7
start = 1
end = 30
density = 0.1
[environment]
type = "image"
file = "sky.hdr"
rotate = [0, 90, 0]
scale = 2
visible = false
[textures.plain]
type = "solid"
color = [1, 0, 0]
[textures.photo]
type = "image"
file = "photo.png"
color_space = "linear"
wrap = "mirror"
mapping = { type = "spherical", center = [0, 1, 0], rotate = [0, 90, 0] }
[textures.photo2]
type = "image"
file = "photo.jpg"
color_space = "srgb"
[textures.board]
type = "checker"
even = 1
odd = [0, 0, 0.5]
size = 0.25
mapping = { type = "cylindrical", center = [0, 0, 0], axis = [0, 1, 0], height = 2 }
[textures.bands]
type = "stripes"
a = 1
b = 0
width = 0.1
mapping = { type = "planar", origin = [0, 0, 0], u = [1, 0, 0], v = [0, 0, 1] }
[textures.wrapped]
type = "checker"
mapping = { type = "uv" }
[materials.all]
color = 0.5
texture = "board"
ambient = 0.5
diffuse = 0.7
specular = [1, 1, 1]
shininess = 80
reflectivity = 0.1
transparency = 0.2
ior = 1.33
absorption = [0.1, 0, 0]
[materials.gold]
type = "conductor"
metal = "Au"
roughness = 0.2
color = 1
[materials.custom_metal]
type = "conductor"
eta = [0.2, 0.9, 1.1]
k = [3.9, 2.4, 2.2]
roughness = "bands"
[materials.glass]
type = "dielectric"
ior = 1.5
roughness = 0.1
absorption = [0.1, 0, 0]
normal_map = "photo"
normal_scale = 0.5
[materials.pane]
type = "thin"
ior = { cauchy = [1.5, 0.004] }
bump = "wrapped"
bump_height = 0.01
[materials.coat]
type = "plastic"
color = [0.8, 0.1, 0.1]
ior = { sellmeier = [1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653] }
roughness = 0.05
[materials.blend]
type = "metallic"
color = [0.9, 0.6, 0.2]
ior = "BK7"
roughness = 0.2
metallic = "bands"
[materials.lamp]
type = "diffuse"
color = 1
emission = [4, 4, 4]
two_sided = true
[meshes.statue]
file = "statue.obj"
smooth = true
[[lights]]
type = "point"
name = "lamp"
position = [0, 5, 0]
color = 1
intensity = 2
falloff = "none"
[[lights]]
type = "directional"
direction = [0, -1, 0]
color = [1, 0.9, 0.8]
intensity = 0.5
[[lights]]
type = "spot"
position = [0, 5, 0]
look_at = [0, 0, 0]
direction = [0, -1, 0]
color = 1
intensity = 3
angle = 25
soft_edge = 4
falloff = "inverse_square"
[[objects]]
type = "sphere"
name = "ball"
material = "all"
transform = { scale = [1, 2, 1], rotate = [0, 45, 0], translate = [0, 1, 0] }
center = [0, 0, 0]
radius = 1
[[objects]]
type = "plane"
material = "all"
point = [0, 0, 0]
normal = [0, 1, 0]
[[objects]]
type = "rectangle"
material = "all"
uv_scale = [1, 2]
corner = [0, 0, 0]
edge_u = [1, 0, 0]
edge_v = [0, 1, 0]
[[objects]]
type = "box"
material = "all"
transform = { scale = 2 }
min = [0, 0, 0]
max = [1, 1, 1]
[[objects]]
type = "cylinder"
material = "all"
base = [0, 0, 0]
axis = [0, 1, 0]
radius = 0.5
height = 2
capped = false
[[objects]]
type = "cone"
material = "all"
base = [0, 0, 0]
axis = [0, 1, 0]
radius = 0.5
height = 1
capped = true
[[objects]]
type = "csg"
material = "all"
operation = "difference"
shapes = [
  { type = "csg", operation = "intersection", shapes = [
    { type = "box", min = [-1, -1, -1], max = [1, 1, 1] },
    { type = "sphere", radius = 1.5 },
  ] },
  { type = "csg", operation = "union", shapes = [
    { type = "sphere", radius = 0.2, center = [0, 1, 0] },
    { type = "sphere", radius = 0.2, center = [0, -1, 0] },
  ] },
]
[[objects]]
type = "torus"
material = "all"
center = [0, 0, 0]
axis = [0, 1, 0]
major_radius = 1
minor_radius = 0.25
[[objects]]
type = "disk"
material = "all"
uv_scale = 4
center = [0, 0, 0]
normal = [0, 0, 1]
radius = 1
[[objects]]
type = "triangle"
material = "all"
vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
[[objects]]
type = "mesh"
file = "statue.obj"
smooth = false
lights = true
[[objects]]
type = "mesh"
mesh = "statue"
[[objects]]
type = "group"
group = "pair"
material = "all"
transform = { translate = [3, 0, 0] }
[groups.pair]
objects = [{ type = "sphere", radius = 0.5 }, { type = "sphere", center = [1, 0, 0], radius = 0.5, material = "all" }]
[animation]
frames = 48
fps = 24
interpolation = "linear"
[[animation.camera]]
frame = 0
interpolation = "step"
position = [0, 2, 6]
look_at = [0, 0, 0]
up = [0, 1, 0]
fov = 40
focus_distance = 6
[[animation.camera]]
time = 1.5
position = [1, 2, 6]
[[animation.objects]]
object = "ball"
frame = 0
interpolation = "smooth"
scale = 1
rotate = [0, 0, 0]
translate = [0, 1, 0]
[[animation.lights]]
light = "lamp"
frame = 0
interpolation = "linear"
position = [0, 5, 0]
direction = [0, -1, 0]
look_at = [0, 0, 0]
color = 1
intensity = 2
"#;

/// Every key (`properties`) and every `const` string the schema names.
pub(super) fn schema_words(schema: &Value, keys: &mut Vec<String>, consts: &mut Vec<Value>) {
    match schema {
        Value::Object(map) => {
            if let Some(Value::Object(props)) = map.get("properties") {
                keys.extend(props.keys().cloned());
            }
            if let Some(c @ Value::String(_)) = map.get("const") {
                consts.push(c.clone());
            }
            map.values().for_each(|v| schema_words(v, keys, consts));
        }
        Value::Array(items) => items.iter().for_each(|v| schema_words(v, keys, consts)),
        _ => {}
    }
}

/// Every key and every string in a scene.
pub(super) fn scene_words(scene: &Value, keys: &mut Vec<String>, strings: &mut Vec<Value>) {
    match scene {
        Value::Object(map) => {
            keys.extend(map.keys().cloned());
            map.values().for_each(|v| scene_words(v, keys, strings));
        }
        Value::Array(items) => items.iter().for_each(|v| scene_words(v, keys, strings)),
        s @ Value::String(_) => strings.push(s.clone()),
        _ => {}
    }
}

/// The sky's keys, which the every-key scene's image environment leaves out: every one at
/// once, which the format takes (the scene builder then refuses the sun placed three ways).
pub(super) const EVERY_SKY_KEY: &str = r#"
[camera]
look_at = [0, 0, -1]
[environment]
type = "sky"
sun_direction = [0, 1, 0]
sun_elevation = 30
sun_azimuth = 200
latitude = 45
longitude = 7
timezone = 1
day = 172
hour = 13.5
turbidity = 3
scale = 1
sun_scale = 1
sun_size = 0.533
visible = true
"#;

#[test]
fn the_every_key_scene_has_every_key_and_type_of_the_schema() {
    // Every key at once, which the rules between keys refuse: the types' schema takes it.
    let scene = toml_value(EVERY_KEY);
    assert_eq!(type_problems(&scene), vec![]);
    assert_eq!(parses(&scene), Ok(()));
    let sky = toml_value(EVERY_SKY_KEY);
    assert_eq!(type_problems(&sky), vec![]);
    assert_eq!(parses(&sky), Ok(()));
    let (mut keys, mut consts, mut used_keys, mut strings) = (vec![], vec![], vec![], vec![]);
    schema_words(&snell::scene::schema(), &mut keys, &mut consts);
    scene_words(&scene, &mut used_keys, &mut strings);
    scene_words(&sky, &mut used_keys, &mut strings);
    let missing: Vec<_> = keys.iter().filter(|k| !used_keys.contains(k)).collect();
    assert!(missing.is_empty(), "keys not in EVERY_KEY: {missing:?}");
    // A scene has one filter, fog mode, integrator, sampler, environment and tone curve: the
    // edits try the others in their place.
    let others = [
        "gaussian",
        "mitchell",
        "exponential",
        "whitted",
        "light",
        "bdpt",
        "power",
        "sobol",
        "phong",
        "constant",
        "perspective",
        "clamp",
        "reinhard",
        "repeat",
    ];
    let missing: Vec<_> = consts
        .iter()
        .filter(|c| !strings.contains(c) && !others.iter().any(|o| *c == o))
        .collect();
    assert!(missing.is_empty(), "types not in EVERY_KEY: {missing:?}");
}
