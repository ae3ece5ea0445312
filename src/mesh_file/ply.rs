//! Stanford PLY meshes: ASCII and binary (either byte order).
//!
//! Reads the `vertex` element's `x y z`, `nx ny nz` and texture coordinates (`u v`,
//! `s t`, `texture_u texture_v` or `texture_s texture_t`) and the `face` element's
//! `vertex_indices` (or `vertex_index`) list; polygons are fan triangulated. Other
//! properties (colours, confidence, ...) and other elements (edges, materials, ...) are
//! skipped. Header and ASCII errors name a line, binary errors a byte offset.

use super::{MeshData, MeshError, capped, count_of};
use std::path::Path;

/// Loads a PLY file.
pub fn load(path: &Path) -> Result<MeshData, MeshError> {
    let bytes = super::read_file(path)?;
    parse(&bytes, path)
}

/// Parses a PLY file held in memory; `path` is used in messages only.
pub fn parse(bytes: &[u8], path: &Path) -> Result<MeshData, MeshError> {
    let header = parse_header(bytes, path)?;
    let body = bytes.get(header.body_start..).unwrap_or_default();
    check_counts(&header, body.len(), path)?;
    let plan = Plan::new(&header, path)?;
    let mut mesh = match header.format {
        Format::Ascii => read_body(
            &mut Ascii {
                data: body,
                pos: 0,
                line: header.lines + 1,
                path,
            },
            &header,
            &plan,
        )?,
        Format::BinaryLe => read_body(
            &mut Binary::<false>::new(body, &header, path),
            &header,
            &plan,
        )?,
        Format::BinaryBe => read_body(
            &mut Binary::<true>::new(body, &header, path),
            &header,
            &plan,
        )?,
    };
    let mut warnings = header.warnings;
    warnings.extend(plan.warnings);
    warnings.append(&mut mesh.warnings);
    mesh.warnings = warnings;
    super::drop_degenerate(&mut mesh);
    Ok(mesh)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Ascii,
    BinaryLe,
    BinaryBe,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> u64 {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_int(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug)]
enum Ty {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: String,
    ty: Ty,
    line: usize,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
    line: usize,
}

impl Element {
    /// "vertices", "faces", "`edge` elements": for truncation messages.
    fn plural(&self) -> String {
        match self.name.as_str() {
            "vertex" => "vertices".to_string(),
            "face" => "faces".to_string(),
            other => format!("`{other}` elements"),
        }
    }

    /// The fewest body bytes one entry can take (lists may be empty).
    fn min_size(&self, format: Format) -> u64 {
        self.props
            .iter()
            .map(|p| match (format, p.ty) {
                // A token and a separator.
                (Format::Ascii, _) => 2,
                (_, Ty::Scalar(s)) => s.size(),
                (_, Ty::List { count, .. }) => count.size(),
            })
            .sum()
    }
}

struct Header {
    format: Format,
    elements: Vec<Element>,
    body_start: usize,
    /// Number of header lines, `end_header` included.
    lines: usize,
    warnings: Vec<String>,
}

fn parse_header(bytes: &[u8], path: &Path) -> Result<Header, MeshError> {
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut warnings = Vec::new();
    let mut pos = 0usize;
    let mut n = 0usize;
    loop {
        let Some(rest) = bytes.get(pos..).filter(|r| !r.is_empty()) else {
            return Err(if n == 0 {
                MeshError::new(path, "file is empty")
            } else {
                MeshError::at_line(path, n, "header has no `end_header` line")
            });
        };
        let (raw, next) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (rest.get(..i).unwrap_or_default(), pos + i + 1),
            None => (rest, bytes.len()),
        };
        n += 1;
        pos = next;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        let err = |message: String| MeshError::at_line(path, n, message);
        if n == 1 {
            if raw.trim_ascii() != b"ply" {
                return Err(err("not a PLY file (the first line is not `ply`)".into()));
            }
            continue;
        }
        let text = String::from_utf8_lossy(raw);
        let mut tokens = text.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        match keyword {
            "format" => {
                let name = tokens.next().unwrap_or("");
                format = Some(match name {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::BinaryLe,
                    "binary_big_endian" => Format::BinaryBe,
                    _ => {
                        return Err(err(format!(
                            "unsupported format `{name}` (expected ascii, \
                             binary_little_endian or binary_big_endian)"
                        )));
                    }
                });
                let version = tokens.next().unwrap_or("");
                if version != "1.0" && version != "1" {
                    warnings.push(format!(
                        "line {n}: format version `{version}` is not 1.0; read as 1.0"
                    ));
                }
            }
            "comment" | "obj_info" => {}
            "element" => {
                let (Some(name), Some(count)) = (tokens.next(), tokens.next()) else {
                    return Err(err("`element` needs a name and a count".into()));
                };
                let count = count
                    .parse::<u64>()
                    .map_err(|_| err(format!("`{count}` is not a valid element count")))?;
                if elements.iter().any(|e| e.name == name) {
                    return Err(err(format!("element `{name}` is declared twice")));
                }
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    props: Vec::new(),
                    line: n,
                });
            }
            "property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(err("`property` before any `element`".into()));
                };
                let scalar = |name: Option<&str>| {
                    let name = name.unwrap_or("");
                    Scalar::parse(name)
                        .ok_or_else(|| err(format!("unknown property type `{name}`")))
                };
                let first = tokens.next();
                let ty = if first == Some("list") {
                    let count = scalar(tokens.next())?;
                    let item = scalar(tokens.next())?;
                    if !count.is_int() {
                        return Err(err("a list's length type must be an integer type".into()));
                    }
                    Ty::List { count, item }
                } else {
                    Ty::Scalar(scalar(first)?)
                };
                let Some(name) = tokens.next() else {
                    return Err(err("`property` needs a name".into()));
                };
                element.props.push(Property {
                    name: name.to_string(),
                    ty,
                    line: n,
                });
            }
            "end_header" => break,
            other => return Err(err(format!("unknown header keyword `{other}`"))),
        }
    }
    let Some(format) = format else {
        return Err(MeshError::at_line(path, n, "header has no `format` line"));
    };
    Ok(Header {
        format,
        elements,
        body_start: pos,
        lines: n,
        warnings,
    })
}

