//! Wavefront OBJ meshes and their MTL material libraries.
//!
//! Supported: `v` (an optional `w` or MeshLab-style `r g b` after x y z is ignored), `vt`,
//! `vn`, `f` in all four corner forms with negative (relative) indices, polygons (fan
//! triangulated, which is right for convex ones), `usemtl`, `mtllib`, `#` comments, CRLF
//! and `\` line continuation. `o`, `g`, `s` and other grouping statements are ignored
//! silently; `l` and `p` elements and unknown statements are ignored with a warning.

mod build;
mod mtl;
#[cfg(test)]
mod tests;
mod text;

pub use mtl::{load_mtl, parse_mtl};

use super::{MeshData, MeshError, MtlMaterial, count_of};
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};
use std::path::{Path, PathBuf};
use text::*;

/// Marks a missing `vt` or `vn` in a face corner, or a triangle without a material.
const NONE: u32 = u32::MAX;

/// Name of the material added for triangles that have none when others do.
pub const NO_MATERIAL_NAME: &str = "(none)";

/// Loads an OBJ file and the MTL files it names.
pub fn load(path: &Path) -> Result<MeshData, MeshError> {
    let bytes = super::read_file(path)?;
    parse(&bytes, path)
}

/// Parses OBJ text held in memory. `path` is used in messages and to find `mtllib` files
/// (relative to its folder). Bytes that are not UTF-8 are replaced, not rejected.
pub fn parse(bytes: &[u8], path: &Path) -> Result<MeshData, MeshError> {
    let text = String::from_utf8_lossy(bytes);
    let mut parser = Parser::new(path);
    for_each_line(&text, |line_no, line| parser.line(line_no, line))?;
    parser.finish()
}

/// Cheap hasher for the (v, vt, vn) dedupe map; the keys are small integers, not
/// attacker-chosen strings, so SipHash's DoS resistance buys nothing here.
#[derive(Default, Clone, Copy)]
struct FxHasher(u64);

impl Hasher for FxHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u32(u32::from(b));
        }
    }

    fn write_u32(&mut self, n: u32) {
        self.0 = (self.0.rotate_left(5) ^ u64::from(n)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Vertex = 0,
    TexCoord = 1,
    Normal = 2,
}

impl Kind {
    fn name(self) -> &'static str {
        ["vertex", "texture coordinate", "normal"][self as usize]
    }

    fn plural(self) -> &'static str {
        ["vertices", "texture coordinates", "normals"][self as usize]
    }
}

/// How many kinds of unknown statement get their own warning before the rest are lumped.
const MAX_UNKNOWN_KINDS: usize = 8;

struct Parser<'p> {
    path: &'p Path,
    dir: PathBuf,
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    normals: Vec<[f32; 3]>,
    /// File indices (0-based) per triangle; `tri_vt`/`tri_vn` stay empty until a face
    /// uses them, so position-only files never pay for them.
    tri_v: Vec<[u32; 3]>,
    tri_vt: Vec<[u32; 3]>,
    tri_vn: Vec<[u32; 3]>,
    any_vt: bool,
    any_vn: bool,
    /// Per triangle index into `used_names`; empty until the first `usemtl`.
    tri_mat: Vec<u32>,
    any_usemtl: bool,
    nameless_usemtl: bool,
    current: u32,
    /// Scratch for one face's corners, reused to avoid per-line allocation.
    corners: Vec<[u32; 3]>,
    /// Largest forward reference per kind (0-based index, line), checked at the end.
    forward: [Option<(u32, usize)>; 3],
    used_names: Vec<(String, usize)>,
    used_lookup: HashMap<String, u32>,
    materials: Vec<MtlMaterial>,
    material_lookup: HashMap<String, u32>,
    loaded_mtl: HashSet<PathBuf>,
    unread_mtl: Vec<String>,
    warnings: Vec<String>,
    unknown: Vec<(String, usize, usize)>,
    unknown_other: usize,
    lines_ignored: (usize, usize),
    points_ignored: (usize, usize),
}

impl<'p> Parser<'p> {
    fn new(path: &'p Path) -> Self {
        Parser {
            path,
            dir: folder_of(path),
            positions: Vec::new(),
            texcoords: Vec::new(),
            normals: Vec::new(),
            tri_v: Vec::new(),
            tri_vt: Vec::new(),
            tri_vn: Vec::new(),
            any_vt: false,
            any_vn: false,
            tri_mat: Vec::new(),
            any_usemtl: false,
            nameless_usemtl: false,
            current: NONE,
            corners: Vec::new(),
            forward: [None; 3],
            used_names: Vec::new(),
            used_lookup: HashMap::new(),
            materials: Vec::new(),
            material_lookup: HashMap::new(),
            loaded_mtl: HashSet::new(),
            unread_mtl: Vec::new(),
            warnings: Vec::new(),
            unknown: Vec::new(),
            unknown_other: 0,
            lines_ignored: (0, 0),
            points_ignored: (0, 0),
        }
    }

