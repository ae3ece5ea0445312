//! A pyramid of rays from one point: every ray a pinhole camera sends through a rectangle of
//! its film lies in it, so a box wholly outside it is met by none of them. A pixel whose
//! pyramid meets no object's box sees only the background, for every sample it could take.

use super::{Aabb, Vec3A};

/// The rays from `eye` on the inner side of four planes through it (a convex pyramid with its
/// apex at the eye, open on the far side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    /// The apex.
    pub eye: Vec3A,
    /// The planes' normals, pointing in: a point `p` is inside where `n . (p - eye) >= 0`
    /// for all four.
    pub normals: [Vec3A; 4],
    /// Per plane, how far below zero `n . p - n . eye` must be for a point to count as
    /// outside: `n . eye` less a slack for the rounding of those products.
    pub limits: [f32; 4],
    /// Per plane, the length of its normal.
    pub lengths: [f32; 4],
}

impl Frustum {
    /// The pyramid of rays from `eye` whose directions are `corner + per_x * x + per_y * y`
    /// for `x` in `[x0, x1]` and `y` in `[y0, y1]`: a pinhole camera's rays through that
    /// rectangle of its film (`corner` the direction through the film's origin, `per_x`
    /// and `per_y` its change per pixel). `scale` is the largest coordinate (in size) of
    /// anything tested against it, for the slack.
    pub fn through_film(
        eye: Vec3A,
        corner: Vec3A,
        per_x: Vec3A,
        per_y: Vec3A,
        rect: [f32; 4],
        scale: f32,
    ) -> Self {
        FilmPlanes::new(corner, per_x, per_y).frustum(eye, rect, scale)
    }

    /// Whether `b` lies wholly outside (beyond one plane: a box that only misses the
    /// pyramid past a corner counts as meeting it, which is safe).
    #[inline]
    pub fn excludes(&self, b: &Aabb) -> bool {
        self.normals.iter().zip(self.limits).any(|(n, limit)| {
            // The box's corner furthest along `n`.
            let far = Vec3A::select(n.cmpgt(Vec3A::ZERO), b.max, b.min);
            n.dot(far) < limit
        })
    }

    /// Whether the ball of `radius` around `center` lies wholly outside (beyond one plane).
    #[inline]
    pub fn excludes_sphere(&self, center: Vec3A, radius: f32) -> bool {
        (0..4).any(|k| self.normals[k].dot(center) + radius * self.lengths[k] < self.limits[k])
    }

    /// A bit per box of `boxes` (eight boxes' bounds side by side: per axis, the smallest
    /// coordinates, then the largest) that lies wholly outside, as [`Frustum::excludes`]
    /// says of each.
    #[inline]
    pub fn excludes_8(&self, boxes: &[[[f32; 8]; 2]; 3]) -> u32 {
        let mut outside = 0u32;
        for (n, limit) in self.normals.iter().zip(self.limits) {
            // Per axis, the side of the boxes furthest along `n`, chosen once for all eight;
            // then the eight lanes side by side (left to itself, the compiler vectorised over
            // the four planes and gathered each box's coordinates: 1 % of the seed's time).
            let [x, y, z] = [0, 1, 2].map(|axis| &boxes[axis][(n[axis] > 0.0) as usize]);
            outside |= below_8(n, [x, y, z], limit);
        }
        outside
    }
}

/// What a pinhole camera's film pyramids ([`Frustum::through_film`]) share, worked out once
/// per render: the plane through the eye holding the film's column at `x` holds the
/// directions `corner + per_x x` and `per_y`, so its normal is their cross product, affine
/// in `x`; and the same for rows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilmPlanes {
    /// The column plane's normal at `x = 0`, and its change per pixel.
    column: Vec3A,
    column_step: Vec3A,
    /// The row plane's, at `y = 0` and per pixel.
    row: Vec3A,
    row_step: Vec3A,
    /// The signs that turn the normals inward: moving along `per_x` goes in on the left
    /// plane and out on the right one (and so for `per_y`).
    sx: f32,
    sy: f32,
}

impl FilmPlanes {
    /// The planes of a film whose directions are `corner + per_x * x + per_y * y`.
    pub fn new(corner: Vec3A, per_x: Vec3A, per_y: Vec3A) -> Self {
        let (column, column_step) = (corner.cross(per_y), per_x.cross(per_y));
        let (row, row_step) = (corner.cross(per_x), per_y.cross(per_x));
        FilmPlanes {
            column,
            column_step,
            row,
            row_step,
            sx: column.dot(per_x).signum(),
            sy: row.dot(per_y).signum(),
        }
    }