/// Rejects counts the body could not hold before anything is allocated for them.
fn check_counts(header: &Header, body_len: usize, path: &Path) -> Result<(), MeshError> {
    for el in &header.elements {
        let min = el.min_size(header.format);
        if min == 0 {
            continue;
        }
        // ASCII: the last token needs no separator after it.
        let room = body_len as u128 + u128::from(header.format == Format::Ascii);
        if u128::from(el.count) * u128::from(min) > room {
            return Err(MeshError::at_line(
                path,
                el.line,
                format!(
                    "element `{}` declares {} entries, but the {body_len} bytes after the \
                     header could hold at most {} (each takes at least {min} bytes): the file \
                     is truncated or the header is wrong",
                    el.name,
                    el.count,
                    room / u128::from(min)
                ),
            ));
        }
    }
    Ok(())
}

/// Slots of the values kept per vertex.
const X: usize = 0;
const NX: usize = 3;
const U: usize = 6;

/// What to do with each element, worked out from the header.
struct Plan {
    vertex: usize,
    /// Per vertex property: the slot (0..8, see `X`, `NX`, `U`) its value goes to.
    roles: Vec<Option<usize>>,
    normals: bool,
    uvs: bool,
    vertex_count: u32,
    /// The face element and the position of its index list among its properties.
    face: Option<(usize, usize)>,
    warnings: Vec<String>,
}

