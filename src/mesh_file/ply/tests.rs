//! The PLY reader's tests: one mesh written in every encoding, headers and bodies that must be
//! refused with a located message, and the properties that are read or skipped.

use super::header::Scalar;
use super::*;
use crate::mesh_file::test_util::{Lcg, temp_dir};

/// One mesh written three ways. Values are exact in f32 so every encoding agrees.
struct Sample {
    verts: Vec<[f32; 8]>,
    faces: Vec<Vec<i32>>,
}

fn sample() -> Sample {
    Sample {
        verts: vec![
            [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0],
            [1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0],
            [-0.5, 0.5, 0.25, 0.0, 1.0, 0.0, 0.5, 0.75],
        ],
        faces: vec![vec![0, 1, 2], vec![0, 2, 3, 4], vec![4, 3, 1, 0, 2]],
    }
}

const HEADER_PROPS: &str = "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
    property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n\
    property uchar red\nproperty uchar green\nproperty uchar blue\nproperty double confidence\n\
    element edge 2\nproperty list uchar int vertex_list\nproperty short kind\n\
    element face 3\nproperty list uchar int vertex_indices\nproperty float quality\n\
    element material 1\nproperty float ambient\n";

fn header(format: &str) -> String {
    format!(
        "ply\r\nformat {format} 1.0\r\ncomment made by a test\r\nobj_info nothing\n{HEADER_PROPS}end_header\n"
    )
}

fn ascii(s: &Sample) -> Vec<u8> {
    let mut out = header("ascii");
    for v in &s.verts {
        let vs: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        out.push_str(&format!("{} 200 100 50 0.5\n", vs.join(" ")));
    }
    out.push_str("3 0 1 2 7\n2 1 2 -3\n");
    for f in &s.faces {
        let is: Vec<String> = f.iter().map(|i| i.to_string()).collect();
        out.push_str(&format!("{} {} 0.5\n", f.len(), is.join(" ")));
    }
    out.push_str("0.25\n");
    out.into_bytes()
}

fn binary(s: &Sample, big: bool) -> Vec<u8> {
    let fmt = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut out = header(fmt).into_bytes();
    let f32b = |x: f32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    let i32b = |x: i32| {
        if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        }
    };
    for v in &s.verts {
        for x in v {
            out.extend_from_slice(&f32b(*x));
        }
        out.extend_from_slice(&[200, 100, 50]);
        out.extend_from_slice(&if big {
            0.5f64.to_be_bytes()
        } else {
            0.5f64.to_le_bytes()
        });
    }
    for (list, kind) in [(&[0, 1, 2][..], 7i16), (&[1, 2][..], -3)] {
        out.push(list.len() as u8);
        for i in list {
            out.extend_from_slice(&i32b(*i));
        }
        out.extend_from_slice(&if big {
            kind.to_be_bytes()
        } else {
            kind.to_le_bytes()
        });
    }
    for f in &s.faces {
        out.push(f.len() as u8);
        for i in f {
            out.extend_from_slice(&i32b(*i));
        }
        out.extend_from_slice(&f32b(0.5));
    }
    out.extend_from_slice(&f32b(0.25));
    out
}

fn parse_bytes(bytes: &[u8]) -> Result<MeshData, MeshError> {
    parse(bytes, Path::new("test.ply"))
}

#[test]
fn ascii_and_both_binary_orders_agree() {
    let s = sample();
    let a = parse_bytes(&ascii(&s)).unwrap();
    let le = parse_bytes(&binary(&s, false)).unwrap();
    let be = parse_bytes(&binary(&s, true)).unwrap();
    assert_eq!(a, le);
    assert_eq!(a, be);
    assert_eq!(a.positions.len(), 5);
    assert_eq!(a.positions[4], [-0.5, 0.5, 0.25]);
    assert_eq!(a.normals[4], [0.0, 1.0, 0.0]);
    assert_eq!(a.uvs[4], [0.5, 0.75]);
    // Fan triangulation of the quad and the pentagon: 1 + 2 + 3 triangles.
    assert_eq!(
        a.triangles,
        vec![
            [0, 1, 2],
            [0, 2, 3],
            [0, 3, 4],
            [4, 3, 1],
            [4, 1, 0],
            [4, 0, 2]
        ]
    );
    assert!(a.triangle_materials.is_empty() && a.materials.is_empty());
    assert_eq!(
        a.warnings,
        vec!["ignored elements: `edge` (2), `material` (1)"]
    );
}

