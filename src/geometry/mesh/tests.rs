//! The mesh's tests: its BVH walks against testing every triangle, its leaves' packing,
//! watertightness, normals and uvs, and refusing bad input.
use super::*;
use crate::geometry::triangle::WatertightRay;
use crate::math::Rng;

/// The test of a block's triangles at once gives, lane by lane, what the scalar
/// watertight test gives, for rays in every direction (so every choice of axes and
/// winding) and rays aimed at corners and edges, where the test falls back to double
/// precision; and it never reports a lane it was not asked about (another leaf's).
#[test]
fn block_test_agrees_with_the_scalar_watertight_test() {
    let mut rng = Rng::new(11);
    let mut r = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
    // Cases tested, and those where the scalar test finds a hit to compare.
    let (mut cases, mut hit_cases) = (0, 0);
    for case in 0..12000 {
        let corners: [Vec3A; 3] =
            std::array::from_fn(|_| Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)));
        // A leaf of `n` triangles from lane `first`, the triangle in one of its lanes,
        // the others random; the lanes outside the leaf random, or (every other case)
        // copies of the triangle, which must not be reported.
        let n = 1 + (case / 4) % LANES;
        let first = (case / 32) % (LANES + 1 - n);
        let lane = first + case % n;
        let leaf = ((1 << n) - 1) << first;
        let mut tris: [[Vec3A; 3]; LANES] = std::array::from_fn(|_| {
            std::array::from_fn(|_| Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)))
        });
        tris[lane] = corners;
        for (l, t) in tris.iter_mut().enumerate() {
            if leaf & (1 << l) == 0 && case % 2 == 0 {
                *t = corners;
            }
        }
        let block = TriangleBlock::new(&tris);
        let origin = Vec3A::new(r(-3.0, 3.0), r(-3.0, 3.0), r(-3.0, 3.0));
        // Aimed at a corner, a point on an edge, or anywhere near the triangle.
        let (a, b) = (case % 3, (case + 1) % 3);
        let target = match case % 4 {
            0 => corners[a],
            1 => corners[a].lerp(corners[b], r(0.0, 1.0)),
            _ => Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)),
        };
        if target == origin {
            continue;
        }
        cases += 1;
        let ray = Ray::new(origin, target - origin);
        let t_max = if case % 5 == 0 {
            r(0.0, 2.0)
        } else {
            f32::INFINITY
        };
        let scalar = WatertightRay::new(&ray).intersect(corners[0], corners[1], corners[2], t_max);
        hit_cases += usize::from(scalar.is_some());
        let hits = BlockRay::new(&ray).lanes(&block, leaf, t_max);
        let lanes = (hits.mask & (1 << lane) != 0).then(|| hits.get(lane));
        // `==` on floats, so a zero weight may differ in sign only.
        assert_eq!(lanes, scalar, "case {case}");
        assert_eq!(hits.mask & !leaf, 0, "case {case}: a lane outside the leaf");
        // The test of builds without AVX, in two halves, finds the same.
        let halves = BlockRay::new(&ray).lanes_in_halves(&block, leaf, t_max);
        assert_eq!(halves.mask, hits.mask, "case {case}");
        for l in (0..LANES).filter(|l| hits.mask & (1 << l) != 0) {
            assert_eq!(halves.get(l), hits.get(l), "case {case}");
        }
        // The nearest lane is the nearest of the leaf's triangles tested one by one.
        let one_by_one = (first..first + n)
            .filter_map(|l| {
                let [a, b, c] = block.corners(l);
                WatertightRay::new(&ray)
                    .intersect(a, b, c, t_max)
                    .map(|h| (l, h))
            })
            .fold(
                None,
                |best: Option<(usize, (f32, f32, f32))>, h| match best {
                    Some(b) if b.1.0 <= h.1.0 => Some(b),
                    _ => Some(h),
                },
            );
        assert_eq!(hits.nearest(), one_by_one, "case {case}");
    }
    // An origin drawn in [-3, 3]^3 equals its target in all three coordinates about once
    // in 2^60 cases: never here.
    assert_eq!(cases, 12000, "cases with a ray");
    // Replaying the generator: about half the rays aimed at a point of an edge hit, a
    // fifth of those aimed at a corner and a twelfth of the others, some 2,400 in all.
    assert!(hit_cases > 1000, "{hit_cases} cases hit the triangle");
}