impl Plan {
    fn new(header: &Header, path: &Path) -> Result<Plan, MeshError> {
        let elements = &header.elements;
        let Some(vertex) = elements.iter().position(|e| e.name == "vertex") else {
            return Err(MeshError::at_line(
                path,
                header.lines,
                "the header declares no `vertex` element",
            ));
        };
        let el = elements
            .get(vertex)
            .ok_or_else(|| MeshError::new(path, "internal: vertex element"))?;
        let vertex_count = u32::try_from(el.count).map_err(|_| {
            MeshError::at_line(
                path,
                el.line,
                format!(
                    "{} vertices are more than 32-bit indices can address",
                    el.count
                ),
            )
        })?;
        let mut warnings = Vec::new();
        let mut roles = vec![None; el.props.len()];
        // Finds a scalar property, giving it `slot` (first one wins for duplicates).
        let find =
            |name: &str, slot: usize, roles: &mut Vec<Option<usize>>| -> Result<bool, MeshError> {
                let Some(i) = el.props.iter().position(|p| p.name == name) else {
                    return Ok(false);
                };
                let prop = el
                    .props
                    .get(i)
                    .ok_or_else(|| MeshError::new(path, "internal: property"))?;
                if matches!(prop.ty, Ty::List { .. }) {
                    return Err(MeshError::at_line(
                        path,
                        prop.line,
                        format!("vertex property `{name}` is a list, not a number"),
                    ));
                }
                if let Some(r) = roles.get_mut(i) {
                    *r = Some(slot);
                }
                Ok(true)
            };
        for (k, name) in ["x", "y", "z"].into_iter().enumerate() {
            if !find(name, X + k, &mut roles)? {
                return Err(MeshError::at_line(
                    path,
                    el.line,
                    format!("the `vertex` element has no `{name}` property"),
                ));
            }
        }
        let mut normal_roles = roles.clone();
        let mut found = 0;
        for (k, name) in ["nx", "ny", "nz"].into_iter().enumerate() {
            found += usize::from(find(name, NX + k, &mut normal_roles)?);
        }
        let normals = found == 3;
        if normals {
            roles = normal_roles;
        } else if found > 0 {
            warnings.push(format!(
                "line {}: the `vertex` element has only some of nx, ny, nz; normals ignored",
                el.line
            ));
        }
        let mut uvs = false;
        for [u, v] in [
            ["u", "v"],
            ["s", "t"],
            ["texture_u", "texture_v"],
            ["texture_s", "texture_t"],
        ] {
            let mut uv_roles = roles.clone();
            if find(u, U, &mut uv_roles)? && find(v, U + 1, &mut uv_roles)? {
                roles = uv_roles;
                uvs = true;
                break;
            }
        }
        let mut face = None;
        if let Some(fi) = elements.iter().position(|e| e.name == "face") {
            let fel = elements
                .get(fi)
                .ok_or_else(|| MeshError::new(path, "internal: face element"))?;
            let Some(pi) = fel
                .props
                .iter()
                .position(|p| p.name == "vertex_indices" || p.name == "vertex_index")
            else {
                return Err(MeshError::at_line(
                    path,
                    fel.line,
                    "the `face` element has no `vertex_indices` list",
                ));
            };
            let prop = fel
                .props
                .get(pi)
                .ok_or_else(|| MeshError::new(path, "internal: face property"))?;
            match prop.ty {
                Ty::List { item, .. } if item.is_int() => {}
                Ty::List { .. } => {
                    return Err(MeshError::at_line(
                        path,
                        prop.line,
                        format!("`{}` must hold integers", prop.name),
                    ));
                }
                Ty::Scalar(_) => {
                    return Err(MeshError::at_line(
                        path,
                        prop.line,
                        format!("`{}` must be a list", prop.name),
                    ));
                }
            }
            face = Some((fi, pi));
        } else {
            warnings
                .push("the file has no `face` element (a point cloud?); no triangles".to_string());
        }
        let ignored: Vec<String> = elements
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != vertex && face.is_none_or(|(f, _)| f != *i))
            .map(|(_, e)| format!("`{}` ({})", e.name, e.count))
            .collect();
        if !ignored.is_empty() {
            warnings.push(format!("ignored elements: {}", ignored.join(", ")));
        }
        Ok(Plan {
            vertex,
            roles,
            normals,
            uvs,
            vertex_count,
            face,
            warnings,
        })
    }
}

/// Where in the file something is: a line (ASCII) or a byte offset (binary).
#[derive(Clone, Copy)]
enum Loc {
    Line(usize),
    Byte(u64),
}

fn error_at(path: &Path, loc: Loc, message: impl Into<String>) -> MeshError {
    match loc {
        Loc::Line(n) => MeshError::at_line(path, n, message),
        Loc::Byte(b) => MeshError::at_byte(path, b, message),
    }
}