#[test]
fn load_from_file_with_sized_type_names_and_faces_first() {
    let dir = temp_dir("plyfile");
    let path = dir.join("m.ply");
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement face 1\n\
        property list uint8 uint32 vertex_index\nelement vertex 3\nproperty float64 x\n\
        property int16 y\nproperty float32 z\nproperty float32 s\nproperty float32 t\nend_header\n"
        .to_vec();
    bytes.push(3);
    for i in [2u32, 1, 0] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    for (x, y, z) in [(0.0f64, 0i16, 1.0f32), (1.0, 0, 1.0), (0.0, 1, 1.0)] {
        bytes.extend_from_slice(&x.to_le_bytes());
        bytes.extend_from_slice(&y.to_le_bytes());
        bytes.extend_from_slice(&z.to_le_bytes());
        bytes.extend_from_slice(&0.5f32.to_le_bytes());
        bytes.extend_from_slice(&0.25f32.to_le_bytes());
    }
    std::fs::write(&path, &bytes).unwrap();
    let m = load(&path).unwrap();
    assert_eq!(
        m.positions,
        vec![[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]]
    );
    assert_eq!(m.triangles, vec![[2, 1, 0]]);
    assert_eq!(m.uvs, vec![[0.5, 0.25]; 3]);
    assert!(m.normals.is_empty());
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

#[test]
fn texture_u_v_names_and_point_clouds() {
    let text = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
                property float z\nproperty float texture_u\nproperty float texture_v\n\
                property float nx\nend_header\n1 2 3 0.5 0.5 1\n4 5 6 1 1 0\n";
    let m = parse_bytes(text.as_bytes()).unwrap();
    assert_eq!(m.uvs, vec![[0.5, 0.5], [1.0, 1.0]]);
    assert!(m.normals.is_empty() && m.triangles.is_empty());
    assert_eq!(m.warnings.len(), 2, "{:?}", m.warnings);
    assert!(
        m.warnings[0].contains("only some of nx, ny, nz"),
        "{:?}",
        m.warnings
    );
    assert!(
        m.warnings[1].contains("no `face` element"),
        "{:?}",
        m.warnings
    );
}

#[test]
fn truncated_binary_files_say_so() {
    let s = sample();
    let full = binary(&s, false);
    // Cut inside the faces: every element count still fits the remaining size.
    let cut = &full[..full.len() - 10];
    let e = parse_bytes(cut).unwrap_err();
    assert!(
        e.message
            .contains("file is truncated: it ends after 2 of 3 faces"),
        "{e}"
    );
    assert_eq!(e.byte_offset, Some(cut.len() as u64));
    assert_eq!(e.line, None);
    // Cut inside the vertices: caught by the size check before reading.
    let body_start = header("binary_little_endian").len();
    let e = parse_bytes(&full[..body_start + 50]).unwrap_err();
    assert!(e.message.contains("truncated"), "{e}");
    assert!(
        e.message.contains("element `vertex` declares 5 entries"),
        "{e}"
    );
    assert_eq!(e.line, Some(5));
    // ASCII too.
    let text = ascii(&s);
    let e = parse_bytes(&text[..text.len() - 30]).unwrap_err();
    assert!(
        e.message
            .contains("file is truncated: it ends after 1 of 3 faces"),
        "{e}"
    );
    assert!(e.line.is_some());
}

#[test]
fn huge_declared_counts_are_rejected_before_allocating() {
    let text = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000000\n\
                property float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0";
    let e = parse_bytes(text.as_bytes()).unwrap_err();
    assert_eq!(e.line, Some(3));
    assert!(e.message.contains("could hold at most 0"), "{e}");
    // Elements without properties take no space and are skipped instantly.
    let text = "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n\
                property float z\nelement nothing 18446744073709551615\nend_header\n";
    assert!(parse_bytes(text.as_bytes()).is_ok());
    let text = "ply\nformat ascii 1.0\nelement vertex 5000000000\nproperty float x\n\
                property float y\nproperty float z\nend_header\n";
    assert!(parse_bytes(text.as_bytes()).is_err());
}

#[test]
fn bad_indices_and_short_faces() {
    let base = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n\
                0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let e = parse_bytes(format!("{base}3 0 1 3\n").as_bytes()).unwrap_err();
    assert_eq!(e.line, Some(14));
    assert_eq!(
        e.message,
        "face 1: vertex index 3 is out of range (the file has 3 vertices)"
    );
    let e = parse_bytes(format!("{base}3 0 -1 2\n").as_bytes()).unwrap_err();
    assert!(e.message.contains("vertex index -1 is out of range"), "{e}");
    let e = parse_bytes(format!("{base}2 0 1\n").as_bytes()).unwrap_err();
    assert_eq!(e.message, "face 1 has 2 vertices; at least 3 are needed");
    let e = parse_bytes(format!("{base}3 0 x 2\n").as_bytes()).unwrap_err();
    assert_eq!(e.message, "`x` is not an integer");
    // Binary: the error gives the byte offset of the face.
    let mut bin = base
        .replace("ascii", "binary_big_endian")
        .split("end_header\n")
        .next()
        .unwrap()
        .to_string()
        .into_bytes();
    bin.extend_from_slice(b"end_header\n");
    let body = bin.len();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for x in v {
            bin.extend_from_slice(&x.to_be_bytes());
        }
    }
    for f in [[0i32, 1, 2], [0, 1, 30]] {
        bin.push(3);
        for i in f {
            bin.extend_from_slice(&i.to_be_bytes());
        }
    }
    let e = parse_bytes(&bin).unwrap_err();
    assert_eq!(e.byte_offset, Some((body + 36 + 13) as u64));
    assert!(e.message.contains("vertex index 30 is out of range"), "{e}");
    assert!(
        e.to_string()
            .starts_with(&format!("test.ply: byte {}: ", body + 49)),
        "{e}"
    );
}

