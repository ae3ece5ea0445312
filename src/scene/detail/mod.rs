//! A hit's shading normal bent by its material's normal or bump map, and the tangent frame
//! both read: how the surface point moves as the texture's `u` and `v` grow.
//!
//! The frame comes from the texture's own coordinates, whatever gives them (the shape's uv,
//! or a spherical, cylindrical or planar mapping): two steps across the surface, what the
//! texture's uv does over them, and the inverse of that. So every shape has a frame, and it
//! always agrees with the image it reads. A mesh with tangents (its file's, or MikkTSpace's)
//! read through its own uv uses those instead, as the tools that bake normal maps do.

use super::{Hit, Scene};
use crate::geometry::{Shape, ShapeHit};
use crate::material::detail::{SurfaceDetail, above, bumped_normal, mapped_normal};
use crate::math::{Frame, Vec2, Vec3A};
use crate::texture::{Footprint, Mapping, TexturePoint};

/// How a surface point moves as a texture's coordinates grow, world space and object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvFrame {
    /// The point's change with `u`, world space.
    pub dpdu: Vec3A,
    /// Its change with `v` (down the image), world space.
    pub dpdv: Vec3A,
    /// The same two in the object's space (where textures are read).
    pub local: [Vec3A; 2],
}

impl Scene {
    /// The tangent frame at `hit` of texture coordinates given by `mapping`; `None` where
    /// they do not change across the surface (a mapping seen edge-on, a degenerate uv).
    pub fn uv_frame(&self, hit: &Hit, mapping: &Mapping) -> Option<UvFrame> {
        let o = &self.objects[hit.object];
        let to_object = |v: Vec3A| o.transform.as_ref().map_or(v, |t| t.vector_to_object(v));
        // Two steps across the surface, a thousandth of the object's size (differences
        // over them are exact on flat uv and close enough on curved).
        let size = o
            .shape
            .bounds()
            .map_or(1.0, |b| (b.max - b.min).length().clamp(1e-6, 1e6));
        let f = Frame::from_axis(hit.normal);
        let steps = [f.u, f.v].map(|w| {
            let l = to_object(w);
            let s = 1e-3 * size / l.length().max(1e-30);
            (w * s, l * s)
        });
        let shape_hit = ShapeHit {
            t: hit.t,
            part: hit.part,
            prim: hit.prim,
            bary: Vec2::ZERO,
        };
        let duv = steps
            .map(|(_, l)| o.shape.differential(hit.tex.point, &shape_hit, l, true).0 * o.uv_scale);
        let duv1 = super::footprint::second_uv_change(o, hit.prim, steps.map(|s| s.1))
            .map_or(duv, |d| d.map(|d| d * o.uv_scale));
        let footprint = Footprint {
            dpdx: steps[0].1,
            dpdy: steps[1].1,
            duvdx: duv[0],
            duvdy: duv[1],
            duv1dx: duv1[0],
            duv1dy: duv1[1],
        };
        let (_, a, b) = mapping.uv_footprint(&TexturePoint {
            footprint: Some(&footprint),
            ..hit.tex
        });
        // [step0 step1] = [dpdu dpdv] [a b], so [dpdu dpdv] = [step0 step1] [a b]^-1.
        let det = a.x * b.y - b.x * a.y;
        if det.abs() <= 1e-20 || !det.is_finite() {
            return None;
        }
        let inv = [
            Vec2::new(b.y, -a.y) / det, // column for dpdu
            Vec2::new(-b.x, a.x) / det, // column for dpdv
        ];
        let world = |c: Vec2| steps[0].0 * c.x + steps[1].0 * c.y;
        let local = |c: Vec2| steps[0].1 * c.x + steps[1].1 * c.y;
        Some(UvFrame {
            dpdu: world(inv[0]),
            dpdv: world(inv[1]),
            local: [local(inv[0]), local(inv[1])],
        })
    }