/// Why a read stopped: the data ran out (turned into a truncation message naming the
/// element), or something else that already has its message.
enum Fail {
    Eof,
    Error(MeshError),
}

impl From<MeshError> for Fail {
    fn from(e: MeshError) -> Self {
        Fail::Error(e)
    }
}

/// A body encoding. The readers are generic over it so that each is compiled per
/// encoding and byte order, with no dispatch per value.
trait Source {
    fn path(&self) -> &Path;
    /// Where the next value starts.
    fn loc(&mut self) -> Loc;
    fn real(&mut self, ty: Scalar) -> Result<f64, Fail>;
    fn int(&mut self, ty: Scalar) -> Result<i64, Fail>;
    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), Fail>;
    /// A warning if anything but whitespace follows the last element.
    fn trailing(&mut self) -> Option<String>;
}

struct Ascii<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
    path: &'a Path,
}

impl<'a> Ascii<'a> {
    fn skip_space(&mut self) {
        while let Some(&b) = self.data.get(self.pos) {
            if b == b'\n' {
                self.line += 1;
            } else if !b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    fn token(&mut self) -> Result<&'a str, Fail> {
        self.skip_space();
        let start = self.pos;
        while self
            .data
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        let bytes = self.data.get(start..self.pos).unwrap_or_default();
        if bytes.is_empty() {
            return Err(Fail::Eof);
        }
        std::str::from_utf8(bytes).map_err(|_| {
            Fail::Error(MeshError::at_line(
                self.path,
                self.line,
                "the data holds a non-text byte",
            ))
        })
    }
}

impl Source for Ascii<'_> {
    fn path(&self) -> &Path {
        self.path
    }

    fn loc(&mut self) -> Loc {
        self.skip_space();
        Loc::Line(self.line)
    }

    fn real(&mut self, ty: Scalar) -> Result<f64, Fail> {
        let token = self.token()?;
        // float32 values are parsed as f32 so they round exactly as a binary file would.
        let value = if ty == Scalar::F32 {
            token.parse::<f32>().map(f64::from).ok()
        } else {
            token.parse::<f64>().ok()
        };
        value.ok_or_else(|| {
            Fail::Error(MeshError::at_line(
                self.path,
                self.line,
                format!("`{token}` is not a number"),
            ))
        })
    }

    fn int(&mut self, _ty: Scalar) -> Result<i64, Fail> {
        let token = self.token()?;
        token
            .parse::<i64>()
            .ok()
            .or_else(|| {
                // Some writers print integers as `3.0`.
                let f = token.parse::<f64>().ok()?;
                (f.fract() == 0.0 && f.abs() < 9e15).then_some(f as i64)
            })
            .ok_or_else(|| {
                Fail::Error(MeshError::at_line(
                    self.path,
                    self.line,
                    format!("`{token}` is not an integer"),
                ))
            })
    }

    fn skip(&mut self, _ty: Scalar, n: u64) -> Result<(), Fail> {
        for _ in 0..n {
            self.token()?;
        }
        Ok(())
    }

    fn trailing(&mut self) -> Option<String> {
        self.skip_space();
        (self.pos < self.data.len())
            .then(|| format!("line {}: data after the last element ignored", self.line))
    }
}

struct Binary<'a, const BIG: bool> {
    data: &'a [u8],
    pos: usize,
    /// File offset of the body, so that errors give offsets into the whole file.
    base: usize,
    path: &'a Path,
}

impl<'a, const BIG: bool> Binary<'a, BIG> {
    fn new(data: &'a [u8], header: &Header, path: &'a Path) -> Self {
        Binary {
            data,
            pos: 0,
            base: header.body_start,
            path,
        }
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], Fail> {
        match self
            .data
            .get(self.pos..)
            .and_then(|rest| rest.first_chunk::<N>())
        {
            Some(bytes) => {
                self.pos += N;
                Ok(*bytes)
            }
            None => {
                // Point at the end of the file in the truncation message.
                self.pos = self.data.len();
                Err(Fail::Eof)
            }
        }
    }
}

