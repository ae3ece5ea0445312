//! The weight of one strategy of a bidirectional path among all that could have made it
//! (Veach's multiple importance sampling over the `(s, t)` strategies, as pbrt's BDPT works
//! it out): the ratio of each other strategy's density to this one's, walked out from the
//! connection along both subpaths, vertex by vertex.

use super::Context;
use super::vertex::Vertex;
use crate::scene::MisHeuristic;

/// The weight of the strategy that joins the first `s` vertices of `light` to the first
/// `t` of `camera`, with `sampled` standing in for the light's vertex (`s = 1`) or the
/// eye's (`t = 1`) where the connection sampled a new one.
pub(super) fn weight(
    ctx: &Context,
    light: &[Vertex],
    camera: &[Vertex],
    sampled: Option<&Vertex>,
    s: usize,
    t: usize,
) -> f32 {
    if s + t == 2 {
        return 1.0;
    }
    let scene = ctx.scene;
    let qs = match (s, sampled) {
        (0, _) => None,
        (1, Some(v)) => Some(v),
        _ => Some(&light[s - 1]),
    };
    let pt = match (t, sampled) {
        (1, Some(v)) => v,
        _ => &camera[t - 1],
    };
    // A camera path that found an emitter no light sampling picks (or the background):
    // no other strategy makes it.
    if s == 0 && pt.light().is_none() {
        return 1.0;
    }
    let qs_minus = (s > 1).then(|| &light[s - 2]);
    let pt_minus = (t > 1).then(|| &camera[t - 2]);
    // The densities the connection changes: each side's last two vertices, as the other
    // side would have made them.
    let pt_rev = match qs {
        Some(qs) => qs.pdf(ctx, qs_minus, pt),
        None => pt_minus.map_or(0.0, |m| pt.pdf_light_origin(ctx, m)),
    };
    let pt_minus_rev = pt_minus.map(|m| match qs {
        Some(qs) => pt.pdf(ctx, Some(qs), m),
        None => pt.pdf_light(ctx, m),
    });
    let qs_rev = qs.map(|qs| pt.pdf(ctx, pt_minus, qs));
    let qs_minus_rev = match (qs, qs_minus) {
        (Some(qs), Some(m)) => Some(qs.pdf(ctx, Some(pt), m)),
        _ => None,
    };
    let remap = |f: f32| if f != 0.0 { f } else { 1.0 };
    let power = |r: f32| match ctx.mis {
        MisHeuristic::Balance => r,
        MisHeuristic::Power => r * r,
    };
    let mut sum = 0.0f32;
    // The strategies with fewer camera vertices.
    let cam_rev = |i: usize| {
        if i == t - 1 {
            pt_rev
        } else if Some(i) == t.checked_sub(2) {
            pt_minus_rev.unwrap_or(0.0)
        } else {
            camera[i].pdf_rev
        }
    };
    let cam_delta = |i: usize| i != t - 1 && camera[i].delta;
    let mut r = 1.0f32;
    for i in (1..t).rev() {
        let fwd = if i == t - 1 {
            pt.pdf_fwd
        } else {
            camera[i].pdf_fwd
        };
        // A delta's density is 0 on both of its sides, where the strategies that cross it
        // count it as 1 (it cancels); any other 0 is a strategy that cannot make the path.
        let rev = cam_rev(i);
        let rev = if i + 1 < t && cam_delta(i + 1) {
            remap(rev)
        } else {
            rev
        };
        let fwd = if cam_delta(i - 1) { remap(fwd) } else { fwd };
        if fwd == 0.0 {
            break;
        }
        r *= rev / fwd;
        if !cam_delta(i) && !cam_delta(i - 1) {
            sum += power(r);
        }
    }
    // The strategies with fewer light vertices.
    let light_at = |i: usize| match (i, s, sampled) {
        (0, 1, Some(v)) => v,
        _ => &light[i],
    };
    let light_rev = |i: usize| {
        if i == s - 1 {
            qs_rev.unwrap_or(0.0)
        } else if Some(i) == s.checked_sub(2) {
            qs_minus_rev.unwrap_or(0.0)
        } else {
            light[i].pdf_rev
        }
    };
    let light_delta = |i: usize| i != s - 1 && light_at(i).delta;
    let mut r = 1.0f32;
    for i in (0..s).rev() {
        let before_delta = if i > 0 {
            light_delta(i - 1)
        } else {
            light_at(0).delta_light(scene)
        };
        let rev = light_rev(i);
        let rev = if i + 1 < s && light_delta(i + 1) {
            remap(rev)
        } else {
            rev
        };
        let fwd = light_at(i).pdf_fwd;
        let fwd = if before_delta { remap(fwd) } else { fwd };
        if fwd == 0.0 {
            break;
        }
        r *= rev / fwd;
        if !light_delta(i) && !before_delta {
            sum += power(r);
        }
    }
    1.0 / (1.0 + sum)
}
