//! Wavefront OBJ meshes and their MTL material libraries.
//!
//! Supported: `v` (an optional `w` or MeshLab-style `r g b` after x y z is ignored), `vt`,
//! `vn`, `f` in all four corner forms with negative (relative) indices, polygons (fan
//! triangulated, which is right for convex ones), `usemtl`, `mtllib`, `#` comments, CRLF
//! and `\` line continuation. `o`, `g`, `s` and other grouping statements are ignored
//! silently; `l` and `p` elements and unknown statements are ignored with a warning.

use super::{MeshData, MeshError, MtlMaterial, count_of};
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};
use std::path::{Path, PathBuf};

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

/// Loads an MTL file on its own (as `mtllib` does); warnings are appended to `warnings`.
pub fn load_mtl(path: &Path, warnings: &mut Vec<String>) -> Result<Vec<MtlMaterial>, MeshError> {
    let bytes = super::read_file(path)?;
    parse_mtl(&bytes, path, warnings)
}

/// Parses MTL text held in memory; `path` names the file in messages and its folder is
/// where `map_Kd` textures are looked for. Later `newmtl` blocks with a name already used
/// are kept as separate entries here; [`parse`] lets the last one win.
pub fn parse_mtl(
    bytes: &[u8],
    path: &Path,
    warnings: &mut Vec<String>,
) -> Result<Vec<MtlMaterial>, MeshError> {
    let text = String::from_utf8_lossy(bytes);
    let dir = folder_of(path);
    let mut materials: Vec<MtlMaterial> = Vec::new();
    // `d` wins over `Tr` whatever their order, since exporters disagree on Tr's meaning.
    let mut d_given = false;
    let mut orphan_line = None;
    for_each_line(&text, |n, line| {
        let Some((keyword, rest)) = split_first(strip_comment(line)) else {
            return Ok(());
        };
        let err = |message: String| MeshError::at_line(path, n, message);
        if keyword.eq_ignore_ascii_case("newmtl") {
            let name = rest.trim_matches(|c: char| c.is_ascii_whitespace());
            if name.is_empty() {
                warnings.push(format!("{}:{n}: `newmtl` without a name", path.display()));
            }
            materials.push(MtlMaterial {
                name: name.to_string(),
                ..MtlMaterial::default()
            });
            d_given = false;
            return Ok(());
        }
        let Some(m) = materials.last_mut() else {
            orphan_line.get_or_insert(n);
            return Ok(());
        };
        let kw = keyword.to_ascii_lowercase();
        match kw.as_str() {
            "kd" | "ks" | "ke" | "tf" => {
                if let Some(c) = color(rest).map_err(err)? {
                    let slot = match kw.as_str() {
                        "kd" => &mut m.kd,
                        "ks" => &mut m.ks,
                        "ke" => &mut m.ke,
                        _ => &mut m.tf,
                    };
                    *slot = Some(c);
                } else {
                    warnings.push(format!(
                        "{}:{n}: `{keyword}` needs 1 or 3 numbers (spectral and xyz colours are not supported); ignored",
                        path.display()
                    ));
                }
            }
            "ns" | "ni" | "d" | "tr" | "pr" | "pm" => {
                // `d -halo 0.5`: the halo option is skipped.
                let value = rest
                    .split_ascii_whitespace()
                    .find(|t| !t.eq_ignore_ascii_case("-halo"));
                let Some(value) = value else {
                    warnings.push(format!(
                        "{}:{n}: `{keyword}` without a value ignored",
                        path.display()
                    ));
                    return Ok(());
                };
                let x = finite(value).map_err(err)?;
                match kw.as_str() {
                    "ns" => m.ns = Some(x),
                    "ni" => m.ni = Some(x),
                    "pr" => m.pr = Some(x),
                    "pm" => m.pm = Some(x),
                    "d" => {
                        m.d = Some(x);
                        d_given = true;
                    }
                    _ if !d_given => m.d = Some(1.0 - x),
                    _ => {}
                }
            }
            "illum" => {
                let Some(value) = rest.split_ascii_whitespace().next() else {
                    return Ok(());
                };
                let model = value
                    .parse::<u32>()
                    .ok()
                    .or_else(|| {
                        // Some exporters write `illum 2.0`.
                        let f = value.parse::<f32>().ok()?;
                        (f >= 0.0 && f.fract() == 0.0 && f < 1e6).then_some(f as u32)
                    })
                    .ok_or_else(|| err(format!("`{value}` is not a non-negative integer")))?;
                m.illum = Some(model);
            }
            "map_kd" => match texture_file(rest) {
                Some(file) => m.map_kd = Some(dir.join(file.replace('\\', "/"))),
                None => warnings.push(format!(
                    "{}:{n}: `{keyword}` without a file name ignored",
                    path.display()
                )),
            },
            _ => {} // Ka, map_Bump, refl, ... are not used by the renderer.
        }
        Ok(())
    })?;
    if let Some(n) = orphan_line {
        warnings.push(format!(
            "{}:{n}: statements before the first `newmtl` ignored",
            path.display()
        ));
    }
    Ok(materials)
}