macro_rules! endian {
    ($big:expr, $t:ty, $bytes:expr) => {
        if $big {
            <$t>::from_be_bytes($bytes)
        } else {
            <$t>::from_le_bytes($bytes)
        }
    };
}

impl<const BIG: bool> Source for Binary<'_, BIG> {
    fn path(&self) -> &Path {
        self.path
    }

    fn loc(&mut self) -> Loc {
        Loc::Byte((self.base + self.pos) as u64)
    }

    fn real(&mut self, ty: Scalar) -> Result<f64, Fail> {
        Ok(match ty {
            Scalar::I8 => f64::from(i8::from_ne_bytes(self.take()?)),
            Scalar::U8 => f64::from(u8::from_ne_bytes(self.take()?)),
            Scalar::I16 => f64::from(endian!(BIG, i16, self.take()?)),
            Scalar::U16 => f64::from(endian!(BIG, u16, self.take()?)),
            Scalar::I32 => f64::from(endian!(BIG, i32, self.take()?)),
            Scalar::U32 => f64::from(endian!(BIG, u32, self.take()?)),
            Scalar::F32 => f64::from(endian!(BIG, f32, self.take()?)),
            Scalar::F64 => endian!(BIG, f64, self.take()?),
        })
    }

    fn int(&mut self, ty: Scalar) -> Result<i64, Fail> {
        Ok(match ty {
            Scalar::I8 => i64::from(i8::from_ne_bytes(self.take()?)),
            Scalar::U8 => i64::from(u8::from_ne_bytes(self.take()?)),
            Scalar::I16 => i64::from(endian!(BIG, i16, self.take()?)),
            Scalar::U16 => i64::from(endian!(BIG, u16, self.take()?)),
            Scalar::I32 => i64::from(endian!(BIG, i32, self.take()?)),
            Scalar::U32 => i64::from(endian!(BIG, u32, self.take()?)),
            // The header check only lets integer types reach here.
            Scalar::F32 | Scalar::F64 => {
                let at = self.loc();
                return Err(Fail::Error(error_at(
                    self.path,
                    at,
                    "expected an integer type",
                )));
            }
        })
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), Fail> {
        let end = n
            .checked_mul(ty.size())
            .and_then(|bytes| usize::try_from(bytes).ok())
            .and_then(|bytes| self.pos.checked_add(bytes))
            .filter(|&end| end <= self.data.len());
        match end {
            Some(end) => {
                self.pos = end;
                Ok(())
            }
            None => {
                self.pos = self.data.len();
                Err(Fail::Eof)
            }
        }
    }

    fn trailing(&mut self) -> Option<String> {
        let extra = self.data.len().saturating_sub(self.pos);
        (extra > 0).then(|| {
            format!(
                "{} after the last element ignored",
                count_of(extra, "byte", "bytes")
            )
        })
    }
}

fn read_body<S: Source>(src: &mut S, header: &Header, plan: &Plan) -> Result<MeshData, MeshError> {
    let mut mesh = MeshData::default();
    for (i, el) in header.elements.iter().enumerate() {
        let mut done = 0u64;
        let result = if i == plan.vertex {
            read_vertices(src, el, plan, &mut mesh, &mut done)
        } else if let Some((_, index_prop)) = plan.face.filter(|(f, _)| *f == i) {
            read_faces(src, el, index_prop, plan.vertex_count, &mut mesh, &mut done)
        } else {
            skip_element(src, el, &mut done)
        };
        match result {
            Ok(()) => {}
            Err(Fail::Error(e)) => return Err(e),
            Err(Fail::Eof) => {
                let at = src.loc();
                return Err(error_at(
                    src.path(),
                    at,
                    format!(
                        "file is truncated: it ends after {done} of {} {}",
                        el.count,
                        el.plural()
                    ),
                ));
            }
        }
    }
    if let Some(w) = src.trailing() {
        mesh.warnings.push(w);
    }
    Ok(mesh)
}