    fn err(&self, line: usize, message: impl Into<String>) -> MeshError {
        MeshError::at_line(self.path, line, message)
    }

    fn line(&mut self, n: usize, line: &str) -> Result<(), MeshError> {
        let Some((keyword, rest)) = split_first(strip_comment(line)) else {
            return Ok(());
        };
        match keyword {
            "v" => {
                let mut tokens = rest.split_ascii_whitespace();
                let p = self.numbers::<3>(n, "v", &mut tokens)?;
                // `w`, or MeshLab's `r g b`: checked to be numbers, then ignored.
                for t in tokens {
                    number(t).map_err(|m| self.err(n, m))?;
                }
                self.positions.push(p);
            }
            "vt" => {
                let mut tokens = rest.split_ascii_whitespace();
                let [u] = self.numbers::<1>(n, "vt", &mut tokens)?;
                let v = match tokens.next() {
                    Some(t) => finite(t).map_err(|m| self.err(n, m))?,
                    None => 0.0,
                };
                self.texcoords.push([u, v]);
            }
            "vn" => {
                let p = self.numbers::<3>(n, "vn", &mut rest.split_ascii_whitespace())?;
                self.normals.push(p);
            }
            "f" | "fo" => self.face(n, rest)?,
            "o" | "g" | "s" | "mg" | "lod" | "shadow_obj" | "trace_obj" | "usemap" | "maplib"
            | "bevel" | "c_interp" | "d_interp" => {}
            "l" => count_ignored(&mut self.lines_ignored, n),
            "p" => count_ignored(&mut self.points_ignored, n),
            "usemtl" => self.usemtl(n, rest),
            "mtllib" => self.mtllib(n, rest)?,
            other => self.unknown_statement(n, other),
        }
        Ok(())
    }

