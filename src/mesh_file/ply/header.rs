//! The PLY header: the body's format, its elements and their properties, and the check that
//! the body is long enough for the counts the header gives.

use crate::mesh_file::MeshError;
use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Format {
    Ascii,
    BinaryLe,
    BinaryBe,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scalar {
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
    pub(super) fn parse(name: &str) -> Option<Scalar> {
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

    pub(super) fn size(self) -> u64 {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub(super) fn is_int(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug)]
pub(super) enum Ty {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
pub(super) struct Property {
    pub(super) name: String,
    pub(super) ty: Ty,
    pub(super) line: usize,
}

#[derive(Debug)]
pub(super) struct Element {
    pub(super) name: String,
    pub(super) count: u64,
    pub(super) props: Vec<Property>,
    pub(super) line: usize,
}

impl Element {
    /// "vertices", "faces", "`edge` elements": for truncation messages.
    pub(super) fn plural(&self) -> String {
        match self.name.as_str() {
            "vertex" => "vertices".to_string(),
            "face" => "faces".to_string(),
            other => format!("`{other}` elements"),
        }
    }

    /// The fewest body bytes one entry can take (lists may be empty).
    pub(super) fn min_size(&self, format: Format) -> u64 {
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

pub(super) struct Header {
    pub(super) format: Format,
    pub(super) elements: Vec<Element>,
    pub(super) body_start: usize,
    /// Number of header lines, `end_header` included.
    pub(super) lines: usize,
    pub(super) warnings: Vec<String>,
}

pub(super) fn parse_header(bytes: &[u8], path: &Path) -> Result<Header, MeshError> {
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
pub(super) fn check_counts(header: &Header, body_len: usize, path: &Path) -> Result<(), MeshError> {
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
