//! The OBJ and MTL readers' tests: every corner form, indices relative and bad, polygons,
//! continuations, materials from MTL files, and what is ignored with a warning.

use super::mtl::texture_file;
use super::*;
use crate::mesh_file::test_util::{Lcg, temp_dir};

fn parse_str(text: &str) -> Result<MeshData, MeshError> {
    parse(text.as_bytes(), Path::new("test.obj"))
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn positions_only_keeps_file_vertices() {
    let m = parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n").unwrap();
    // The unreferenced 4th vertex stays: output vertices are the file's vertices.
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
    assert!(m.normals.is_empty() && m.uvs.is_empty());
    assert!(m.triangle_materials.is_empty() && m.materials.is_empty());
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

#[test]
fn crlf_comments_tabs_and_continuations() {
    let text = "# header comment\r\n\r\nv\t0 0 0   \r\nv 1 0 0 # trailing comment\r\n\
                v 0 1 \\\r\n 0\r\n  \r\nf 1 \\\r\n2 3\t\r\n# comment ending in backslash \\\r\n\
                v 0 0 1\r\n";
    let m = parse_str(text).unwrap();
    assert_eq!(
        m.positions,
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0]
        ]
    );
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

#[test]
fn continuation_errors_name_the_first_line() {
    let e = parse_str("v 0 0 0\nv 1 \\\n x 0\n").unwrap_err();
    assert_eq!(e.line, Some(2));
    assert_eq!(e.message, "`x` is not a number");
}

#[test]
fn negative_indices_are_relative() {
    let m = parse_str(&format!("{SQUARE}f -4 -3 -2\nf 1 -2 -1\n")).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    let e = parse_str("v 0 0 0\nv 1 0 0\nf -1 -2 -3\n").unwrap_err();
    assert_eq!(e.line, Some(3));
    assert!(e.message.contains("relative vertex index -3"), "{e}");
    assert!(e.message.contains("only 2 vertices so far"), "{e}");
}

#[test]
fn quads_and_pentagons_are_fan_triangulated() {
    let text = format!("{SQUARE}v 2 0 0\nv 2 1 0\nv 3 0.5 0\nf 1 2 3 4\nf 2 5 6 7 3\n");
    let m = parse_str(&text).unwrap();
    assert_eq!(
        m.triangles,
        vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 6], [1, 6, 2]]
    );
}

#[test]
fn corners_with_same_triple_share_a_vertex() {
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
                vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nvn 0 0 -1\n\
                f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\nf 1/1/2 3/3/2 2/2/2\n";
    let m = parse_str(text).unwrap();
    // 4 shared corners for the front faces, 3 more for the back face (other normal).
    assert_eq!(m.positions.len(), 7);
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]]);
    assert_eq!(m.uvs.len(), 7);
    assert_eq!(m.normals.len(), 7);
    assert_eq!(m.uvs[3], [0.0, 1.0]);
    assert_eq!(m.normals[0], [0.0, 0.0, 1.0]);
    assert_eq!(m.normals[4], [0.0, 0.0, -1.0]);
    assert_eq!(m.positions[6], [1.0, 0.0, 0.0]);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

#[test]
fn normal_only_and_uv_only_forms() {
    let m = parse_str(&format!("{SQUARE}vn 0 0 1\nf 1//1 2//1 3//1 4//1\n")).unwrap();
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.normals, vec![[0.0, 0.0, 1.0]; 4]);
    assert!(m.uvs.is_empty());
    let m = parse_str(&format!("{SQUARE}vt 0.5\nvt 1 1 0\nf 1/1 2/2 3/2\n")).unwrap();
    assert_eq!(m.uvs, vec![[0.5, 0.0], [1.0, 1.0], [1.0, 1.0]]);
    assert!(m.normals.is_empty());
}

