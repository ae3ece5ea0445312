//! `[animation]`: its keys checked where they are written, and one frame's values put into
//! the scene's own tables (the camera, objects' transforms, lights) before the scene is
//! built, so a frame is built exactly as a still scene with those values would be.

use super::super::diag::{DocPath, name_help};
use super::super::format::*;
use super::Builder;
use crate::math::keyframes::{Interpolation, Key, sample};

/// The most frames an animation may have (10 hours at 24 frames a second, with room).
pub const MAX_FRAMES: u32 = 1_000_000;

/// A scene's animation: how many frames, how fast.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Animation {
    /// Frames 0 to `frames - 1`.
    pub frames: u32,
    /// Frames per second.
    pub fps: f32,
}

/// When each key of one target is, and how its curves leave it.
type Times = Vec<(f32, Interpolation)>;

impl Builder<'_> {
    /// Checks `[animation]` and puts the values of `frame` into `def`. `None` for a scene
    /// without one (which has frame 0 only).
    pub(super) fn animate(&mut self, def: &mut SceneFile, frame: u32) -> Option<Animation> {
        let root = DocPath::default();
        let Some(a) = def.animation.take() else {
            if frame != 0 {
                self.error_help(
                    root,
                    format!("frame {frame} was asked for, but the scene has no [animation]: it is one frame, 0"),
                    "add [animation] with a frame count and keys, or render frame 0",
                );
            }
            return None;
        };
        let path = root.key("animation");
        let frames = a.frames;
        if frames == 0 || frames > MAX_FRAMES {
            self.error(
                path.key("frames"),
                format!("must be between 1 and {MAX_FRAMES}, not {frames}"),
            );
            return None;
        }
        let fps = self.positive(a.fps, &path.key("fps"));
        if frame >= frames {
            self.error_help(
                path.key("frames"),
                format!(
                    "frame {frame} was asked for, but the animation has {frames} frames (0 to {})",
                    frames - 1
                ),
                "ask for frames in that range",
            );
        }
        let info = Animation { frames, fps };
        let t = frame.min(frames - 1) as f32;
        let default = interpolation(a.interpolation);
        self.animate_camera(def, &a.camera, &path.key("camera"), info, default, t);
        self.animate_objects(def, &a.objects, &path.key("objects"), info, default, t);
        self.animate_lights(def, &a.lights, &path.key("lights"), info, default, t);
        Some(info)
    }

    /// The times of `keys` (all of one target, at `paths`), checked: each has `frame` or
    /// `time`, within the animation, in increasing order. `None` where one is not.
    fn key_times<K: Keyed>(
        &mut self,
        keys: &[(&K, DocPath)],
        a: Animation,
        default: Interpolation,
    ) -> Option<Times> {
        let mut times: Times = vec![];
        let mut ok = true;
        for (k, path) in keys {
            let w = k.when();
            let t = match (w.frame, w.time) {
                (Some(f), None) => self.finite(f, &path.key("frame")),
                (None, Some(s)) => self.finite(s, &path.key("time")) * a.fps,
                (Some(_), Some(_)) => {
                    self.error_help(
                        path.key("time"),
                        "a key takes `frame` or `time`, not both",
                        "remove one of them",
                    );
                    ok = false;
                    continue;
                }
                (None, None) => {
                    self.error_help(
                        path.clone(),
                        "a key needs a `frame` (or a `time` in seconds)",
                        "add frame = 0",
                    );
                    ok = false;
                    continue;
                }
            };
            let at = path.key(if w.frame.is_some() { "frame" } else { "time" });
            let last = (a.frames - 1) as f32;
            if !(0.0..=last).contains(&t) {
                self.error_help(
                    at,
                    format!("this key is at frame {t}, outside the animation's frames 0 to {last}"),
                    "keys lie within the frames; raise [animation] frames to go further",
                );
                ok = false;
                continue;
            }
            if let Some(&(before, _)) = times.last()
                && t <= before
            {
                self.error_help(
                    at,
                    format!(
                        "this key is at frame {t}, not after the key before it (frame {before})"
                    ),
                    "write each target's keys in the order of their frames, each at its own frame",
                );
                ok = false;
                continue;
            }
            times.push((t, w.interpolation.map_or(default, interpolation)));
        }
        ok.then_some(times)
    }

    fn animate_camera(
        &mut self,
        def: &mut SceneFile,
        keys: &[CameraKeyDef],
        path: &DocPath,
        a: Animation,
        default: Interpolation,
        t: f32,
    ) {
        if keys.is_empty() {
            return;
        }
        let keyed: Vec<_> = keys
            .iter()
            .enumerate()
            .map(|(i, k)| (k, path.index(i)))
            .collect();
        let Some(times) = self.key_times(&keyed, a, default) else {
            return;
        };
        let c = &mut def.camera;
        for (k, p) in &keyed {
            if c.gltf.is_some()
                && let Some(name) = [
                    (k.position.is_some(), "position"),
                    (k.look_at.is_some(), "look_at"),
                    (k.up.is_some(), "up"),
                    (k.fov.is_some(), "fov"),
                ]
                .iter()
                .find_map(|(given, name)| given.then_some(*name))
            {
                self.error_help(
                    p.key(name),
                    "the camera is placed by a glTF file (`gltf`): its keys cannot move it",
                    "animate the camera of a scene that places it by position and look_at",
                );
            }
            if [k.position, k.look_at, k.up].iter().all(Option::is_none)
                && k.fov.is_none()
                && k.focus_distance.is_none()
            {
                self.no_values(p, "position, look_at, up, fov, focus_distance");
            }
            for (v, name) in [(k.position, "position"), (k.look_at, "look_at")] {
                if let Some(v) = v {
                    self.point(v, &p.key(name));
                }
            }
            if let Some(v) = k.up {
                self.direction(v, &p.key("up"));
            }
            if let Some(f) = k.fov {
                let f = self.finite(f, &p.key("fov"));
                if !(f > 0.0 && f < 180.0) {
                    self.error(
                        p.key("fov"),
                        format!(
                            "field of view must be between 0 and 180 degrees (exclusive), not {f}"
                        ),
                    );
                }
            }
            if let Some(f) = k.focus_distance {
                self.positive(f, &p.key("focus_distance"));
            }
        }
        let vector = |get: &dyn Fn(&CameraKeyDef) -> Option<[f32; 3]>| {
            curve(&times, keys.iter().map(get), t)
        };
        if let Some(v) = vector(&|k| k.position) {
            c.position = v;
        }
        if let Some(v) = vector(&|k| k.look_at) {
            c.look_at = Some(v);
        }
        if let Some(v) = vector(&|k| k.up) {
            c.up = v;
        }
        let scalar = |get: &dyn Fn(&CameraKeyDef) -> Option<f32>| {
            bounded_curve(&times, keys.iter().map(|k| get(k).map(|x| [x])), t).map(|v| v[0])
        };
        if let Some(v) = scalar(&|k| k.fov) {
            c.fov = Some(v);
        }
        if let Some(v) = scalar(&|k| k.focus_distance) {
            c.focus_distance = Some(v);
        }
    }

    fn animate_objects(
        &mut self,
        def: &mut SceneFile,
        keys: &[ObjectKeyDef],
        path: &DocPath,
        a: Animation,
        default: Interpolation,
        t: f32,
    ) {
        let names: Vec<Option<String>> = def.objects.iter().map(|o| o.common().0.clone()).collect();
        for (target, keyed) in by_target(keys, path, |k| &k.object) {
            let Some(i) = self.target(&names, &target, &keyed[0].1.key("object"), "object") else {
                continue;
            };
            let Some(times) = self.key_times(&keyed, a, default) else {
                continue;
            };
            for (k, p) in &keyed {
                if k.scale.is_none() && k.rotate.is_none() && k.translate.is_none() {
                    self.no_values(p, "translate, rotate, scale");
                }
                for (v, name) in [(k.rotate, "rotate"), (k.translate, "translate")] {
                    if let Some(v) = v {
                        self.point(v, &p.key(name));
                    }
                }
                if let Some(s) = k.scale {
                    let v = self.point(s.0, &p.key("scale"));
                    if v.cmpeq(crate::math::Vec3A::ZERO).any() {
                        self.error(
                            p.key("scale"),
                            "a scale of 0 flattens the object to nothing",
                        );
                    }
                }
            }
            let keys: Vec<&ObjectKeyDef> = keyed.iter().map(|(k, _)| *k).collect();
            let transform = def.objects[i]
                .placement_mut()
                .1
                .get_or_insert(TransformDef {
                    scale: ScaleDef([1.0; 3]),
                    rotate: [0.0; 3],
                    translate: [0.0; 3],
                });
            if let Some(v) = curve(&times, keys.iter().map(|k| k.translate), t) {
                transform.translate = v;
            }
            if let Some(v) = curve(&times, keys.iter().map(|k| k.rotate), t) {
                transform.rotate = v;
            }
            // A scale does not pass through 0 between keys of one sign.
            if let Some(v) = bounded_curve(&times, keys.iter().map(|k| k.scale.map(|s| s.0)), t) {
                transform.scale = ScaleDef(v);
            }
        }
    }

    fn animate_lights(
        &mut self,
        def: &mut SceneFile,
        keys: &[LightKeyDef],
        path: &DocPath,
        a: Animation,
        default: Interpolation,
        t: f32,
    ) {
        let names: Vec<Option<String>> = def.lights.iter().map(|l| l.name().clone()).collect();
        for (target, keyed) in by_target(keys, path, |k| &k.light) {
            let Some(i) = self.target(&names, &target, &keyed[0].1.key("light"), "light") else {
                continue;
            };
            let Some(times) = self.key_times(&keyed, a, default) else {
                continue;
            };
            let light = &def.lights[i];
            let (has_position, aim) = match light {
                LightDef::Point { .. } => (true, None),
                LightDef::Directional { .. } => (false, Some("direction")),
                LightDef::Spot { look_at, .. } => (
                    true,
                    Some(if look_at.is_some() {
                        "look_at"
                    } else {
                        "direction"
                    }),
                ),
            };
            for (k, p) in &keyed {
                let given = [
                    (k.position.is_some(), "position"),
                    (k.direction.is_some(), "direction"),
                    (k.look_at.is_some(), "look_at"),
                    (k.color.is_some(), "color"),
                    (k.intensity.is_some(), "intensity"),
                ];
                if given.iter().all(|(g, _)| !g) {
                    self.no_values(p, "position, direction, look_at, color, intensity");
                }
                for (g, name) in given {
                    let fits = match name {
                        "position" => has_position,
                        "direction" | "look_at" => aim == Some(name),
                        _ => true,
                    };
                    if g && !fits {
                        let why = match (name, aim) {
                            ("position", _) => "a directional light has no position".to_string(),
                            (_, Some(aim)) => {
                                format!("this light is aimed by `{aim}`: key `{aim}` instead")
                            }
                            _ => "a point light shines every way: it has no aim".to_string(),
                        };
                        self.error(p.key(name), why);
                    }
                }
                if let Some(v) = k.position {
                    self.point(v, &p.key("position"));
                }
                if let Some(v) = k.look_at {
                    self.point(v, &p.key("look_at"));
                }
                if let Some(v) = k.direction {
                    self.direction(v, &p.key("direction"));
                }
                if let Some(c) = k.color {
                    self.color(c, &p.key("color"));
                }
                if let Some(x) = k.intensity {
                    self.non_negative(x, &p.key("intensity"));
                }
            }
            let keys: Vec<&LightKeyDef> = keyed.iter().map(|(k, _)| *k).collect();
            let position = curve(&times, keys.iter().map(|k| k.position), t);
            let direction = curve(&times, keys.iter().map(|k| k.direction), t);
            let target = curve(&times, keys.iter().map(|k| k.look_at), t);
            let color = bounded_curve(&times, keys.iter().map(|k| k.color.map(|c| c.0)), t);
            let scalar = bounded_curve(&times, keys.iter().map(|k| k.intensity.map(|x| [x])), t);
            let (pos, dir, look, col, int) = match &mut def.lights[i] {
                LightDef::Point {
                    position,
                    color,
                    intensity,
                    ..
                } => (Some(position), None, None, color, intensity),
                LightDef::Directional {
                    direction,
                    color,
                    intensity,
                    ..
                } => (None, Some(direction), None, color, intensity),
                LightDef::Spot {
                    position,
                    look_at,
                    direction,
                    color,
                    intensity,
                    ..
                } => {
                    let dir = direction.as_mut();
                    (Some(position), dir, look_at.as_mut(), color, intensity)
                }
            };
            if let (Some(slot), Some(v)) = (pos, position) {
                *slot = v;
            }
            if let (Some(slot), Some(v)) = (dir, direction) {
                *slot = v;
            }
            if let (Some(slot), Some(v)) = (look, target) {
                *slot = v;
            }
            if let Some(v) = color {
                *col = ColorDef(v);
            }
            if let Some(v) = scalar {
                *int = v[0];
            }
        }
    }

    /// The index of the one object (or light) named `name`, or an error at `at`.
    fn target(
        &mut self,
        names: &[Option<String>],
        name: &str,
        at: &DocPath,
        what: &str,
    ) -> Option<usize> {
        let found: Vec<usize> = (0..names.len())
            .filter(|&i| names[i].as_deref() == Some(name))
            .collect();
        match found[..] {
            [i] => Some(i),
            [] => {
                let help = name_help(
                    name,
                    names.iter().flatten().map(String::as_str),
                    &format!("named {what}s"),
                    &format!("give the {what} a name: name = \"{name}\""),
                );
                self.error_help(at.clone(), format!("no {what} is named `{name}`"), help);
                None
            }
            _ => {
                self.error_help(
                    at.clone(),
                    format!(
                        "{} {what}s are named `{name}`: which to animate?",
                        found.len()
                    ),
                    format!("give each {what} a name of its own"),
                );
                None
            }
        }
    }

    fn no_values(&mut self, at: &DocPath, which: &str) {
        self.error_help(
            at.clone(),
            "this key gives no value to animate",
            format!("give one or more of {which}"),
        );
    }
}

