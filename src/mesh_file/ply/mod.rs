//! Stanford PLY meshes: ASCII and binary (either byte order).
//!
//! Reads the `vertex` element's `x y z`, `nx ny nz` and texture coordinates (`u v`,
//! `s t`, `texture_u texture_v` or `texture_s texture_t`) and the `face` element's
//! `vertex_indices` (or `vertex_index`) list; polygons are fan triangulated. Other
//! properties (colours, confidence, ...) and other elements (edges, materials, ...) are
//! skipped. Header and ASCII errors name a line, binary errors a byte offset.

mod body;
mod header;
mod plan;
mod source;
#[cfg(test)]
mod tests;

use super::{MeshData, MeshError};
use body::read_body;
use header::{Format, check_counts, parse_header};
use plan::Plan;
use source::{Ascii, Binary};
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
