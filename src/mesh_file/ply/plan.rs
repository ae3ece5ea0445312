//! What the reader does with each element and property, worked out from the header once:
//! which vertex properties are the position, normal and uv, and where the face's index list is.

use super::header::*;
use crate::mesh_file::MeshError;
use std::path::Path;

/// Slots of the values kept per vertex.
pub(super) const X: usize = 0;
pub(super) const NX: usize = 3;
pub(super) const U: usize = 6;

/// What to do with each element, worked out from the header.
pub(super) struct Plan {
    pub(super) vertex: usize,
    /// Per vertex property: the slot (0..8, see `X`, `NX`, `U`) its value goes to.
    pub(super) roles: Vec<Option<usize>>,
    pub(super) normals: bool,
    pub(super) uvs: bool,
    pub(super) vertex_count: u32,
    /// The face element and the position of its index list among its properties.
    pub(super) face: Option<(usize, usize)>,
    pub(super) warnings: Vec<String>,
}

impl Plan {
    pub(super) fn new(header: &Header, path: &Path) -> Result<Plan, MeshError> {
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
