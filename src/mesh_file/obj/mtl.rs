//! MTL material libraries: each `newmtl` block's colours (`Kd`, `Ks`, `Ke`), exponent, index,
//! opacity, PBR extension (`Pr`, `Pm`), `illum` model and colour map, read into `MtlMaterial`s.

use super::text::*;
use crate::mesh_file::{MeshError, MtlMaterial};
use std::path::Path;

/// Loads an MTL file on its own (as `mtllib` does); warnings are appended to `warnings`.
pub fn load_mtl(path: &Path, warnings: &mut Vec<String>) -> Result<Vec<MtlMaterial>, MeshError> {
    let bytes = crate::mesh_file::read_file(path)?;
    parse_mtl(&bytes, path, warnings)
}

/// Parses MTL text held in memory; `path` names the file in messages and its folder is
/// where `map_Kd` textures are looked for. Later `newmtl` blocks with a name already used
/// are kept as separate entries here; [`super::parse`] lets the last one win.
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
pub(super) fn texture_file(rest: &str) -> Option<&str> {
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