#[test]
fn missing_normals_are_zero_filled_with_a_warning() {
    let m = parse_str(&format!("{SQUARE}vn 0 0 1\nf 1 2 3\nf 1//1 3//1 4//1\n")).unwrap();
    // (1, -, -) and (1, -, 1) are different corners, so 6 vertices.
    assert_eq!(m.triangles, vec![[0, 1, 2], [3, 4, 5]]);
    assert_eq!(m.normals.len(), 6);
    assert_eq!(m.normals[0], [0.0; 3]);
    assert_eq!(m.normals[3], [0.0, 0.0, 1.0]);
    assert_eq!(m.warnings.len(), 1, "{:?}", m.warnings);
    assert!(
        m.warnings[0].contains("3 vertices have no normal"),
        "{:?}",
        m.warnings
    );
}

#[test]
fn vertex_w_and_colours_are_ignored() {
    let m = parse_str("v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0 1 0 0 1\nf 1 2 3\n").unwrap();
    assert_eq!(m.positions[1], [1.0, 0.0, 0.0]);
    let e = parse_str("v 0 0 0 red\n").unwrap_err();
    assert_eq!(e.message, "`red` is not a number");
}

#[test]
fn forward_references_resolve_at_the_end() {
    let m = parse_str("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
}

#[test]
fn bad_indices_name_the_face_line() {
    let e = parse_str(&format!("{SQUARE}f 1 2 3\nf 1 2 9\nf 1 2 4\n")).unwrap_err();
    assert_eq!(e.line, Some(6));
    assert_eq!(
        e.message,
        "vertex index 9 is out of range: the file has only 4 vertices"
    );
    assert!(e.to_string().starts_with("test.obj:6: "), "{e}");
    let e = parse_str(&format!("{SQUARE}f 1 0 2\n")).unwrap_err();
    assert_eq!(e.line, Some(5));
    assert!(e.message.contains("index 0 is invalid"), "{e}");
    let e = parse_str(&format!("{SQUARE}f 1/3 2/1 3/1\nvt 0 0\n")).unwrap_err();
    assert_eq!(e.line, Some(5));
    assert!(e.message.contains("texture coordinate index 3"), "{e}");
    let e = parse_str(&format!("{SQUARE}f 1//1 2//1 3//1\n")).unwrap_err();
    assert!(e.message.contains("the file has no normals"), "{e}");
    let e = parse_str(&format!("{SQUARE}f 1 2 x\n")).unwrap_err();
    assert_eq!(e.message, "`x` is not a valid index");
    let e = parse_str(&format!("{SQUARE}f 1 2 3/1/1/1\n")).unwrap_err();
    assert_eq!(e.message, "`3/1/1/1` is not a valid face vertex");
    let e = parse_str(&format!("{SQUARE}f 1 2 99999999999999\n")).unwrap_err();
    assert!(e.message.contains("too large"), "{e}");
}

#[test]
fn non_numbers_and_non_finite_values_name_the_line() {
    let text = "v 0 0 0\nv 1 0 0\n\n\n\n\nv 1 abc 3\n";
    let e = parse_str(text).unwrap_err();
    assert_eq!(
        (e.line, e.message.as_str()),
        (Some(7), "`abc` is not a number")
    );
    assert_eq!(e.to_string(), "test.obj:7: `abc` is not a number");
    let e = parse_str("v 0 0 0\nv NaN 0 0\n").unwrap_err();
    assert_eq!(e.line, Some(2));
    assert_eq!(e.message, "`NaN` is not a finite number");
    let e = parse_str("vn 0 inf 0\n").unwrap_err();
    assert_eq!(e.line, Some(1));
    let e = parse_str("vt 1e39 0\n").unwrap_err();
    assert!(e.message.contains("not a finite number"), "{e}");
    let e = parse_str("v 1 2\n").unwrap_err();
    assert_eq!(e.message, "`v` needs 3 numbers, found 2");
}

#[test]
fn short_faces_are_errors() {
    let e = parse_str(&format!("{SQUARE}f 1 2\n")).unwrap_err();
    assert_eq!(e.line, Some(5));
    assert_eq!(e.message, "face has 2 vertices; at least 3 are needed");
    assert!(parse_str(&format!("{SQUARE}f\n")).is_err());
}

#[test]
fn lines_points_and_unknown_statements_are_summarised() {
    let mut text = format!("{SQUARE}o thing\ng part\ns off\nl 1 2\nl 2 3\np 1\n");
    for _ in 0..1000 {
        text.push_str("curv 0 1 1 2\n");
    }
    for i in 0..20 {
        text.push_str(&format!("junk{i} 1\n"));
    }
    text.push_str("f 1 2 3\n");
    let m = parse_str(&text).unwrap();
    assert_eq!(m.triangles.len(), 1);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("ignored 2 line (`l`) elements (first on line 8)")),
        "{:?}",
        m.warnings
    );
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("ignored 1 point (`p`) element"))
    );
    assert!(
        m.warnings
            .contains(&"line 11: unknown statement `curv` ignored (1000 times)".to_string()),
        "{:?}",
        m.warnings
    );
    assert!(m.warnings.len() <= 12, "{:?}", m.warnings);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("13 other unknown statements")),
        "{:?}",
        m.warnings
    );
}