/// A closed unit cube from 12 triangles, outward winding.
fn cube() -> MeshInput {
    let positions: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
        .collect();
    let quads = [
        [0, 2, 3, 1], // z = 0, facing -z
        [4, 5, 7, 6], // z = 1
        [0, 1, 5, 4], // y = 0
        [2, 6, 7, 3], // y = 1
        [0, 4, 6, 2], // x = 0
        [1, 3, 7, 5], // x = 1
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    MeshInput {
        positions,
        triangles,
        ..Default::default()
    }
}

#[test]
fn closed_cube_is_hit_from_outside_and_inside() {
    let (m, dropped) = Mesh::new(cube()).unwrap();
    assert_eq!((m.triangle_count(), dropped), (12, 0));
    let ray = Ray::new(Vec3A::new(0.3, 0.4, 5.0), Vec3A::NEG_Z);
    let h = m.intersect(&ray, f32::INFINITY).unwrap();
    assert!((h.t - 4.0).abs() < 1e-6);
    let s = m.hit_surface(&h);
    assert!(
        (s.normal - Vec3A::Z).length() < 1e-6,
        "outward normal {}",
        s.normal
    );
    assert!((s.point - Vec3A::new(0.3, 0.4, 1.0)).length() < 1e-6);
    // From inside, the far side.
    let inside = Ray::new(Vec3A::splat(0.5), Vec3A::X);
    let h = m.intersect(&inside, f32::INFINITY).unwrap();
    assert!((h.t - 0.5).abs() < 1e-6);
    assert!(m.intersect(&inside, 0.4).is_none(), "t_max respected");
    assert!(m.occluded(&inside, 0.6) && !m.occluded(&inside, 0.4));
    // A miss.
    let miss = Ray::new(Vec3A::new(2.0, 2.0, 5.0), Vec3A::NEG_Z);
    assert!(m.intersect(&miss, f32::INFINITY).is_none());
}

#[test]
fn directions_of_minus_zero_hit_like_plus_zero() {
    // A direction component of -0 (as a reflection or a transform can give) has an
    // inverse of -inf: the node test must then treat the axis as running backwards, or
    // every box's slab comes out empty and the ray misses the mesh.
    let (m, _) = Mesh::new(cube()).unwrap();
    let top = Vec3A::new(0.3, 0.4, 1.0);
    let side = Vec3A::new(1.0, 0.4, 0.3);
    for (dir, entry) in [
        (Vec3A::new(-0.0, -0.0, -1.0), top),
        (Vec3A::new(-0.0, 0.0, -1.0), top),
        (Vec3A::new(0.0, -0.0, -1.0), top),
        (Vec3A::new(-1.0, -0.0, -0.0), side),
    ] {
        let ray = Ray::new(entry - dir * 5.0, dir);
        let h = m.intersect(&ray, f32::INFINITY);
        assert!(h.is_some_and(|h| (h.t - 5.0).abs() < 1e-5), "{dir}: {h:?}");
        assert!(m.occluded(&ray, f32::INFINITY), "{dir}");
    }
}

#[test]
fn no_ray_slips_through_shared_edges() {
    // A flat grid of 2 x 32 x 32 triangles sharing edges and vertices: rays aimed at the
    // edges and vertices themselves (where each triangle's test is at its limit) must
    // all hit, from every direction.
    let n = 32;
    let positions: Vec<Vec3> = (0..=n)
        .flat_map(|j| {
            (0..=n).map(move |i| Vec3::new(i as f32 / n as f32, j as f32 / n as f32, 0.0))
        })
        .collect();
    let idx = |i: u32, j: u32| j * (n + 1) + i;
    let mut triangles = vec![];
    for j in 0..n {
        for i in 0..n {
            triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    let (m, _) = Mesh::new(MeshInput {
        positions,
        triangles,
        ..Default::default()
    })
    .unwrap();
    let mut rng = Rng::new(7);
    let mut misses = 0;
    for k in 0..20_000 {
        // Targets on the grid lines (and the diagonals), strictly inside the grid.
        let a = 1 + (rng.next_f32() * (n - 1) as f32) as u32;
        let f = rng.next_f32();
        let target = match k % 3 {
            0 => Vec3A::new(a as f32 / n as f32, f * 0.9 + 0.05, 0.0),
            1 => Vec3A::new(f * 0.9 + 0.05, a as f32 / n as f32, 0.0),
            _ => {
                let b = 1 + (rng.next_f32() * (n - 1) as f32) as u32;
                let t = rng.next_f32() / n as f32;
                Vec3A::new(a as f32 / n as f32 + t, b as f32 / n as f32 + t, 0.0)
            }
        };
        let dir = Vec3A::new(
            rng.next_f32() - 0.5,
            rng.next_f32() - 0.5,
            -(0.05 + rng.next_f32()),
        )
        .normalize();
        let origin = target - dir * (1.0 + 3.0 * rng.next_f32());
        let ray = Ray::new(origin, dir);
        if m.intersect(&ray, f32::INFINITY).is_none() {
            let wt = super::super::triangle::WatertightRay::new(&ray);
            let brute = (0..m.triangle_count() as u32).any(|p| {
                let [a, b, c] = m.corners(p);
                wt.intersect(a, b, c, f32::INFINITY).is_some()
            });
            eprintln!("miss k={k} target={target} brute={brute}");
            misses += 1;
        }
    }
    assert_eq!(misses, 0, "rays slipped between triangles");
}

#[test]
fn smooth_normals_and_uvs_are_interpolated() {
    let input = MeshInput {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        normals: vec![Vec3::Z, Vec3::new(1.0, 0.0, 1.0).normalize(), Vec3::Z],
        uvs: vec![Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.0, 2.0)],
        triangles: vec![[0, 1, 2]],
        ..Default::default()
    };
    let (m, _) = Mesh::new(input).unwrap();
    let h = m
        .intersect(&Ray::new(Vec3A::new(0.5, 0.25, 1.0), Vec3A::NEG_Z), 10.0)
        .unwrap();
    assert!((h.bary - Vec2::new(0.5, 0.25)).length() < 1e-6);
    let s = m.hit_surface(&h);
    assert!((s.uv - Vec2::new(0.5, 0.5)).length() < 1e-6);
    let n = m.interpolated_normal(&h).unwrap();
    assert!(n.x > 0.1 && n.z > 0.5 && (n.length() - 1.0).abs() < 1e-6);
}

#[test]
fn bad_input_is_refused_and_degenerate_triangles_dropped() {
    let mut c = cube();
    c.triangles.push([0, 1, 99]);
    assert!(Mesh::new(c).unwrap_err().contains("vertex 99"));
    let mut c = cube();
    c.triangles.push([0, 1, 1]);
    c.triangles.push([0, 1, 1]);
    assert_eq!(Mesh::new(c).unwrap().1, 2);
    let flat = MeshInput {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
        triangles: vec![[0, 1, 2]],
        ..Default::default()
    };
    assert!(Mesh::new(flat).unwrap_err().contains("zero area"));
}

#[test]
fn area_weighted_normals_favour_big_triangles() {
    // A big triangle facing +z and a small one facing +x share vertex 0.
    let positions = vec![Vec3::ZERO, Vec3::X * 10.0, Vec3::Y * 10.0, Vec3::Y, Vec3::Z];
    let n = area_weighted_normals(&positions, &[[0, 1, 2], [0, 3, 4]]);
    assert!(n[0].z > 0.99 && n[0].x > 0.0, "{}", n[0]);
    assert!((n[3] - Vec3::X).length() < 1e-6);
}

/// A soup of `count` separate small triangles in the cube [-1, 1]^3: each has its corners
/// within `size` of a random centre along each axis.
fn soup(rng: &mut Rng, count: u32, size: f32) -> MeshInput {
    let mut r = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
    let mut positions = vec![];
    let mut triangles = vec![];
    for i in 0..count {
        let c = Vec3::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0));
        for _ in 0..3 {
            positions.push(c + Vec3::new(r(-size, size), r(-size, size), r(-size, size)));
        }
        triangles.push([3 * i, 3 * i + 1, 3 * i + 2]);
    }
    MeshInput {
        positions,
        triangles,
        ..MeshInput::default()
    }
}