#[test]
fn non_finite_coordinates_are_errors() {
    let text = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
                property float z\nend_header\n0 0 0\n0 nan 0\n";
    let e = parse_bytes(text.as_bytes()).unwrap_err();
    assert_eq!(e.line, Some(9));
    assert!(e.message.starts_with("vertex 1: position"), "{e}");
    let mut bin = b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\n\
                    property double y\nproperty double z\nend_header\n"
        .to_vec();
    let start = bin.len();
    for x in [0.0f64, 1e300, 0.0] {
        bin.extend_from_slice(&x.to_le_bytes());
    }
    let e = parse_bytes(&bin).unwrap_err();
    assert_eq!(e.byte_offset, Some(start as u64));
    assert!(e.message.contains("not finite"), "{e}");
    let e = parse_bytes(text.replace("nan", "abc").as_bytes()).unwrap_err();
    assert_eq!(
        (e.line, e.message.as_str()),
        (Some(9), "`abc` is not a number")
    );
}

#[test]
fn header_errors_name_the_line() {
    let ok = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
    assert!(parse_bytes(ok.as_bytes()).is_ok());
    let cases: [(&str, usize, &str); 9] = [
        ("", 0, "file is empty"),
        ("solid cube\n", 1, "not a PLY file"),
        (
            "ply\nformat binary_middle_endian 1.0\n",
            2,
            "unsupported format `binary_middle_endian`",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
            3,
            "has no `z` property",
        ),
        (
            "ply\nformat ascii 1.0\nproperty float x\n",
            3,
            "`property` before any `element`",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n",
            4,
            "unknown property type `quad`",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex x\n",
            3,
            "`x` is not a valid element count",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 0\n",
            3,
            "no `end_header`",
        ),
        (
            "ply\nformat ascii 1.0\nfrobnicate\nend_header\n",
            3,
            "unknown header keyword `frobnicate`",
        ),
    ];
    for (text, line, message) in cases {
        let e = parse_bytes(text.as_bytes()).unwrap_err();
        assert!(e.message.contains(message), "{text:?}: {e}");
        assert_eq!(e.line, (line > 0).then_some(line), "{text:?}: {e}");
    }
    let e = parse_bytes(b"ply\nelement vertex 0\nend_header\n").unwrap_err();
    assert!(e.message.contains("no `format` line"), "{e}");
    let e = parse_bytes(b"ply\nformat ascii 1.0\nelement face 0\nproperty list float int vertex_indices\nend_header\n")
        .unwrap_err();
    assert!(e.message.contains("length type must be an integer"), "{e}");
    let e = parse_bytes(b"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n")
        .unwrap_err();
    assert!(e.message.contains("no `vertex` element"), "{e}");
}

#[test]
fn every_scalar_type_name_is_known() {
    let names = [
        ("char", 1),
        ("int8", 1),
        ("uchar", 1),
        ("uint8", 1),
        ("short", 2),
        ("int16", 2),
        ("ushort", 2),
        ("uint16", 2),
        ("int", 4),
        ("int32", 4),
        ("uint", 4),
        ("uint32", 4),
        ("float", 4),
        ("float32", 4),
        ("double", 8),
        ("float64", 8),
    ];
    for (name, size) in names {
        assert_eq!(Scalar::parse(name).map(Scalar::size), Some(size), "{name}");
    }
    assert_eq!(Scalar::parse("int64"), None);
    // Signed and unsigned bytes read differently in a binary body.
    let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty char x\n\
        property uchar y\nproperty ushort z\nproperty short w\nend_header\n"
        .to_vec();
    bytes.extend_from_slice(&[0xff, 0xff, 0x01, 0x00, 0xff, 0xfe]);
    let m = parse_bytes(&bytes).unwrap();
    assert_eq!(m.positions, vec![[-1.0, 255.0, 256.0]]);
}

#[test]
fn trailing_data_is_a_warning() {
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n9\n";
    let m = parse_bytes(text.as_bytes()).unwrap();
    assert!(
        m.warnings
            .contains(&"line 9: data after the last element ignored".to_string()),
        "{:?}",
        m.warnings
    );
}

#[test]
fn mangled_files_never_panic() {
    let s = sample();
    let inputs = [ascii(&s), binary(&s, false), binary(&s, true)];
    let mut rng = Lcg(11);
    for round in 0..4000 {
        let mut bytes = inputs[round % 3].clone();
        for _ in 0..1 + rng.below(4) {
            if bytes.is_empty() {
                break;
            }
            let at = rng.below(bytes.len());
            match rng.below(4) {
                0 => bytes[at] = rng.next() as u8,
                1 => bytes[at] = b"0123456789 \n-"[rng.below(13)],
                2 => {
                    bytes.remove(at);
                }
                _ => bytes.truncate(at),
            }
        }
        let _ = parse_bytes(&bytes);
    }
}