#[test]
fn degenerate_faces_are_skipped_with_one_warning() {
    let text = format!("{SQUARE}v 2 0 0\nf 1 2 3\nf 1 1 2\nf 1 2 5\nf 2 3 4\n");
    let m = parse_str(&text).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2], [1, 2, 3]]);
    assert_eq!(
        m.warnings,
        vec!["skipped 2 degenerate (zero-area) triangles"]
    );
}

const MTL: &str = "# materials\r\nKd 9 9 9\r\nnewmtl red\r\nKd 0.8 0.1 0.1\r\nKs 0.5\r\n\
    Ka 1 1 1\r\nNs 32\r\nNi 1.5\r\nd 0.75\r\nTr 0.9\r\nillum 2\r\n\
    map_Kd -s 1 1 1 -o 0.5 -bm 0.2 -clamp on textures\\red wood.png\r\nmap_Bump bump.png\r\n\
    newmtl glass\r\nTr 0.25\r\nTf 0.9\r\nKe 1 2 3\r\nillum 7.0\r\nmap_Kd /abs/tex.png\r\nPr 0.3\r\nPM 1\r\n\
    newmtl spectral\r\nKd spectral foo.rfl\r\nd -halo 0.5\r\n";

#[test]
fn usemtl_with_mtl_next_to_the_obj() {
    let dir = temp_dir("usemtl");
    write(&dir, "scene.mtl", MTL);
    let obj = write(
        &dir,
        "scene.obj",
        &format!("mtllib scene.mtl\n{SQUARE}f 1 2 3\nusemtl glass\nf 1 3 4\nusemtl red\nf 1 2 4\n"),
    );
    let m = load(&obj).unwrap();
    let names: Vec<&str> = m.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["red", "glass", "spectral", NO_MATERIAL_NAME]);
    // The face before the first usemtl gets the added "(none)" material.
    assert_eq!(m.triangle_materials, vec![3, 1, 0]);
    let red = &m.materials[0];
    assert_eq!(red.kd, Some([0.8, 0.1, 0.1]));
    assert_eq!(red.ks, Some([0.5; 3]));
    assert_eq!(red.ns, Some(32.0));
    assert_eq!(red.ni, Some(1.5));
    assert_eq!(red.d, Some(0.75), "d wins over a later Tr");
    assert_eq!(red.illum, Some(2));
    assert_eq!(red.map_kd, Some(dir.join("textures/red wood.png")));
    assert_eq!(red.ke, None);
    let glass = &m.materials[1];
    assert_eq!(glass.d, Some(0.75));
    assert_eq!(glass.tf, Some([0.9; 3]));
    assert_eq!(glass.ke, Some([1.0, 2.0, 3.0]));
    assert_eq!(glass.illum, Some(7));
    assert_eq!((glass.pr, glass.pm), (Some(0.3), Some(1.0)));
    assert_eq!((red.pr, red.pm), (None, None));
    assert_eq!(glass.map_kd, Some(PathBuf::from("/abs/tex.png")));
    let spectral = &m.materials[2];
    assert_eq!(spectral.kd, None);
    assert_eq!(spectral.d, Some(0.5));
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("scene.mtl:2: statements before the first `newmtl`")),
        "{:?}",
        m.warnings
    );
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("scene.mtl:23: `Kd` needs 1 or 3 numbers")),
        "{:?}",
        m.warnings
    );
    assert_eq!(m.warnings.len(), 2, "{:?}", m.warnings);
}