/// Leaves share blocks: each leaf's lanes lie in one block, no lane belongs to two
/// leaves, and the leaves' lanes hold every triangle once; lanes no leaf names repeat
/// one of their block's.
#[test]
fn leaves_are_packed_into_blocks_and_hold_every_triangle_once() {
    let input = soup(&mut Rng::new(5), 2000, 0.1);
    let triangles = input.triangles.clone();
    let (m, dropped) = Mesh::new(input).unwrap();
    assert_eq!(dropped, 0);
    let mut owner = vec![None; m.faces.len()];
    let mut leaves = 0;
    for (i, node) in m.bvh.nodes.iter().enumerate() {
        for &child in node.child.iter().filter(|&&c| c & LEAF != 0) {
            let block = (child & LEAF_BLOCK) as usize;
            let lanes = LEAF_LANE_MASKS[(child >> LEAF_LANES) as usize & 63];
            assert!(lanes != 0 && block < m.blocks.len(), "{child:#x}");
            for lane in (0..LANES).filter(|l| lanes & (1 << l) != 0) {
                let prim = block * LANES + lane;
                assert_eq!(owner[prim], None, "triangle {prim} in two leaves");
                owner[prim] = Some(i);
            }
            leaves += 1;
        }
    }
    let mut held: Vec<[u32; 3]> = (0..m.faces.len())
        .filter(|&p| owner[p].is_some())
        .map(|p| m.faces[p])
        .collect();
    held.sort();
    let mut all = triangles;
    all.sort();
    assert_eq!(held, all);
    for (p, face) in m.faces.iter().enumerate() {
        let block = &m.faces[p / LANES * LANES..][..LANES];
        assert!(owner[p].is_some() || block.contains(face));
        assert_eq!(m.corners(p as u32), m.blocks[p / LANES].corners(p % LANES));
    }
    // Most leaves hold fewer than eight triangles, and blocks are shared.
    assert_eq!(m.triangle_count(), 2000);
    assert!(
        m.blocks.len() < leaves,
        "{} blocks, {leaves} leaves",
        m.blocks.len()
    );
    assert!(
        m.blocks.len() * LANES < 2000 * 11 / 10,
        "{} blocks",
        m.blocks.len()
    );
}

