//! Why one pixel has its colour, asked of a loaded scene: the tree of rays behind one
//! Whitted sample, the one path of a path-traced sample, or a bidirectional sample's
//! subpaths and strategies, and the JSON document that `snell explain --json` prints and the
//! preview's click shows (for the scene's integrator: `pixel_json`). The command line, the
//! preview server and scripts all ask here.

use crate::Scene;
use crate::integrator::explain::{RayNode, TreeRecorder};
use crate::integrator::path_explain::PathRecord;
use crate::integrator::{Path, RayStats, Whitted};
use crate::math::{Color, Vec3A};
use serde_json::{Value, json};

/// A Whitted sample explained: where it lies on the film, the colour it returns, the rays it
/// traced and their tree.
#[derive(Clone, Debug)]
pub struct WhittedExplained {
    /// The film position of the camera ray, in pixels.
    pub film: (f32, f32),
    /// The colour it returns, linear RGB.
    pub color: Color,
    /// The rays traced for it.
    pub rays: RayStats,
    /// The tree of rays.
    pub tree: RayNode,
}

/// The Whitted tree of the ray through film position `film`, recording at most `max_rays`
/// rays; `None` when nothing was recorded. `sample`, `((x, y), k)`, says the ray is sample
/// `k` of pixel `(x, y)` as the render takes it: then it passes through the camera's lens
/// where the render's sample does, and follows its wavelength through dispersive glass;
/// `None` for a ray through a pixel's centre (and the lens's).
pub fn whitted(
    scene: &Scene,
    film: (f32, f32),
    sample: Option<((u32, u32), u32)>,
    max_rays: usize,
) -> Option<WhittedExplained> {
    let s = &scene.settings;
    let camera = scene.camera.raster(s.width, s.height);
    let ray = match sample {
        Some(((x, y), k)) => camera.ray_lens(
            film.0,
            film.1,
            crate::render::whitted_lens_sample(s, x, y, k),
        ),
        None => camera.ray(film.0, film.1),
    };
    let mut rec = TreeRecorder::new(max_rays);
    let mut rays = RayStats::default();
    let color = Whitted.explain_sample(scene, &ray, sample, &mut rays, &mut rec);
    rec.finish().map(|tree| WhittedExplained {
        film,
        color,
        rays,
        tree,
    })
}

impl WhittedExplained {
    /// `explain --json`'s document: the scene file's name as `scene_path` gives it, the
    /// pixel, and which sample (`None`: the ray through the pixel's centre).
    pub fn to_json(
        &self,
        scene: &Scene,
        scene_path: &std::path::Path,
        pixel: (u32, u32),
        sample: Option<u32>,
    ) -> Value {
        let r = &self.rays;
        json!({
            "scene": scene_path.display().to_string(),
            "integrator": "whitted",
            "image": [scene.settings.width, scene.settings.height],
            "pixel": [pixel.0, pixel.1],
            "sample": sample,
            "film_position": [self.film.0, self.film.1],
            "color": self.color.to_array(),
            "rays_traced": { "camera": r.camera, "secondary": r.secondary, "shadow": r.shadow },
            "tree": &self.tree,
        })
    }
}

/// What explaining a pixel under light tracing says: the path shown is the path tracer's.
pub const LIGHT_NOTE: &str = "light tracing traces no camera paths: this is the path tracer's path of the pixel, whose picture light tracing agrees with";

/// A path-traced sample explained: its pixel and index, where it lies on the film, the
/// colour it returns, the rays it traced and the record of its path.
#[derive(Clone, Debug)]
pub struct PathExplained {
    /// The pixel, column and row.
    pub pixel: (u32, u32),
    /// Which of the pixel's samples.
    pub sample: u32,
    /// Its film position, in pixels.
    pub film: (f32, f32),
    /// The colour it returns, linear RGB (after the clamp, if the scene sets one).
    pub color: Color,
    /// The rays traced for it.
    pub rays: RayStats,
    /// The path, vertex by vertex.
    pub record: PathRecord,
}

/// Sample `k` of pixel `(x, y)` as the render takes it: its sampler (started, the film
/// position and the lens drawn), its film position, and its camera ray.
fn sample_ray(
    scene: &Scene,
    (x, y): (u32, u32),
    k: u32,
) -> (crate::sampler::Sampler, (f32, f32), crate::math::Ray) {
    let s = &scene.settings;
    let mut sampler = crate::sampler::Sampler::new(s.integrator.sampler, s.seed);
    let (px, py, _) = crate::render::start_sample(s, &mut sampler, x, y, k);
    let camera = scene.camera.raster(s.width, s.height);
    let ray = crate::render::camera_ray(&camera, &mut sampler, px, py);
    (sampler, (px, py), ray)
}