fn interpolation(d: InterpolationDef) -> Interpolation {
    match d {
        InterpolationDef::Smooth => Interpolation::Smooth,
        InterpolationDef::Linear => Interpolation::Linear,
        InterpolationDef::Step => Interpolation::Step,
    }
}

/// Keys grouped by the target they name, in order of first mention, each with its path.
fn by_target<'k, K>(
    keys: &'k [K],
    path: &DocPath,
    name: impl Fn(&K) -> &String,
) -> Vec<(String, Vec<(&'k K, DocPath)>)> {
    let mut groups: Vec<(String, Vec<(&K, DocPath)>)> = vec![];
    for (i, k) in keys.iter().enumerate() {
        let n = name(k);
        let item = (k, path.index(i));
        match groups.iter_mut().find(|(g, _)| g == n) {
            Some((_, list)) => list.push(item),
            None => groups.push((n.clone(), vec![item])),
        }
    }
    groups
}

/// The curve of one property at `t`, through the keys that give it; `None` where none does.
fn curve<const N: usize>(
    times: &Times,
    values: impl Iterator<Item = Option<[f32; N]>>,
    t: f32,
) -> Option<[f32; N]> {
    let keys: Vec<Key<N>> = times
        .iter()
        .zip(values)
        .filter_map(|(&(t, how), v)| v.map(|v| Key { t, v, how }))
        .collect();
    (!keys.is_empty()).then(|| sample(&keys, t))
}

/// As [`curve`], each component kept within its keys' values: a smooth curve of a
/// quantity with a range (a field of view, an intensity, a colour, a scale) never
/// overshoots out of it.
fn bounded_curve<const N: usize>(
    times: &Times,
    values: impl Iterator<Item = Option<[f32; N]>> + Clone,
    t: f32,
) -> Option<[f32; N]> {
    let v = curve(times, values.clone(), t)?;
    let given: Vec<[f32; N]> = values.flatten().collect();
    Some(std::array::from_fn(|c| {
        let lo = given.iter().map(|g| g[c]).fold(f32::INFINITY, f32::min);
        let hi = given.iter().map(|g| g[c]).fold(f32::NEG_INFINITY, f32::max);
        v[c].clamp(lo, hi)
    }))
}
