//! The body's two encodings, ASCII and binary (either byte order), behind one `Source` trait
//! that the readers are generic over, and where in the file a value is (a line or a byte).

use super::header::*;
use crate::mesh_file::{MeshError, count_of};
use std::path::Path;

/// Where in the file something is: a line (ASCII) or a byte offset (binary).
#[derive(Clone, Copy)]
pub(super) enum Loc {
    Line(usize),
    Byte(u64),
}

pub(super) fn error_at(path: &Path, loc: Loc, message: impl Into<String>) -> MeshError {
    match loc {
        Loc::Line(n) => MeshError::at_line(path, n, message),
        Loc::Byte(b) => MeshError::at_byte(path, b, message),
    }
}

/// Why a read stopped: the data ran out (turned into a truncation message naming the
/// element), or something else that already has its message.
pub(super) enum Fail {
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
pub(super) trait Source {
    fn path(&self) -> &Path;
    /// Where the next value starts.
    fn loc(&mut self) -> Loc;
    fn real(&mut self, ty: Scalar) -> Result<f64, Fail>;
    fn int(&mut self, ty: Scalar) -> Result<i64, Fail>;
    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), Fail>;
    /// A warning if anything but whitespace follows the last element.
    fn trailing(&mut self) -> Option<String>;
}

pub(super) struct Ascii<'a> {
    pub(super) data: &'a [u8],
    pub(super) pos: usize,
    pub(super) line: usize,
    pub(super) path: &'a Path,
}

impl<'a> Ascii<'a> {
    pub(super) fn skip_space(&mut self) {
        while let Some(&b) = self.data.get(self.pos) {
            if b == b'\n' {
                self.line += 1;
            } else if !b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    pub(super) fn token(&mut self) -> Result<&'a str, Fail> {
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

pub(super) struct Binary<'a, const BIG: bool> {
    pub(super) data: &'a [u8],
    pub(super) pos: usize,
    /// File offset of the body, so that errors give offsets into the whole file.
    pub(super) base: usize,
    pub(super) path: &'a Path,
}

impl<'a, const BIG: bool> Binary<'a, BIG> {
    pub(super) fn new(data: &'a [u8], header: &Header, path: &'a Path) -> Self {
        Binary {
            data,
            pos: 0,
            base: header.body_start,
            path,
        }
    }

    pub(super) fn take<const N: usize>(&mut self) -> Result<[u8; N], Fail> {
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