#[test]
fn walks_find_the_hit_that_testing_every_triangle_finds() {
    // A soup of small triangles in a cube, so that rays cross many overlapping boxes
    // and the order of visits matters; rays from inside and outside it, in random
    // directions and along the axes (zero and minus-zero components).
    let mut rng = Rng::new(17);
    let (m, _) = Mesh::new(soup(&mut rng, 3000, 0.2)).unwrap();
    let mut r = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
    let (mut hits, mut misses) = (0, 0);
    for case in 0..3000 {
        let o = Vec3A::new(r(-1.5, 1.5), r(-1.5, 1.5), r(-1.5, 1.5));
        let mut d = Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0));
        match case % 5 {
            1 => (d.x, d.y) = (0.0, -0.0),
            2 => d.z = -0.0,
            _ => {}
        }
        let ray = Ray::new(o, d);
        // Every triangle, one by one, with the same test the walks use.
        let scalar = WatertightRay::new(&ray);
        let mut nearest: Option<(f32, u32)> = None;
        for p in 0..m.faces.len() as u32 {
            let limit = nearest.map_or(f32::INFINITY, |n| n.0);
            let [a, b, c] = m.corners(p);
            if let Some((t, _, _)) = scalar.intersect(a, b, c, limit) {
                nearest = Some((t, p));
            }
        }
        let found = m.intersect(&ray, f32::INFINITY).map(|h| (h.t, h.prim));
        assert_eq!(found, nearest, "{ray:?}");
        // The portable walks (the only ones in builds without AVX2 and FMA) agree too.
        let mut query = TriangleQuery::<false> {
            blocks: &m.blocks,
            source: &ray,
            ray: None,
            hit: None,
        };
        m.bvh
            .walk_with::<true, 160>(&ray, f32::INFINITY, &mut query, &mut []);
        assert_eq!(query.hit.map(|h| (h.t, h.prim)), nearest, "{ray:?}");
        let mut any = TriangleQuery::<true> {
            blocks: &m.blocks,
            source: &ray,
            ray: None,
            hit: None,
        };
        m.bvh
            .walk_with::<false, 160>(&ray, f32::INFINITY, &mut any, &mut []);
        assert_eq!(any.hit.is_some(), nearest.is_some(), "{ray:?}");
        assert_eq!(
            m.occluded(&ray, f32::INFINITY),
            nearest.is_some(),
            "{ray:?}"
        );
        // Nothing is nearer than the nearest.
        if let Some((t, _)) = nearest {
            assert_eq!(m.intersect(&ray, t), None, "{ray:?}");
            hits += 1;
        } else {
            misses += 1;
        }
    }
    assert!(hits > 1000 && misses > 300, "{hits} hits, {misses} misses");
}