/// `Kd r g b` or `Kd v` (grey); `None` for other forms (spectral, xyz, wrong count).
fn color(rest: &str) -> Result<Option<[f32; 3]>, String> {
    let mut tokens = rest.split_ascii_whitespace();
    let mut values = [0.0f32; 3];
    let mut given = 0;
    for (slot, token) in values.iter_mut().zip(&mut tokens) {
        if given == 0
            && (token.eq_ignore_ascii_case("spectral") || token.eq_ignore_ascii_case("xyz"))
        {
            return Ok(None);
        }
        *slot = finite(token)?;
        given += 1;
    }
    Ok(match given {
        1 => Some([values[0]; 3]),
        3 => Some(values),
        _ => None,
    })
}

/// The file name of a texture statement, after its options (`-s 1 1 1`, `-bm 0.5`, ...).
/// The rest of the line is one name, so names with spaces work.
fn texture_file(rest: &str) -> Option<&str> {
    let mut rest = rest;
    loop {
        let (token, after) = split_first(rest)?;
        if !token.starts_with('-') {
            return Some(rest.trim_matches(|c: char| c.is_ascii_whitespace()));
        }
        rest = after;
        // How many numeric arguments the option may take (at most).
        let (numeric, max_args) = match token.to_ascii_lowercase().as_str() {
            "-o" | "-s" | "-t" => (true, 3),
            "-mm" => (true, 2),
            "-blendu" | "-blendv" | "-cc" | "-clamp" | "-boost" | "-texres" | "-bm"
            | "-imfchan" | "-type" => (false, 1),
            _ => (false, 0),
        };
        for _ in 0..max_args {
            match split_first(rest) {
                Some((arg, after)) if !numeric || arg.parse::<f32>().is_ok() => rest = after,
                _ => break,
            }
        }
    }
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

    fn finish(mut self) -> Result<MeshData, MeshError> {
        let counts = [
            self.positions.len(),
            self.texcoords.len(),
            self.normals.len(),
        ];
        for kind in [Kind::Vertex, Kind::TexCoord, Kind::Normal] {
            if let Some((max, line)) = self.forward[kind as usize]
                && max as usize >= counts[kind as usize]
            {
                let count = counts[kind as usize];
                return Err(self.err(
                    line,
                    format!(
                        "{} index {} is out of range: the file has {}",
                        kind.name(),
                        u64::from(max) + 1,
                        if count == 0 {
                            format!("no {}", kind.plural())
                        } else {
                            format!("only {}", count_of(count, kind.name(), kind.plural()))
                        }
                    ),
                ));
            }
        }
        let mut warnings = std::mem::take(&mut self.warnings);
        self.summarise_ignored(&mut warnings);
        let mut mesh = self.build(&mut warnings)?;
        self.assign_materials(&mut mesh, &mut warnings);
        mesh.warnings = warnings;
        mesh.unread_mtl = std::mem::take(&mut self.unread_mtl);
        mesh.mtl_files = self.loaded_mtl.iter().cloned().collect();
        mesh.mtl_files.sort();
        super::drop_degenerate(&mut mesh);
        Ok(mesh)
    }

    fn summarise_ignored(&self, warnings: &mut Vec<String>) {
        for ((count, line), what) in [
            (self.lines_ignored, "line (`l`) element"),
            (self.points_ignored, "point (`p`) element"),
        ] {
            if count > 0 {
                let s = if count == 1 { "" } else { "s" };
                warnings.push(format!(
                    "ignored {count} {what}{s} (first on line {line}); only faces are rendered"
                ));
            }
        }
        for (keyword, line, count) in &self.unknown {
            let times = if *count > 1 {
                format!(" ({count} times)")
            } else {
                String::new()
            };
            warnings.push(format!(
                "line {line}: unknown statement `{keyword}` ignored{times}"
            ));
        }
        if self.unknown_other > 0 {
            warnings.push(format!(
                "{} other unknown statements ignored",
                self.unknown_other
            ));
        }
    }

    /// Turns file-index triangles into output vertices: positions as they are when faces
    /// use positions only, otherwise one vertex per distinct (v, vt, vn) triple.
    fn build(&mut self, warnings: &mut Vec<String>) -> Result<MeshData, MeshError> {
        let tri_v = std::mem::take(&mut self.tri_v);
        if !self.any_vt && !self.any_vn {
            return Ok(MeshData {
                positions: std::mem::take(&mut self.positions),
                triangles: tri_v,
                ..MeshData::default()
            });
        }
        let (want_vt, want_vn) = (self.any_vt, self.any_vn);
        let corner_count = tri_v.len() * 3;
        let mut map: HashMap<(u32, u32, u32), u32, BuildHasherDefault<FxHasher>> =
            HashMap::with_capacity_and_hasher(corner_count.min(1 << 20), Default::default());
        let mut positions = Vec::with_capacity(corner_count.min(1 << 20) / 2);
        let mut uvs = Vec::new();
        let mut normals = Vec::new();
        let mut triangles = Vec::with_capacity(tri_v.len());
        let (mut missing_vt, mut missing_vn) = (0usize, 0usize);
        for (t, v) in tri_v.iter().enumerate() {
            let vt = self.tri_vt.get(t).copied().unwrap_or([NONE; 3]);
            let vn = self.tri_vn.get(t).copied().unwrap_or([NONE; 3]);
            let mut out = [0u32; 3];
            for (k, slot) in out.iter_mut().enumerate() {
                let key = (v[k], vt[k], vn[k]);
                if let Some(&i) = map.get(&key) {
                    *slot = i;
                    continue;
                }
                let Ok(i) = u32::try_from(positions.len()) else {
                    return Err(MeshError::new(self.path, "too many distinct vertices"));
                };
                positions.push(
                    self.positions
                        .get(key.0 as usize)
                        .copied()
                        .unwrap_or_default(),
                );
                if want_vt {
                    let uv = self.texcoords.get(key.1 as usize).copied();
                    missing_vt += usize::from(uv.is_none());
                    uvs.push(uv.unwrap_or_default());
                }
                if want_vn {
                    let n = self.normals.get(key.2 as usize).copied();
                    missing_vn += usize::from(n.is_none());
                    normals.push(n.unwrap_or_default());
                }
                map.insert(key, i);
                *slot = i;
            }
            triangles.push(out);
        }
        if missing_vt > 0 {
            warnings.push(format!(
                "{} no texture coordinates while others have; they were given (0, 0)",
                count_of(missing_vt, "vertex has", "vertices have")
            ));
        }
        if missing_vn > 0 {
            warnings.push(format!(
                "{} no normal while others have; their normals were set to zero",
                count_of(missing_vn, "vertex has", "vertices have")
            ));
        }
        Ok(MeshData {
            positions,
            normals,
            uvs,
            triangles,
            ..MeshData::default()
        })
    }

    fn assign_materials(&mut self, mesh: &mut MeshData, warnings: &mut Vec<String>) {
        mesh.materials = std::mem::take(&mut self.materials);
        if self.tri_mat.is_empty() {
            return;
        }
        let mut unknown = 0usize;
        let resolved: Vec<u32> = self
            .used_names
            .iter()
            .map(|(name, line)| match self.material_lookup.get(name) {
                Some(&i) => i,
                None => {
                    unknown += 1;
                    // Name a few; a file with thousands of unknown names gets one more line.
                    if unknown <= MAX_UNKNOWN_KINDS {
                        warnings.push(format!(
                            "line {line}: `usemtl {name}`: no such material in the loaded MTL \
                             files; its faces get no material"
                        ));
                    }
                    NONE
                }
            })
            .collect();
        if unknown > MAX_UNKNOWN_KINDS {
            warnings.push(format!(
                "{} more unknown material names used",
                unknown - MAX_UNKNOWN_KINDS
            ));
        }
        let mut per_triangle: Vec<u32> = self
            .tri_mat
            .iter()
            .map(|&u| resolved.get(u as usize).copied().unwrap_or(NONE))
            .collect();
        if per_triangle.iter().all(|&m| m == NONE) {
            return;
        }
        if per_triangle.contains(&NONE) {
            let default = mesh.materials.len() as u32;
            mesh.materials.push(MtlMaterial {
                name: NO_MATERIAL_NAME.to_string(),
                ..MtlMaterial::default()
            });
            for m in per_triangle.iter_mut().filter(|m| **m == NONE) {
                *m = default;
            }
        }
        mesh.triangle_materials = per_triangle;
    }
}

