//! Reading the body: the vertex element's kept values, the faces fan triangulated, and every
//! other element skipped, through whichever `Source` the header names.

use super::header::*;
use super::plan::*;
use super::source::*;
use crate::mesh_file::{MeshData, MeshError, capped, count_of};

pub(super) fn read_body<S: Source>(
    src: &mut S,
    header: &Header,
    plan: &Plan,
) -> Result<MeshData, MeshError> {
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

pub(super) fn read_vertices<S: Source>(
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

pub(super) fn read_faces<S: Source>(
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

pub(super) fn skip_list<S: Source>(src: &mut S, count: Scalar, item: Scalar) -> Result<(), Fail> {
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

pub(super) fn skip_element<S: Source>(
    src: &mut S,
    el: &Element,
    done: &mut u64,
) -> Result<(), Fail> {
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
