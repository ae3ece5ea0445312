//! The checks a glTF file passes before the `gltf` crate reads it: what the crate's
//! validation asks (less `min` and `max` on POSITION accessors, which snell does not
//! read), what the crate takes for granted and would panic on, buffer views and accessors
//! within their buffers, and each attribute's layout. Each failure is a message naming
//! what is wrong and where.

use super::decode_uri;

/// The document, checked as the `gltf` crate checks it but for its demand for `min` and
/// `max` on every POSITION accessor: snell works out its own bounds and never reads them,
/// and other viewers read files without them.
pub(super) fn validated(root: gltf::json::Root) -> Result<gltf::Document, gltf::Error> {
    use gltf::json::validation::{Error, Validate};
    let mut errors = vec![];
    root.validate(&root, gltf::json::Path::new, &mut |path, e| {
        let path = path();
        let bounds = [r#"["POSITION"].min"#, r#"["POSITION"].max"#]
            .iter()
            .any(|end| path.as_str().ends_with(end));
        if !(bounds && matches!(e, Error::Missing)) {
            errors.push((path, e));
        }
    });
    if errors.is_empty() {
        Ok(gltf::Document::from_json_without_validation(root))
    } else {
        Err(gltf::Error::Validation(errors))
    }
}

/// What the `gltf` crate (1.4.1) takes for granted and panics on where a file breaks it,
/// each found by the fuzz target: every primitive's attributes name accessors that exist
/// (its validation reads a primitive's POSITION accessor before checking that); an image
/// in a buffer view has a MIME type, and one not in a buffer view has a URI; URIs decode
/// from their %-escapes to UTF-8.
pub(super) fn check_before_validation(root: &gltf::json::Root) -> Result<(), String> {
    for (i, image) in root.images.iter().enumerate() {
        if image.buffer_view.is_some() && image.mime_type.is_none() {
            return Err(format!("image {i} is in a buffer view but has no mimeType"));
        }
        if image.buffer_view.is_none() && image.uri.is_none() {
            return Err(format!("image {i} has neither a uri nor a buffer view"));
        }
    }
    let uris = root
        .images
        .iter()
        .filter_map(|i| i.uri.as_deref())
        .chain(root.buffers.iter().filter_map(|b| b.uri.as_deref()));
    for uri in uris {
        if !uri.starts_with("data:") && decode_uri(uri).is_none() {
            return Err(format!("the uri `{uri}` does not decode to UTF-8"));
        }
    }
    // A camera's type must name a projection it has: the crate's validation only asks for
    // one of the two, and its reader unwraps the one the type names.
    for (i, c) in root.cameras.iter().enumerate() {
        use gltf::json::camera::Type;
        use gltf::json::validation::Checked;
        let (has, name) = match c.type_ {
            Checked::Valid(Type::Perspective) => (c.perspective.is_some(), "perspective"),
            Checked::Valid(Type::Orthographic) => (c.orthographic.is_some(), "orthographic"),
            Checked::Invalid => (true, ""),
        };
        if !has {
            return Err(format!(
                "camera {i} is of type {name} but has no `{name}` projection"
            ));
        }
    }
    let n = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let indices = prim
                .indices
                .iter()
                .map(|i| ("indices".to_string(), i.value()));
            let attributes = prim.attributes.iter().map(|(k, i)| match k {
                gltf::json::validation::Checked::Valid(s) => (s.to_string(), i.value()),
                gltf::json::validation::Checked::Invalid => ("an attribute".into(), i.value()),
            });
            for (name, i) in attributes.chain(indices) {
                if i >= n {
                    return Err(format!(
                        "mesh {m}, primitive {p}: {name} names accessor {i}, but there are {n}"
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Every buffer view within its buffer, and every accessor within its view (or, without
/// one, refused: sparse accessors and accessors of zeros are not read).
pub(super) fn check_views(
    doc: &gltf::Document,
    buffers: &[gltf::buffer::Data],
) -> Result<(), String> {
    for v in doc.views() {
        let len = buffers.get(v.buffer().index()).map_or(0, |b| b.len());
        if v.offset()
            .checked_add(v.length())
            .is_none_or(|end| end > len)
        {
            return Err(format!(
                "buffer view {} ({} bytes from {}) runs past the end of buffer {} ({len} bytes)",
                v.index(),
                v.length(),
                v.offset(),
                v.buffer().index()
            ));
        }
    }
    for a in doc.accessors() {
        if a.sparse().is_some() {
            return Err(format!(
                "accessor {} is sparse, which snell does not read",
                a.index()
            ));
        }
        // glTF asks for at least one element, and the crate's readers count on it.
        if a.count() == 0 {
            return Err(format!(
                "accessor {} has no elements (glTF asks for a count of at least 1)",
                a.index()
            ));
        }
        let Some(view) = a.view() else {
            return Err(format!("accessor {} has no buffer view", a.index()));
        };
        let stride = view.stride().unwrap_or(a.size());
        let end = (a.count() - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(a.offset()))
            .and_then(|x| x.checked_add(a.size()));
        if end.is_none_or(|end| end > view.length()) {
            return Err(format!(
                "accessor {} ({} elements of {} bytes from {}) runs past the end of buffer view {} ({} bytes)",
                a.index(),
                a.count(),
                a.size(),
                a.offset(),
                view.index(),
                view.length()
            ));
        }
    }
    Ok(())
}

/// Each attribute snell reads is laid out as glTF requires (positions and normals three
/// floats, uvs two floats or normalized bytes or shorts, indices unsigned scalars): the
/// `gltf` crate's readers assume it (and assert it where debug assertions are on). The
/// second uv set is read (and checked) only where `uv1` says.
pub(super) fn check_layouts(prim: &gltf::Primitive, uv1: bool) -> Result<(), String> {
    use gltf::accessor::{DataType as T, Dimensions as D};
    use gltf::mesh::Semantic as S;
    let checks: [(S, &str, D, &[T]); 5] = [
        (S::Positions, "POSITION", D::Vec3, &[T::F32]),
        (S::Normals, "NORMAL", D::Vec3, &[T::F32]),
        (S::Tangents, "TANGENT", D::Vec4, &[T::F32]),
        (
            S::TexCoords(0),
            "TEXCOORD_0",
            D::Vec2,
            &[T::F32, T::U8, T::U16],
        ),
        (
            S::TexCoords(1),
            "TEXCOORD_1",
            D::Vec2,
            &[T::F32, T::U8, T::U16],
        ),
    ];
    for (semantic, name, dims, types) in checks {
        if semantic == S::TexCoords(1) && !uv1 {
            continue;
        }
        if let Some(a) = prim.get(&semantic)
            && (a.dimensions() != dims || !types.contains(&a.data_type()))
        {
            return Err(format!(
                "its {name} accessor {} is {:?} of {:?}, not {dims:?} of {types:?}",
                a.index(),
                a.dimensions(),
                a.data_type()
            ));
        }
    }
    if let Some(a) = prim.get(&S::Colors(0))
        && (!matches!(a.dimensions(), D::Vec3 | D::Vec4)
            || !matches!(a.data_type(), T::F32 | T::U8 | T::U16))
    {
        return Err(format!(
            "its COLOR_0 accessor {} is {:?} of {:?}, not Vec3 or Vec4 of F32, U8 or U16",
            a.index(),
            a.dimensions(),
            a.data_type()
        ));
    }
    if let Some(a) = prim.indices()
        && (a.dimensions() != D::Scalar || !matches!(a.data_type(), T::U8 | T::U16 | T::U32))
    {
        return Err(format!(
            "its indices accessor {} is {:?} of {:?}, not unsigned scalars",
            a.index(),
            a.dimensions(),
            a.data_type()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Missing bounds on a POSITION accessor pass; bounds of the wrong shape, and the crate's
    /// other checks, do not.
    #[test]
    fn validation_lets_only_missing_position_bounds_pass() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/data/gltf/no-bounds.gltf"
        ))
        .unwrap();
        let root: gltf::json::Root = serde_json::from_str(&text).unwrap();
        assert!(validated(root.clone()).is_ok());
        let mut bad = root.clone();
        bad.accessors[0].min = Some(serde_json::json!([0, 0]));
        bad.accessors[0].max = Some(serde_json::json!([1, 1, 1]));
        let e = validated(bad).unwrap_err().to_string();
        assert!(e.contains(r#"["POSITION"].min: Invalid value"#), "{e}");
        assert!(!e.contains(".max"), "{e}");
    }
}