    /// `hit` with its shading normal bent by its material's normal or bump map (read over
    /// `tex`'s footprint where it has one), kept above the surface. Unchanged for materials
    /// without one.
    #[inline]
    pub fn with_detail(&self, hit: &mut Hit, tex: &TexturePoint) {
        if let Some(d) = &self.materials[hit.material].detail {
            self.apply_detail(d, hit, tex);
        }
    }

    #[cold]
    #[inline(never)]
    fn apply_detail(&self, d: &SurfaceDetail, hit: &mut Hit, tex: &TexturePoint) {
        if let Some(m) = self.detail_normal(d, hit, tex) {
            hit.shading_normal = above(m, hit.normal);
        }
    }

    /// The normal `d` gives at `hit`, before it is kept above the surface.
    fn detail_normal(&self, d: &SurfaceDetail, hit: &Hit, tex: &TexturePoint) -> Option<Vec3A> {
        let texture = &self.textures[d.texture()];
        let n = hit.shading_normal;
        match *d {
            SurfaceDetail::Normal { scale, .. } => {
                let (t, b) = self.normal_map_frame(hit, &texture.mapping)?;
                mapped_normal(texture.eval(tex).to_array(), scale, t, b, n)
            }
            SurfaceDetail::Bump { height, .. } => {
                let f = self.uv_frame(hit, &texture.mapping)?;
                // The frame in the shading plane (pbrt's shading dpdu): the geometric plane's
                // would give a smooth mesh its facets back.
                let flat = |d: Vec3A| d - n * n.dot(d);
                let (dpdu, dpdv) = (flat(f.dpdu), flat(f.dpdv));
                // Differences over half the footprint in uv (pbrt's), or a thousandth of a
                // unit where there is none.
                let step = match tex.area() {
                    Some(_) => {
                        let (_, x, y) = texture.mapping.uv_footprint(tex);
                        0.5 * (x.abs() + y.abs()).max_element()
                    }
                    None => 0.0,
                };
                let step = if step > 1e-6 { step } else { 1e-3 };
                let h = |p: &TexturePoint| texture.eval(p).element_sum() / 3.0 * height;
                let here = h(tex);
                // The point a step along u or v: moved on the surface (for mappings that
                // read the point) and in the shape's uv (for those that read it, where the
                // texture's uv is the shape's: a transformed uv would need the step taken
                // back through its map, and only glTF files make one, with no bump maps).
                let moved = |k: usize| {
                    let mut p = *tex;
                    p.point += f.local[k] * step;
                    p.uv[k] += step;
                    p.uv1[k] += step;
                    p
                };
                let dhdu = (h(&moved(0)) - here) / step;
                let dhdv = (h(&moved(1)) - here) / step;
                bumped_normal(dpdu, dpdv, n, dhdu, dhdv)
            }
        }
    }

    /// The unit tangent and bitangent (up the image) a normal map read through `mapping`
    /// is read in at `hit`, world space, orthogonal to the shading normal.
    fn normal_map_frame(&self, hit: &Hit, mapping: &Mapping) -> Option<(Vec3A, Vec3A)> {
        let n = hit.shading_normal;
        let o = &self.objects[hit.object];
        let (t, up) = match &o.shape {
            Shape::Mesh(m) if mapping.keeps_uv_axes() && m.has_tangents() => {
                let (t, b) = m.tangent_frame(hit.tex.point, hit.prim)?;
                // A negative `uv_scale` mirrors the texture along that axis.
                let (t, b) = (t * o.uv_scale.x.signum(), b * o.uv_scale.y.signum());
                match &o.transform {
                    None => (t, b),
                    Some(x) => (x.vector_to_world(t), x.vector_to_world(b)),
                }
            }
            _ => {
                let f = self.uv_frame(hit, mapping)?;
                (f.dpdu, -f.dpdv)
            }
        };
        let t = (t - n * n.dot(t)).normalize_or_zero();
        if t == Vec3A::ZERO {
            return None;
        }
        let b = n.cross(t);
        Some((t, if b.dot(up) < 0.0 { -b } else { b }))
    }
}

#[cfg(test)]
mod tests;