fn read_vertices<S: Source>(
    src: &mut S,
    el: &Element,
    plan: &Plan,
    mesh: &mut MeshData,
    done: &mut u64,
) -> Result<(), Fail> {
    mesh.positions.reserve(capped(el.count));
    if plan.normals {
        mesh.normals.reserve(capped(el.count));
    }
    if plan.uvs {
        mesh.uvs.reserve(capped(el.count));
    }
    for i in 0..el.count {
        let at = src.loc();
        let mut slots = [0.0f64; 8];
        for (prop, role) in el.props.iter().zip(&plan.roles) {
            match (prop.ty, role) {
                (Ty::Scalar(ty), Some(slot)) => {
                    let value = src.real(ty)?;
                    if let Some(s) = slots.get_mut(*slot) {
                        *s = value;
                    }
                }
                (Ty::Scalar(ty), None) => src.skip(ty, 1)?,
                (Ty::List { count, item }, _) => skip_list(src, count, item)?,
            }
        }
        let v = slots.map(|x| x as f32);
        let [x, y, z, nx, ny, nz, u, w] = v;
        let bad = |what: &str, values: &[f32]| {
            Fail::Error(error_at(
                src.path(),
                at,
                format!("vertex {i}: {what} {values:?} is not finite"),
            ))
        };
        if !(x.is_finite() && y.is_finite() && z.is_finite()) {
            return Err(bad("position", &[x, y, z]));
        }
        mesh.positions.push([x, y, z]);
        if plan.normals {
            if !(nx.is_finite() && ny.is_finite() && nz.is_finite()) {
                return Err(bad("normal", &[nx, ny, nz]));
            }
            mesh.normals.push([nx, ny, nz]);
        }
        if plan.uvs {
            if !(u.is_finite() && w.is_finite()) {
                return Err(bad("texture coordinate", &[u, w]));
            }
            mesh.uvs.push([u, w]);
        }
        *done += 1;
    }
    Ok(())
}

fn read_faces<S: Source>(
    src: &mut S,
    el: &Element,
    index_prop: usize,
    vertex_count: u32,
    mesh: &mut MeshData,
    done: &mut u64,
) -> Result<(), Fail> {
    mesh.triangles.reserve(capped(el.count));
    for f in 0..el.count {
        let at = src.loc();
        for (p, prop) in el.props.iter().enumerate() {
            match prop.ty {
                Ty::List { count, item } if p == index_prop => {
                    let n = src.int(count)?;
                    if n < 3 {
                        return Err(Fail::Error(error_at(
                            src.path(),
                            at,
                            format!("face {f} has {n} vertices; at least 3 are needed"),
                        )));
                    }
                    let index = |src: &mut S| -> Result<u32, Fail> {
                        let i = src.int(item)?;
                        match u32::try_from(i) {
                            Ok(i) if i < vertex_count => Ok(i),
                            _ => Err(Fail::Error(error_at(
                                src.path(),
                                at,
                                format!(
                                    "face {f}: vertex index {i} is out of range (the file has {})",
                                    count_of(vertex_count as usize, "vertex", "vertices")
                                ),
                            ))),
                        }
                    };
                    let first = index(src)?;
                    let mut prev = index(src)?;
                    for _ in 2..n {
                        let next = index(src)?;
                        mesh.triangles.push([first, prev, next]);
                        prev = next;
                    }
                }
                Ty::List { count, item } => skip_list(src, count, item)?,
                Ty::Scalar(ty) => src.skip(ty, 1)?,
            }
        }
        *done += 1;
    }
    Ok(())
}

fn skip_list<S: Source>(src: &mut S, count: Scalar, item: Scalar) -> Result<(), Fail> {
    let at = src.loc();
    let n = src.int(count)?;
    let n = u64::try_from(n).map_err(|_| {
        Fail::Error(error_at(
            src.path(),
            at,
            format!("list length {n} is negative"),
        ))
    })?;
    src.skip(item, n)
}

fn skip_element<S: Source>(src: &mut S, el: &Element, done: &mut u64) -> Result<(), Fail> {
    // Entries without properties take no bytes: nothing to skip, however many there are.
    if el.props.is_empty() {
        return Ok(());
    }
    for _ in 0..el.count {
        for prop in &el.props {
            match prop.ty {
                Ty::Scalar(ty) => src.skip(ty, 1)?,
                Ty::List { count, item } => skip_list(src, count, item)?,
            }
        }
        *done += 1;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
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
        let mut bin =
            b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\n\
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
}