/// The one path of sample `k` of pixel `(x, y)` under the path tracer, the same random
/// numbers as the render gives that sample.
pub fn path(scene: &Scene, (x, y): (u32, u32), k: u32) -> PathExplained {
    let (mut sampler, (px, py), ray) = sample_ray(scene, (x, y), k);
    let mut rays = RayStats::default();
    let mut record = PathRecord::default();
    let color = Path.trace(scene, &ray, &mut sampler, &mut rays, &mut record);
    PathExplained {
        pixel: (x, y),
        sample: k,
        film: (px, py),
        color,
        rays,
        record,
    }
}

impl PathExplained {
    /// `explain --json`'s document, with the scene file's name as `scene_path` gives it.
    pub fn to_json(&self, scene: &Scene, scene_path: &std::path::Path) -> Value {
        let s = &scene.settings;
        let r = &self.rays;
        let mut doc = json!({
            "scene": scene_path.display().to_string(),
            "integrator": "path",
            "image": [s.width, s.height],
            "pixel": [self.pixel.0, self.pixel.1],
            "sample": self.sample,
            "film_position": [self.film.0, self.film.1],
            "color": self.color.to_array(),
            "sum_of_contributions": self.record.total(),
            "clamp": s.integrator.clamp,
            "rays_traced": { "camera": r.camera, "secondary": r.secondary, "shadow": r.shadow },
            "path": &self.record,
        });
        // Light tracing's scene is explained by the path tracer's path: said so.
        if s.integrator.kind == crate::scene::IntegratorKind::Light {
            doc["note"] = LIGHT_NOTE.into();
        }
        doc
    }
}

/// A bidirectional sample explained: its pixel and index, where it lies on the film, the
/// lengths of its two subpaths, and every strategy that carried light, with its weight.
#[derive(Clone, Debug)]
pub struct BdptExplained {
    /// The pixel.
    pub pixel: (u32, u32),
    /// The sample's index.
    pub sample: u32,
    /// Where it lies on the film.
    pub film: (f32, f32),
    /// What the sample adds to its own pixel (the strategies with more than one camera
    /// vertex).
    pub color: Color,
    /// The eye's subpath (the eye first) and the light's (the light first), vertex by
    /// vertex.
    pub subpaths: (
        Vec<crate::integrator::ShownVertex>,
        Vec<crate::integrator::ShownVertex>,
    ),
    /// The strategies that carried light, in the order they were joined.
    pub strategies: Vec<crate::integrator::Strategy>,
    /// The rays traced.
    pub rays: RayStats,
}

/// Sample `k` of pixel `(x, y)` under bidirectional path tracing, the same random numbers
/// as the render gives it, with each strategy it joined.
pub fn bdpt(scene: &Scene, (x, y): (u32, u32), k: u32) -> BdptExplained {
    let (mut sampler, (px, py), ray) = sample_ray(scene, (x, y), k);
    let mut rays = RayStats::default();
    let mut paths = crate::integrator::Paths::default();
    let mut strategies = vec![];
    let view = crate::integrator::LightView::of(scene);
    let color = crate::integrator::Bdpt.sample_with(
        scene,
        &view,
        &ray,
        &mut sampler,
        &mut paths,
        &mut rays,
        &mut |_, _, _| {},
        &mut |st| strategies.push(*st),
    );
    BdptExplained {
        pixel: (x, y),
        sample: k,
        film: (px, py),
        color,
        subpaths: paths.shown(scene),
        strategies,
        rays,
    }
}

impl BdptExplained {
    /// `explain --json`'s document, with the scene file's name as `scene_path` gives it.
    pub fn to_json(&self, scene: &Scene, scene_path: &std::path::Path) -> Value {
        let s = &scene.settings;
        let r = &self.rays;
        let strategies: Vec<Value> = self
            .strategies
            .iter()
            .map(|st| {
                json!({
                    "s": st.s,
                    "t": st.t,
                    "unweighted": st.light.to_array(),
                    "weight": st.weight,
                    "contribution": (st.light * st.weight).to_array(),
                    "lands_at": st.film.map(|(x, y)| [x, y]),
                })
            })
            .collect();
        json!({
            "scene": scene_path.display().to_string(),
            "integrator": "bdpt",
            "mis": format!("{:?}", s.integrator.mis).to_lowercase(),
            "image": [s.width, s.height],
            "pixel": [self.pixel.0, self.pixel.1],
            "sample": self.sample,
            "film_position": [self.film.0, self.film.1],
            "color": self.color.to_array(),
            "camera_vertices": self.subpaths.0.len(),
            "light_vertices": self.subpaths.1.len(),
            "camera_path": shown(&self.subpaths.0),
            "light_path": shown(&self.subpaths.1),
            "rays_traced": { "camera": r.camera, "secondary": r.secondary, "shadow": r.shadow },
            "strategies": strategies,
        })
    }