    /// The pyramid of rays from `eye` through the film's rectangle `[x0, x1, y0, y1]`, as
    /// [`Frustum::through_film`].
    #[inline]
    pub fn frustum(&self, eye: Vec3A, [x0, x1, y0, y1]: [f32; 4], scale: f32) -> Frustum {
        let (sx, sy) = (self.sx, self.sy);
        let normals = [
            (self.column + self.column_step * x0) * sx,
            (self.column + self.column_step * x1) * -sx,
            (self.row + self.row_step * y0) * sy,
            (self.row + self.row_step * y1) * -sy,
        ];
        // A product `n . p` of numbers up to `scale` in size is off by at most a few ulps of
        // `|n|_1 scale`; a point must be further out than many times that to count.
        let limits = normals.map(|n| n.dot(eye) - n.abs().element_sum() * scale * 1e-5);
        Frustum {
            eye,
            normals,
            limits,
            lengths: normals.map(|n| n.length()),
        }
    }
}

/// A bit per lane where `n . (x, y, z)` (as `(n.x x + n.y y) + n.z z`) is under `limit`.
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
#[inline(always)]
fn below_8(n: &Vec3A, [x, y, z]: [&[f32; 8]; 3], limit: f32) -> u32 {
    use safe_arch::{cmp_op, cmp_op_mask_m256, m256, move_mask_m256, set_splat_m256};
    let lanes = |v: &[f32; 8]| m256::from_array(*v);
    let along = set_splat_m256(n.x) * lanes(x)
        + set_splat_m256(n.y) * lanes(y)
        + set_splat_m256(n.z) * lanes(z);
    let below = cmp_op_mask_m256::<{ cmp_op!(LessThanOrdered) }>(along, set_splat_m256(limit));
    move_mask_m256(below) as u32
}

/// A bit per lane where `n . (x, y, z)` (as `(n.x x + n.y y) + n.z z`) is under `limit`.
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
#[inline(always)]
fn below_8(n: &Vec3A, [x, y, z]: [&[f32; 8]; 3], limit: f32) -> u32 {
    (0..8).fold(0, |bits, lane| {
        let along = n.x * x[lane] + n.y * y[lane] + n.z * z[lane];
        bits | (((along < limit) as u32) << lane)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rng;

    /// A camera at `eye` looking down -z, 1 unit to the film, pixels 0.01 apart.
    fn film(eye: Vec3A) -> (Vec3A, Vec3A, Vec3A, Vec3A) {
        let (per_x, per_y) = (Vec3A::X * 0.01, Vec3A::NEG_Y * 0.01);
        (eye, Vec3A::new(-0.5, 0.5, -1.0), per_x, per_y)
    }

    /// Boxes around points on rays through the rectangle are never excluded; boxes beside
    /// it, behind the eye or past a side, are; eight at once say what each says alone.
    #[test]
    fn boxes_met_by_the_rays_are_never_excluded() {
        let mut rng = Rng::new(7);
        let (mut inside, mut outside) = (0, 0);
        for round in 0..2000 {
            let eye = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 20.0 - 10.0;
            let (eye, corner, per_x, per_y) = film(eye);
            let (x0, y0) = (rng.next_f32() * 90.0, rng.next_f32() * 90.0);
            let rect = [x0, x0 + 3.0, y0, y0 + 3.0];
            let f = Frustum::through_film(eye, corner, per_x, per_y, rect, 100.0);
            // A ray through the rectangle (edges included) and a point along it.
            let (x, y) = (x0 + 3.0 * rng.next_f32(), y0 + 3.0 * rng.next_f32());
            let (x, y) = match round % 5 {
                0 => (x0, y),
                1 => (x0 + 3.0, y),
                _ => (x, y),
            };
            let dir = (corner + per_x * x + per_y * y).normalize();
            let p = eye + dir * (0.01 + 50.0 * rng.next_f32());
            let size = 0.001 + rng.next_f32();
            let met = Aabb {
                min: p - Vec3A::splat(rng.next_f32() * size),
                max: p + Vec3A::splat(rng.next_f32() * size),
            };
            assert!(!f.excludes(&met), "{f:?} {met:?}");
            assert!(!f.excludes_sphere(p, size), "{f:?} {p} {size}");
            inside += 1;
            // A box well to the side of the rectangle, and one behind the eye.
            let beside = (corner + per_x * (x0 - 10.0) + per_y * y).normalize();
            let q = eye + beside * 30.0;
            let behind = eye - dir * 5.0;
            for c in [q, behind] {
                let b = Aabb {
                    min: c - Vec3A::splat(0.01),
                    max: c + Vec3A::splat(0.01),
                };
                assert!(f.excludes(&b), "{f:?} {b:?}");
                assert!(f.excludes_sphere(c, 0.01), "{f:?} {c}");
                outside += 1;
            }
            // The same boxes eight at a time (the rest empty: inverted).
            let mut boxes = [[[f32::INFINITY; 8], [f32::NEG_INFINITY; 8]]; 3];
            for (lane, b) in [met, Aabb::EMPTY].iter().enumerate() {
                for (axis, [lo, hi]) in boxes.iter_mut().enumerate() {
                    lo[lane] = b.min[axis];
                    hi[lane] = b.max[axis];
                }
            }
            assert_eq!(f.excludes_8(&boxes) & 1, 0);
        }
        assert_eq!((inside, outside), (2000, 4000));
    }
}