#[test]
fn all_faces_with_materials_need_no_default() {
    let dir = temp_dir("allmat");
    write(&dir, "a.mtl", "newmtl a\nKd 1 0 0\n");
    write(&dir, "b b.mtl", "newmtl b\nKd 0 1 0\nnewmtl a\nKd 0 0 1\n");
    let obj = write(
        &dir,
        "m.obj",
        &format!(
            "usemtl b\n{SQUARE}f 1 2 3\nmtllib a.mtl\nmtllib b b.mtl\nmtllib a.mtl\nusemtl a\nf 1 3 4\n"
        ),
    );
    let m = load(&obj).unwrap();
    // usemtl before mtllib works; a later `newmtl a` replaces the first one.
    assert_eq!(m.materials.len(), 2);
    assert_eq!(m.materials[0].kd, Some([0.0, 0.0, 1.0]));
    assert_eq!(m.triangle_materials, vec![1, 0]);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    // Several names on one mtllib line.
    let obj2 = write(
        &dir,
        "n.obj",
        &format!("mtllib a.mtl nothere.mtl\n{SQUARE}usemtl a\nf 1 2 3\n"),
    );
    let m = load(&obj2).unwrap();
    assert_eq!(m.triangle_materials, vec![0]);
    assert_eq!(m.warnings.len(), 1, "{:?}", m.warnings);
    assert!(
        m.warnings[0].contains("nothere.mtl` not found"),
        "{:?}",
        m.warnings
    );
}

#[test]
fn missing_mtl_and_unknown_material_are_warnings() {
    let dir = temp_dir("missingmtl");
    let obj = write(
        &dir,
        "m.obj",
        &format!("mtllib gone.mtl\n{SQUARE}usemtl wood\nf 1 2 3\n"),
    );
    let m = load(&obj).unwrap();
    assert_eq!(m.triangles.len(), 1);
    assert!(m.materials.is_empty() && m.triangle_materials.is_empty());
    assert_eq!(m.warnings.len(), 2, "{:?}", m.warnings);
    assert!(
        m.warnings[0].starts_with("line 1: MTL file `"),
        "{:?}",
        m.warnings
    );
    assert!(
        m.warnings[0].contains("gone.mtl` not found"),
        "{:?}",
        m.warnings
    );
    assert!(
        m.warnings[1].starts_with("line 6: `usemtl wood`: no such material"),
        "{:?}",
        m.warnings
    );
}

#[test]
fn many_unknown_material_names_are_summarised() {
    let mut text = SQUARE.to_string();
    for i in 0..50 {
        text.push_str(&format!("usemtl m{i}\nf 1 2 3\nusemtl\n"));
    }
    let m = parse_str(&text).unwrap();
    assert_eq!(m.triangles.len(), 50);
    assert!(m.triangle_materials.is_empty());
    assert_eq!(
        m.warnings.len(),
        1 + MAX_UNKNOWN_KINDS + 1,
        "{:?}",
        m.warnings
    );
    assert_eq!(
        m.warnings[0],
        "line 7: `usemtl` without a name; no material used"
    );
    assert_eq!(
        m.warnings.last().unwrap(),
        "42 more unknown material names used"
    );
}