#[test]
fn coincident_triangles_are_all_found_through_a_deep_bvh() {
    // Found by the `mesh` fuzz target: an OBJ whose polygons repeat the same corners
    // gives hundreds of coincident triangles, and obvhs builds them into a chain so deep
    // that its own debug validation (off in snell's builds) rejects it. The eight-wide
    // BVH snell traverses must still find every hit, and the other triangle beside them.
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(5.0, 0.0, 0.0),
        Vec3::new(6.0, 0.0, 0.0),
        Vec3::new(5.0, 1.0, 0.0),
    ];
    let mut triangles = vec![[0, 1, 2]; 2000];
    triangles.push([3, 4, 5]);
    let (m, dropped) = Mesh::new(MeshInput {
        positions,
        triangles,
        ..MeshInput::default()
    })
    .unwrap();
    assert_eq!((m.triangle_count(), dropped), (2001, 0));
    for i in 0..50 {
        let (x, y) = (0.05 + (i % 10) as f32 * 0.05, 0.05 + (i / 10) as f32 * 0.05);
        for (ox, dz) in [(0.0, -1.0), (0.0, 1.0), (5.0, -1.0), (5.0, 1.0)] {
            let ray = Ray::new(Vec3A::new(ox + x, y, -3.0 * dz), Vec3A::new(0.0, 0.0, dz));
            let hit = m.intersect(&ray, f32::INFINITY);
            assert!(hit.is_some_and(|h| (h.t - 3.0).abs() < 1e-5), "{ray:?}");
            assert!(m.occluded(&ray, f32::INFINITY), "{ray:?}");
        }
    }
}

/// A quad in the plane z = 0 facing +z, its uv laid on it with `u` along `u_dir` and `v`
/// (down the image) along `v_dir`, wound counter-clockwise seen from +z.
fn quad(u_dir: Vec3, v_dir: Vec3) -> Mesh {
    let corners = [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    let triangles = if u_dir.cross(v_dir).z > 0.0 {
        vec![[0, 1, 2], [0, 2, 3]]
    } else {
        vec![[0, 2, 1], [0, 3, 2]]
    };
    let (m, _) = Mesh::new(MeshInput {
        positions: corners.iter().map(|c| u_dir * c.x + v_dir * c.y).collect(),
        normals: vec![Vec3::Z; 4],
        uvs: corners.to_vec(),
        triangles,
        ..Default::default()
    })
    .unwrap();
    m
}

#[test]
fn mikktspace_tangents_follow_u_and_the_bitangent_points_up_the_image() {
    // u along +x, v (down the image) along -y: the image lies upright, seen from +z.
    let m = quad(Vec3::X, Vec3::NEG_Y);
    assert!(!m.has_tangents());
    m.ensure_tangents();
    assert!(m.has_tangents());
    for p in [Vec3A::new(0.7, -0.2, 0.0), Vec3A::new(0.2, -0.7, 0.0)] {
        let prim = m
            .intersect(&Ray::new(p + Vec3A::Z, Vec3A::NEG_Z), 10.0)
            .unwrap()
            .prim;
        let (t, b) = m.tangent_frame(p, prim).unwrap();
        assert!((t - Vec3A::X).length() < 1e-5, "{t}");
        assert!((b - Vec3A::Y).length() < 1e-5, "{b}");
    }
    // The image mirrored (v down along +y): up the image is now -y, and the frame is
    // left-handed.
    let m = quad(Vec3::X, Vec3::Y);
    m.ensure_tangents();
    let p = Vec3A::new(0.7, 0.2, 0.0);
    let prim = m
        .intersect(&Ray::new(p + Vec3A::Z, Vec3A::NEG_Z), 10.0)
        .unwrap()
        .prim;
    let (t, b) = m.tangent_frame(p, prim).unwrap();
    assert!((t - Vec3A::X).length() < 1e-5, "{t}");
    assert!((b - Vec3A::NEG_Y).length() < 1e-5, "{b}");
}

#[test]
fn a_files_tangents_are_kept_and_made_orthogonal_to_the_normal() {
    let (m, _) = Mesh::new(MeshInput {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        normals: vec![Vec3::Z; 3],
        uvs: vec![Vec2::ZERO, Vec2::X, Vec2::Y],
        triangles: vec![[0, 1, 2]],
        // Tilted out of the plane, and with a negative sign.
        tangents: vec![[0.0, 0.6, 0.8, -1.0]; 3],
        ..Default::default()
    })
    .unwrap();
    assert!(m.has_tangents());
    let (t, b) = m.tangent_frame(Vec3A::new(0.2, 0.2, 0.0), 0).unwrap();
    assert!((t - Vec3A::Y).length() < 1e-5, "{t}");
    assert!((b - Vec3A::X).length() < 1e-5, "{b}");
    // A count that does not match the vertices is refused.
    assert!(
        Mesh::new(MeshInput {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
            tangents: vec![[1.0, 0.0, 0.0, 1.0]; 2],
            ..Default::default()
        })
        .is_err()
    );
}