fn count_ignored(slot: &mut (usize, usize), line: usize) {
    if slot.0 == 0 {
        slot.1 = line;
    }
    slot.0 += 1;
}

/// The folder relative file names are resolved against (`.` for a bare file name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn number(token: &str) -> Result<f32, String> {
    token
        .parse::<f32>()
        .map_err(|_| format!("`{token}` is not a number"))
}

fn finite(token: &str) -> Result<f32, String> {
    let x = number(token)?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("`{token}` is not a finite number"))
    }
}

/// The first whitespace-separated word of `s` and everything after it.
fn split_first(s: &str) -> Option<(&str, &str)> {
    let s = s.trim_start_matches(|c: char| c.is_ascii_whitespace());
    if s.is_empty() {
        return None;
    }
    let end = s.find(|c: char| c.is_ascii_whitespace()).unwrap_or(s.len());
    Some(s.split_at(end))
}

/// Cuts a `#` comment: at the start of the line or after whitespace, so that file names
/// such as `part#2.mtl` survive.
fn strip_comment(line: &str) -> &str {
    let bytes = line.as_bytes();
    let mut from = 0;
    while let Some(i) = bytes
        .get(from..)
        .and_then(|b| b.iter().position(|&c| c == b'#'))
    {
        let at = from + i;
        if at == 0 || bytes.get(at - 1).is_some_and(u8::is_ascii_whitespace) {
            return line.get(..at).unwrap_or(line);
        }
        from = at + 1;
    }
    line
}