#[test]
fn bad_numbers_in_mtl_name_the_mtl_file_and_line() {
    let dir = temp_dir("badmtl");
    let mtl = write(&dir, "bad.mtl", "newmtl a\nKd 1 0 0\nNs lots\n");
    let obj = write(&dir, "m.obj", &format!("mtllib bad.mtl\n{SQUARE}f 1 2 3\n"));
    let e = load(&obj).unwrap_err();
    assert_eq!(e.path, mtl);
    assert_eq!(e.line, Some(3));
    assert_eq!(e.message, "`lots` is not a number");
    write(&dir, "bad.mtl", "newmtl a\nillum -1\n");
    assert!(
        load(&obj)
            .unwrap_err()
            .message
            .contains("not a non-negative integer")
    );
    write(&dir, "bad.mtl", "newmtl a\nKd 1 nan 0\n");
    assert!(load(&obj).is_err());
}

#[test]
fn texture_options_are_skipped() {
    assert_eq!(texture_file(" a.png"), Some("a.png"));
    assert_eq!(texture_file("-s 2 a.png"), Some("a.png"));
    assert_eq!(
        texture_file("-o 1 2 3 -mm 0 1 -imfchan r my tex.png "),
        Some("my tex.png")
    );
    assert_eq!(texture_file("-s 1 1 1"), None);
    assert_eq!(texture_file(""), None);
}

#[test]
fn unreadable_and_non_utf8_files() {
    let dir = temp_dir("unreadable");
    let e = load(&dir.join("nope.obj")).unwrap_err();
    assert!(e.message.starts_with("cannot read file"), "{e}");
    let mut bytes = b"# caf\xe9 latin-1 comment\n".to_vec();
    bytes.extend_from_slice(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_eq!(
        parse(&bytes, Path::new("x.obj")).unwrap().triangles.len(),
        1
    );
}

#[test]
fn mangled_files_never_panic() {
    let base = "mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n\
                usemtl a\nf 1/1/1 2/2/1 3/1/1 4/2/1\nf -1 -2 -3\nf 1//1 2//1 4//1\nl 1 2\n";
    let alphabet = b" \n/\\#-0123456789.eEfvntl\r\t";
    let mut rng = Lcg(7);
    for _ in 0..3000 {
        let mut bytes = base.as_bytes().to_vec();
        for _ in 0..1 + rng.below(6) {
            let at = rng.below(bytes.len());
            match rng.below(3) {
                0 => bytes[at] = alphabet[rng.below(alphabet.len())],
                1 => {
                    bytes.remove(at);
                }
                _ => bytes.insert(at, alphabet[rng.below(alphabet.len())]),
            }
        }
        let _ = parse(&bytes, Path::new("/nonexistent/fuzz.obj"));
    }
}

#[test]
fn stanford_bunny() {
    let path = &Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/models/stanford-bunny.obj");
    let start = std::time::Instant::now();
    let m = load(path).unwrap();
    eprintln!(
        "bunny: {:?} (debug build), warnings {:?}",
        start.elapsed(),
        m.warnings
    );
    assert_eq!(m.positions.len(), 35947);
    assert!(m.normals.is_empty() && m.uvs.is_empty());
    // All 69451 faces of the file are proper triangles: none is dropped as degenerate.
    assert_eq!(m.triangles.len(), 69451);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

#[test]
fn spot_with_uvs() {
    let path =
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/models/spot/spot_triangulated.obj");
    let m = load(path).unwrap();
    assert_eq!(m.triangles.len(), 5856);
    assert_eq!(m.uvs.len(), m.positions.len());
    assert!(m.normals.is_empty());
    assert!(m.positions.len() >= 2930);
    // Spot's UVs stray slightly outside [0, 1] (e.g. `vt -0.00486957 0.444274`).
    assert!(m.uvs.iter().flatten().all(|c| (-0.1..=1.1).contains(c)));
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}
