//! One pixel's light shared out by the kind of path that brought it (the preview's bar:
//! "62 % direct diffuse, 20 % diffuse then more, 18 % through the glass"), from the path
//! tracer's own samples of the pixel, with a few of each kind's paths vertex by vertex and
//! the scene's layout to draw them over (a view from above and one from the side).

use super::{LpeSet, Named, Tracker};
use crate::integrator::path_explain::PathRecord;
use crate::integrator::{Path, RayStats};
use crate::math::{Color, luminance};
use crate::render::{camera_ray, start_sample};
use crate::scene::Scene;
use serde_json::{Value, json};

/// The kinds a pixel's light is shared out by: every path the path tracer makes matches
/// exactly one (a path's first event is none, a diffuse reflection, a glossy event or a
/// singular one; then the light, or more).
pub const KINDS: [(&str, &str); 6] = [
    ("seen directly", "CL"),
    ("direct, diffuse", "C<RD>L"),
    ("direct, glossy", "CGL"),
    ("diffuse, then more", "C<RD>.+L"),
    ("glossy, then more", "CG.+L"),
    ("mirror or glass first", "CS.*L"),
];

/// Paths kept to draw, at most, of each kind.
pub const PATHS_PER_KIND: usize = 3;

/// Pixel `(x, y)`'s light over `samples` of the path tracer's samples (the render's own:
/// sample `k` takes the numbers the render gives it), shared out by [`KINDS`], as JSON:
/// `color` (their mean), `kinds` (each one's `name`, `expr`, mean `color` and `share` of the
/// luminance), `paths` (a few of each kind: `kind`, `sample`, `color` and the `vertices` of
/// `explain`'s path), and the layout: `camera`, `objects` (each bounded one's `name`, `min`,
/// `max`) and `lights` (those with a position).
/// `Err` with the reason where the scene's events cannot be numbered (too many materials).
pub fn pixel_paths(scene: &Scene, (x, y): (u32, u32), samples: u32) -> Result<Value, String> {
    let named: Vec<Named> = KINDS
        .iter()
        .map(|(n, e)| Named {
            name: n.to_string(),
            expr: e.to_string(),
        })
        .collect();
    let set = LpeSet::new(scene, &named).map_err(|e| e.error.to_string())?;
    let s = &scene.settings;
    let camera = scene.camera.raster(s.width, s.height);
    let mut total = Color::ZERO;
    let mut sums = [Color::ZERO; KINDS.len()];
    let mut kept = [0usize; KINDS.len()];
    let mut paths = vec![];
    let mut counted = 0u32;
    for k in 0..samples {
        let mut sampler = crate::sampler::Sampler::new(s.integrator.sampler, s.seed);
        let (px, py, _) = start_sample(s, &mut sampler, x, y, k);
        let ray = camera_ray(&camera, &mut sampler, px, py);
        let mut rec = (PathRecord::default(), Tracker::new(&set));
        let c = Path.trace(
            scene,
            &ray,
            &mut sampler,
            &mut RayStats::default(),
            &mut rec,
        );
        if !c.is_finite() {
            continue;
        }
        counted += 1;
        total += c;
        let (record, tracker) = rec;
        for (sum, part) in sums.iter_mut().zip(&tracker.sums) {
            *sum += *part;
        }
        // The sample's kind: the one that carries most of its light.
        let kind = (0..KINDS.len())
            .max_by(|&a, &b| luminance(tracker.sums[a]).total_cmp(&luminance(tracker.sums[b])))
            .filter(|&i| luminance(tracker.sums[i]) > 0.0);
        if let Some(i) = kind
            && kept[i] < PATHS_PER_KIND
        {
            kept[i] += 1;
            paths.push(json!({
                "kind": i,
                "sample": k,
                "color": c.to_array(),
                "vertices": record.vertices,
                "end": record.end,
            }));
        }
    }
    let n = counted.max(1) as f32;
    let all = luminance(total);
    let kinds: Vec<Value> = KINDS
        .iter()
        .zip(&sums)
        .map(|((name, expr), sum)| {
            json!({
                "name": name,
                "expr": expr,
                "color": (*sum / n).to_array(),
                "share": if all > 0.0 { luminance(*sum) / all } else { 0.0 },
            })
        })
        .collect();
    let objects: Vec<Value> = scene
        .objects
        .iter()
        .filter_map(|o| {
            let b = o.world_bounds?;
            Some(json!({ "name": o.name, "min": b.min.to_array(), "max": b.max.to_array() }))
        })
        .collect();
    let lights: Vec<Value> = scene
        .lights
        .iter()
        .filter_map(|l| l.position().map(|p| json!(p.to_array())))
        .collect();
    Ok(json!({
        "pixel": [x, y],
        "samples": counted,
        "color": (total / n).to_array(),
        "kinds": kinds,
        "paths": paths,
        "camera": scene.camera.position.to_array(),
        "objects": objects,
        "lights": lights,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Format, load_str};

    /// The kinds' colours add up to the pixel's; its share of each is in [0, 1] and they add
    /// up to 1; each kept path carries light of its kind and starts at a surface the camera
    /// sees. A pixel on the floor between a glass ball and a white one, under a lamp, has
    /// direct and indirect light.
    #[test]
    fn a_pixels_kinds_add_up_to_its_colour() {
        let text = "[image]\nwidth = 16\nheight = 12\n[integrator]\ntype = \"path\"\n\
                    [camera]\nposition = [0, 1, 4]\nlook_at = [0, 0, 0]\nfov = 40\n\
                    [materials.white]\ntype = \"diffuse\"\ncolor = 0.7\n\
                    [materials.glass]\ntype = \"dielectric\"\n\
                    [materials.glow]\ntype = \"diffuse\"\ncolor = 0\nemission = 8\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [0, 2, 0]\nradius = 0.5\nmaterial = \"glow\"\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [0.6, 0, 0]\nradius = 0.4\nmaterial = \"glass\"\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [-0.7, 0.1, -0.3]\nradius = 0.5\nmaterial = \"white\"\n\
                    [[objects]]\ntype = \"plane\"\npoint = [0, -0.4, 0]\nmaterial = \"white\"\n";
        let scene = load_str(
            text,
            std::path::Path::new("t.toml"),
            std::path::Path::new("."),
            Format::Toml,
        )
        .unwrap();
        let doc = pixel_paths(&scene, (8, 9), 64).unwrap();
        assert_eq!(doc["samples"], 64);
        let color: Vec<f64> = serde_json::from_value(doc["color"].clone()).unwrap();
        let kinds = doc["kinds"].as_array().unwrap();
        assert_eq!(kinds.len(), KINDS.len());
        let (mut sum, mut share) = ([0.0f64; 3], 0.0);
        for k in kinds {
            let c: Vec<f64> = serde_json::from_value(k["color"].clone()).unwrap();
            for i in 0..3 {
                sum[i] += c[i];
            }
            let s = k["share"].as_f64().unwrap();
            assert!((0.0..=1.0 + 1e-6).contains(&s), "{k}");
            share += s;
        }
        for i in 0..3 {
            assert!(
                (sum[i] - color[i]).abs() <= 1e-5 * color[i].max(1.0),
                "{sum:?} {color:?}"
            );
        }
        assert!((share - 1.0).abs() < 1e-4, "{share}");
        let share_of = |name: &str| {
            kinds.iter().find(|k| k["name"] == name).unwrap()["share"]
                .as_f64()
                .unwrap()
        };
        assert!(share_of("direct, diffuse") > 0.2);
        assert!(share_of("diffuse, then more") > 0.0);
        let paths = doc["paths"].as_array().unwrap();
        assert!(!paths.is_empty());
        for p in paths {
            let kind = p["kind"].as_u64().unwrap() as usize;
            assert!(kinds[kind]["share"].as_f64().unwrap() > 0.0);
            assert!(!p["vertices"].as_array().unwrap().is_empty());
        }
        assert_eq!(
            doc["objects"].as_array().unwrap().len(),
            3,
            "the plane is unbounded"
        );
    }
}