/// Calls `f` with each logical line and the number of its first physical line. CR before
/// LF is dropped, and a line ending in `\` is joined with the next (except in comments,
/// where a trailing backslash is just text).
fn for_each_line<E>(text: &str, mut f: impl FnMut(usize, &str) -> Result<(), E>) -> Result<(), E> {
    let mut joined = String::new();
    let mut joined_from = None;
    for (i, raw) in text.split('\n').enumerate() {
        let n = i + 1;
        let raw = raw.strip_suffix('\r').unwrap_or(raw);
        let head = raw.trim_end_matches(|c: char| c.is_ascii_whitespace());
        if let Some(head) = head.strip_suffix('\\')
            && (joined_from.is_some() || !raw.trim_start().starts_with('#'))
        {
            if joined_from.is_none() {
                joined_from = Some(n);
                joined.clear();
            }
            joined.push_str(head);
            joined.push(' ');
            continue;
        }
        match joined_from.take() {
            Some(first) => {
                joined.push_str(raw);
                f(first, &joined)?;
            }
            None => f(n, raw)?,
        }
    }
    if let Some(first) = joined_from {
        f(first, &joined)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
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
            &format!(
                "mtllib scene.mtl\n{SQUARE}f 1 2 3\nusemtl glass\nf 1 3 4\nusemtl red\nf 1 2 4\n"
            ),
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
}