    /// The strategies as a table: `(s, t)`, what each strategy is, its light before and
    /// after its weight, and where a splat lands.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut out = String::new();
        let (c, l) = (&self.subpaths.0, &self.subpaths.1);
        let _ = writeln!(
            out,
            "  the eye's subpath has {} vertices (the eye included), the light's {}; each (s, t) joins s of the light's to t of the eye's",
            c.len(),
            l.len()
        );
        let chain = |v: &[crate::integrator::ShownVertex]| {
            v.iter()
                .map(|v| v.what.as_str())
                .collect::<Vec<_>>()
                .join(" -> ")
        };
        let _ = writeln!(out, "  the eye's: {}", chain(c));
        if !l.is_empty() {
            let _ = writeln!(out, "  the light's: {}", chain(l));
        }
        let rgb = |c: Color| format!("({:.4}, {:.4}, {:.4})", c.x, c.y, c.z);
        for st in &self.strategies {
            let kind = match (st.s, st.t) {
                (0, _) => "the eye's path found the light",
                (1, _) => "a light sampled from the eye's path",
                (_, 1) => "the light's path joined to the eye",
                _ => "the two paths joined",
            };
            let lands = match st.film {
                Some((x, y)) => format!(", lands at ({x:.1}, {y:.1})"),
                None => String::new(),
            };
            let _ = writeln!(
                out,
                "  (s={}, t={}) {kind}: light {} x weight {:.4} = {}{lands}",
                st.s,
                st.t,
                rgb(st.light),
                st.weight,
                rgb(st.light * st.weight)
            );
        }
        if self.strategies.is_empty() {
            let _ = writeln!(out, "  no strategy carried light");
        }
        out
    }
}

/// A subpath's vertices as `explain --json` gives them: what each is, and where.
fn shown(v: &[crate::integrator::ShownVertex]) -> Vec<Value> {
    v.iter()
        .map(|v| json!({ "what": v.what, "point": v.point.to_array() }))
        .collect()
}

/// What the preview shows for a click on pixel `(x, y)`, as `snell explain --json` gives
/// it for the scene's integrator: under Whitted the ray through the pixel's centre (at most
/// `max_rays` of its tree; the render's sample 0 where a pixel takes one), under the path tracer the path of sample 0, under bdpt sample
/// 0's two subpaths and its strategies, and under light tracing (which traces no camera
/// paths) the path tracer's path, said so in its `note`; each point with its place on the
/// picture ([`place_on_picture`]). `None` when nothing was recorded.
pub fn pixel_json(
    scene: &Scene,
    scene_path: &std::path::Path,
    (x, y): (u32, u32),
    max_rays: usize,
) -> Option<Value> {
    use crate::scene::IntegratorKind;
    let mut doc = match scene.settings.integrator.kind {
        IntegratorKind::Whitted => {
            let film = (x as f32 + 0.5, y as f32 + 0.5);
            // With one sample a pixel, that ray is the render's sample 0.
            let sample = (scene.settings.spp == 1).then_some(((x, y), 0));
            whitted(scene, film, sample, max_rays)?.to_json(scene, scene_path, (x, y), None)
        }
        IntegratorKind::Bdpt => bdpt(scene, (x, y), 0).to_json(scene, scene_path),
        IntegratorKind::Path | IntegratorKind::Light => {
            path(scene, (x, y), 0).to_json(scene, scene_path)
        }
    };
    place_on_picture(&mut doc, scene);
    Some(doc)
}

/// Adds `screen: [x, y]` (or null where the camera does not see it) beside every `point:
/// [x, y, z]` in `doc`: where a hit point lies on the picture, for drawing a path over it.
pub fn place_on_picture(doc: &mut Value, scene: &Scene) {
    let (w, h) = (scene.settings.width, scene.settings.height);
    place_points(doc, &|p| scene.camera.project(p, w, h));
}

fn place_points(doc: &mut Value, project: &dyn Fn(Vec3A) -> Option<(f32, f32)>) {
    match doc {
        Value::Object(map) => {
            let point = map.get("point").and_then(|p| {
                let a = p.as_array()?;
                let v: Vec<f32> = a
                    .iter()
                    .filter_map(|c| c.as_f64())
                    .map(|c| c as f32)
                    .collect();
                (v.len() == 3).then(|| Vec3A::new(v[0], v[1], v[2]))
            });
            if let Some(p) = point {
                let screen = project(p).map(|(x, y)| vec![x, y]);
                map.insert("screen".into(), json!(screen));
            }
            for v in map.values_mut() {
                place_points(v, project);
            }
        }
        Value::Array(items) => {
            for v in items {
                place_points(v, project);
            }
        }
        _ => {}
    }
}