    /// Reads exactly `N` finite numbers from `tokens`.
    fn numbers<'a, const N: usize>(
        &self,
        n: usize,
        keyword: &str,
        tokens: &mut impl Iterator<Item = &'a str>,
    ) -> Result<[f32; N], MeshError> {
        let mut out = [0.0f32; N];
        for (i, slot) in out.iter_mut().enumerate() {
            let Some(token) = tokens.next() else {
                return Err(self.err(n, format!("`{keyword}` needs {N} numbers, found {i}")));
            };
            *slot = finite(token).map_err(|m| self.err(n, m))?;
        }
        Ok(out)
    }

    fn face(&mut self, n: usize, rest: &str) -> Result<(), MeshError> {
        self.corners.clear();
        let (mut has_vt, mut has_vn) = (false, false);
        for token in rest.split_ascii_whitespace() {
            let mut parts = token.split('/');
            let v = parts.next().unwrap_or("");
            let vt = parts.next().unwrap_or("");
            let vn = parts.next().unwrap_or("");
            if v.is_empty() || parts.next().is_some() {
                return Err(self.err(n, format!("`{token}` is not a valid face vertex")));
            }
            let v = self.index(n, v, Kind::Vertex)?;
            let vt = if vt.is_empty() {
                NONE
            } else {
                has_vt = true;
                self.index(n, vt, Kind::TexCoord)?
            };
            let vn = if vn.is_empty() {
                NONE
            } else {
                has_vn = true;
                self.index(n, vn, Kind::Normal)?
            };
            self.corners.push([v, vt, vn]);
        }
        let count = self.corners.len();
        if count < 3 {
            return Err(self.err(
                n,
                format!("face has {count} vertices; at least 3 are needed"),
            ));
        }
        // Start the optional streams only when first needed, back-filled with NONE.
        if has_vt && !self.any_vt {
            self.any_vt = true;
            self.tri_vt.resize(self.tri_v.len(), [NONE; 3]);
        }
        if has_vn && !self.any_vn {
            self.any_vn = true;
            self.tri_vn.resize(self.tri_v.len(), [NONE; 3]);
        }
        let (want_vt, want_vn) = (self.any_vt, self.any_vn);
        let Some((&first, rest)) = self.corners.split_first() else {
            return Ok(());
        };
        for pair in rest.windows(2) {
            let [b, c] = [pair[0], pair[1]];
            self.tri_v.push([first[0], b[0], c[0]]);
            if want_vt {
                self.tri_vt.push([first[1], b[1], c[1]]);
            }
            if want_vn {
                self.tri_vn.push([first[2], b[2], c[2]]);
            }
            if self.any_usemtl {
                self.tri_mat.push(self.current);
            }
        }
        Ok(())
    }

    /// Resolves a 1-based or negative (relative) index to a 0-based one. Positive indices
    /// past the current count are allowed here and checked at the end of the file.
    fn index(&mut self, n: usize, text: &str, kind: Kind) -> Result<u32, MeshError> {
        let Ok(i) = text.parse::<i64>() else {
            return Err(self.err(n, format!("`{text}` is not a valid index")));
        };
        let count = match kind {
            Kind::Vertex => self.positions.len(),
            Kind::TexCoord => self.texcoords.len(),
            Kind::Normal => self.normals.len(),
        };
        match i {
            0 => Err(self.err(
                n,
                format!(
                    "{} index 0 is invalid (OBJ indices start at 1)",
                    kind.name()
                ),
            )),
            i if i > 0 => {
                let Ok(zero_based) = u32::try_from(i - 1) else {
                    return Err(self.err(n, format!("{} index {i} is too large", kind.name())));
                };
                if zero_based == NONE {
                    return Err(self.err(n, format!("{} index {i} is too large", kind.name())));
                }
                if zero_based as usize >= count {
                    let slot = &mut self.forward[kind as usize];
                    if slot.is_none_or(|(max, _)| zero_based > max) {
                        *slot = Some((zero_based, n));
                    }
                }
                Ok(zero_based)
            }
            i => {
                let resolved = i64::try_from(count).unwrap_or(i64::MAX).saturating_add(i);
                u32::try_from(resolved).map_err(|_| {
                    self.err(
                        n,
                        format!(
                            "relative {} index {i} points before the first one (only {} so far)",
                            kind.name(),
                            count_of(count, kind.name(), kind.plural())
                        ),
                    )
                })
            }
        }
    }

    fn usemtl(&mut self, n: usize, rest: &str) {
        let name = rest.trim_matches(|c: char| c.is_ascii_whitespace());
        if !self.any_usemtl {
            self.any_usemtl = true;
            self.tri_mat.resize(self.tri_v.len(), NONE);
        }
        if name.is_empty() {
            if !self.nameless_usemtl {
                self.nameless_usemtl = true;
                self.warnings.push(format!(
                    "line {n}: `usemtl` without a name; no material used"
                ));
            }
            self.current = NONE;
            return;
        }
        self.current = match self.used_lookup.get(name) {
            Some(&i) => i,
            None => {
                let i = self.used_names.len() as u32;
                self.used_names.push((name.to_string(), n));
                self.used_lookup.insert(name.to_string(), i);
                i
            }
        };
    }

    fn mtllib(&mut self, n: usize, rest: &str) -> Result<(), MeshError> {
        let rest = rest.trim_matches(|c: char| c.is_ascii_whitespace());
        if rest.is_empty() {
            self.warnings
                .push(format!("line {n}: `mtllib` without a file name ignored"));
            return Ok(());
        }
        // The whole rest of the line first (names with spaces), then each word.
        let whole = self.dir.join(rest.replace('\\', "/"));
        if whole.is_file() {
            return self.load_mtl(n, whole);
        }
        for name in rest.split_ascii_whitespace() {
            let file = self.dir.join(name.replace('\\', "/"));
            self.load_mtl(n, file)?;
        }
        Ok(())
    }

    fn load_mtl(&mut self, n: usize, file: PathBuf) -> Result<(), MeshError> {
        // Some exporters repeat `mtllib` per object; read each file once.
        if !self.loaded_mtl.insert(file.clone()) {
            return Ok(());
        }
        let bytes = match crate::read_regular_file(&file) {
            Ok(bytes) => bytes,
            Err(e) => {
                let why = if e.kind() == std::io::ErrorKind::NotFound {
                    "not found".to_string()
                } else {
                    format!("cannot be read ({e})")
                };
                self.warnings.push(format!(
                    "line {n}: MTL file `{}` {why}; its materials are not available",
                    file.display()
                ));
                self.unread_mtl.push(format!("`{}` {why}", file.display()));
                return Ok(());
            }
        };
        for m in parse_mtl(&bytes, &file, &mut self.warnings)? {
            match self.material_lookup.get(&m.name) {
                // A later definition of a name replaces the earlier one.
                Some(&i) => {
                    if let Some(slot) = self.materials.get_mut(i as usize) {
                        *slot = m;
                    }
                }
                None => {
                    self.material_lookup
                        .insert(m.name.clone(), self.materials.len() as u32);
                    self.materials.push(m);
                }
            }
        }
        Ok(())
    }

    fn unknown_statement(&mut self, n: usize, keyword: &str) {
        if let Some(entry) = self.unknown.iter_mut().find(|(k, _, _)| k == keyword) {
            entry.2 += 1;
        } else if self.unknown.len() < MAX_UNKNOWN_KINDS && keyword.len() <= 32 {
            self.unknown.push((keyword.to_string(), n, 1));
        } else {
            self.unknown_other += 1;
        }
    }
}
