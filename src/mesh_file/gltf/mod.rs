//! glTF 2.0 files (`.gltf` with its buffers and images beside it or inside it, and `.glb`)
//! through the `gltf` crate: every mesh of the default scene (each stored once, however
//! many nodes use it), the node hierarchy's placements of them, and the metallic-roughness
//! materials with their base-colour images.
//!
//! Nothing in a file reaches the `gltf` crate's readers until its buffer views and
//! accessors have been checked against the buffers' sizes (checks.rs), and indices against
//! the vertex counts, so a malformed file is an error that names it and what is wrong,
//! never a panic. What the file holds and snell does not read (skins, morph targets,
//! animations, material extensions) comes back as warnings (unsupported.rs).
//! glTF's axes are snell's (+y up, right-handed, metres), and its texture coordinates put
//! v = 0 at the top of the image, as snell does.

mod checks;
mod material;
mod placed;
mod unsupported;

pub use material::{Alpha, PbrMaterial, TextureRef, uv_transform};
pub use placed::{GltfCamera, GltfLight, GltfLightKind};
pub use unsupported::named;

use super::{MeshData, MeshError};
use checks::{check_before_validation, check_layouts, check_views, validated};
use gltf::mesh::Mode;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// What a glTF file holds, ready to become scene objects.
#[derive(Debug, Default)]
pub struct GltfScene {
    /// Each glTF mesh that a node places, its primitives merged (`triangle_materials`
    /// index `slots`).
    pub meshes: Vec<GltfMesh>,
    /// The file's materials.
    pub materials: Vec<PbrMaterial>,
    /// Decoded images, by glTF image index (`None` for one no material uses).
    pub images: Vec<Option<::image::DynamicImage>>,
    /// The placements: a mesh of `meshes` and its node's world matrix (column-major).
    pub instances: Vec<GltfInstance>,
    /// Problems that did not stop the load.
    pub warnings: Vec<String>,
    /// The files read besides the glTF file itself (external buffers and images).
    pub files: Vec<PathBuf>,
    /// The cameras the nodes place (the default scene's node tree, depth first).
    pub cameras: Vec<GltfCamera>,
    /// The KHR_lights_punctual lights the nodes place.
    pub lights: Vec<GltfLight>,
}

/// One glTF mesh as one snell mesh.
#[derive(Debug)]
pub struct GltfMesh {
    /// Its name in the file, or `mesh N`.
    pub name: String,
    /// Its triangles; `triangle_materials` index `slots`.
    pub data: MeshData,
    /// The glTF material of each slot (`None`: glTF's default material).
    pub slots: Vec<Option<usize>>,
}

/// A node placing a mesh.
#[derive(Clone, Debug)]
pub struct GltfInstance {
    /// Index into [`GltfScene::meshes`].
    pub mesh: usize,
    /// The node's name, or `node N`.
    pub node: String,
    /// Object to world, column-major, the product of the node's and its ancestors'.
    pub matrix: [[f32; 4]; 4],
}

/// Extensions a file may require that snell reads (or may ignore without changing the
/// picture's geometry); a file that uses them without requiring them gets no warning
/// for them.
const SUPPORTED_REQUIRED: &[&str] = &[
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_materials_emissive_strength",
    "KHR_texture_transform",
    "KHR_lights_punctual",
];

fn error(path: &Path, message: impl Into<String>) -> MeshError {
    MeshError {
        path: path.to_path_buf(),
        line: None,
        byte_offset: None,
        message: message.into(),
    }
}

/// Reads a `.gltf` or `.glb` file.
pub fn load(path: &Path) -> Result<GltfScene, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| error(path, format!("cannot read it: {e}")))?;
    parse(&bytes, path)
}

/// Reads only the cameras and lights of a `.gltf` or `.glb` file (no meshes, no images).
pub fn load_placements(path: &Path) -> Result<GltfScene, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| error(path, format!("cannot read it: {e}")))?;
    parse_with(&bytes, path, false)
}

/// A glTF file's `bytes` (JSON or GLB) as [`load`] reads them, as if read from `path` (whose
/// folder its buffer and image files are found in).
pub fn parse(bytes: &[u8], path: &Path) -> Result<GltfScene, MeshError> {
    parse_with(bytes, path, true)
}

/// [`parse`], with its meshes, materials and images only where `geometry` asks.
fn parse_with(bytes: &[u8], path: &Path, geometry: bool) -> Result<GltfScene, MeshError> {
    // The `gltf` crate subtracts the 12-byte header from a GLB's stated length before it
    // checks it (an overflow, and a panic where overflow is checked: found by the fuzz
    // target).
    if let Some(len) = bytes.strip_prefix(b"glTF").and_then(|rest| rest.get(4..8)) {
        let len = u32::from_le_bytes([len[0], len[1], len[2], len[3]]);
        if len < 12 {
            return Err(error(
                path,
                format!(
                    "its GLB header gives a length of {len} bytes, less than the header itself"
                ),
            ));
        }
    }
    let invalid = |e: gltf::Error| error(path, format!("not a valid glTF 2.0 file: {e}"));
    // The extensions it requires first (their names say more than a failed validation),
    // then the whole document.
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(invalid)?;
    for ext in document.extensions_required() {
        if !SUPPORTED_REQUIRED.contains(&ext) {
            return Err(error(
                path,
                format!("it requires the extension {ext}, which snell does not support"),
            ));
        }
    }
    let root = document.into_json();
    check_before_validation(&root).map_err(|m| error(path, m))?;
    let document = validated(root).map_err(invalid)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let mut out = GltfScene::default();
    for b in document.buffers() {
        if let gltf::buffer::Source::Uri(uri) = b.source()
            && !uri.starts_with("data:")
        {
            let file = base.join(decode_uri(uri).unwrap_or_default());
            out.files.push(file.clone());
            if !file.is_file() {
                return Err(error(
                    path,
                    format!("its buffer file {} is missing", file.display()),
                ));
            }
        }
    }
    let buffers = gltf::import_buffers(&document, Some(base), blob)
        .map_err(|e| error(path, format!("cannot read its buffers: {e}")))?;
    check_views(&document, &buffers).map_err(|m| error(path, m))?;

    // The scene's nodes, depth first, with their world matrices.
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next());
    let mut stack: Vec<(gltf::Node, [[f32; 4]; 4], usize)> = match &scene {
        Some(s) => s.nodes().map(|n| (n, IDENTITY, 0)).collect(),
        None => vec![],
    };
    let mut mesh_of: HashMap<usize, usize> = HashMap::new();
    // The nodes that show a mesh, by index.
    let mut placed_nodes = vec![];
    let mut used_materials = vec![false; document.materials().len()];
    if geometry {
        out.materials = document.materials().map(|m| material::read(&m)).collect();
    }
    while let Some((node, parent, depth)) = stack.pop() {
        if depth > 256 {
            return Err(error(
                path,
                "its node hierarchy is deeper than 256 (a cycle?)",
            ));
        }
        let world = mul(&parent, &node.transform().matrix());
        if let Some(mesh) = node.mesh().filter(|_| geometry) {
            let k = match mesh_of.get(&mesh.index()) {
                Some(&k) => k,
                None => {
                    let m = read_mesh(&mesh, &buffers, &out.materials, &mut out.warnings)
                        .map_err(|msg| error(path, msg))?;
                    for s in m.slots.iter().flatten() {
                        used_materials[*s] = true;
                    }
                    out.meshes.push(m);
                    mesh_of.insert(mesh.index(), out.meshes.len() - 1);
                    out.meshes.len() - 1
                }
            };
            placed_nodes.push(node.index());
            out.instances.push(GltfInstance {
                mesh: k,
                node: node
                    .name()
                    .map_or_else(|| format!("node {}", node.index()), str::to_string),
                matrix: world,
            });
        }
        if let Some(c) = placed::camera(&node, world) {
            out.cameras.push(c);
        }
        if let Some(l) = placed::light(&node, world) {
            out.lights.push(l);
        }
        stack.extend(node.children().map(|c| (c, world, depth + 1)));
    }
    out.instances.reverse();
    out.cameras.reverse();
    out.lights.reverse();

    if !geometry {
        return Ok(out);
    }
    out.warnings.extend(unsupported::warnings(
        &document,
        &placed_nodes,
        &used_materials,
    ));
    // The images the used materials show, decoded.
    let mut wanted = vec![false; document.images().len()];
    for (m, used) in out.materials.iter().zip(&used_materials) {
        if *used {
            for t in m.textures() {
                wanted[t.image] = true;
            }
        }
    }
    for image in document.images() {
        if !wanted[image.index()] {
            out.images.push(None);
            continue;
        }
        if let gltf::image::Source::Uri { uri, .. } = image.source()
            && !uri.starts_with("data:")
        {
            out.files
                .push(base.join(decode_uri(uri).unwrap_or_default()));
        }
        let data = gltf::image::Data::from_source(image.source(), Some(base), &buffers)
            .map_err(|e| error(path, format!("cannot read image {}: {e}", image.index())))?;
        out.images.push(Some(to_dynamic(data).ok_or_else(|| {
            error(
                path,
                format!(
                    "image {} has a pixel format snell does not read",
                    image.index()
                ),
            )
        })?));
    }
    Ok(out)
}

const IDENTITY: [[f32; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// `a * b` of column-major matrices.
fn mul(a: &[[f32; 4]; 4], b: &[[f32; 4]; 4]) -> [[f32; 4]; 4] {
    let mut out = [[0.0; 4]; 4];
    for (c, col) in out.iter_mut().enumerate() {
        for (r, v) in col.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[k][r] * b[c][k]).sum();
        }
    }
    out
}

/// A relative URI's path: its %-escapes decoded, if they make UTF-8.
fn decode_uri(uri: &str) -> Option<String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// One glTF mesh's triangle primitives merged into one mesh; points and lines are skipped
/// with a warning.
fn read_mesh(
    mesh: &gltf::Mesh,
    buffers: &[gltf::buffer::Data],
    materials: &[PbrMaterial],
    warnings: &mut Vec<String>,
) -> Result<GltfMesh, String> {
    let name = mesh
        .name()
        .map_or_else(|| format!("mesh {}", mesh.index()), str::to_string);
    let mut data = MeshData::default();
    let mut slots: Vec<Option<usize>> = vec![];
    let mut any_normals = false;
    let mut normals: Vec<Option<[f32; 3]>> = vec![];
    let mut uvs: Vec<Option<[f32; 2]>> = vec![];
    let mut uvs1: Vec<Option<[f32; 2]>> = vec![];
    let mut tangents: Vec<Option<[f32; 4]>> = vec![];
    let mut colors: Vec<Option<[f32; 3]>> = vec![];
    for (p, prim) in mesh.primitives().enumerate() {
        let mode = prim.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            warnings.push(format!(
                "{name}: primitive {p} is {mode:?}, not triangles: skipped"
            ));
            continue;
        }
        // The second uv set only where the primitive's material reads it (files that
        // carry one for a light map snell does not use keep their meshes as before).
        let wants_uv1 = prim
            .material()
            .index()
            .and_then(|i| materials.get(i))
            .is_some_and(|m| m.textures().any(|t| t.texcoord == 1));
        check_layouts(&prim, wants_uv1).map_err(|m| format!("{name}: primitive {p}: {m}"))?;
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let Some(positions) = reader.read_positions() else {
            return Err(format!("{name}: primitive {p} has no POSITION"));
        };
        let base = data.positions.len();
        data.positions.extend(positions);
        let n = data.positions.len() - base;
        match reader.read_normals() {
            Some(it) => {
                any_normals = true;
                normals.extend(it.map(Some));
            }
            None => normals.extend(std::iter::repeat_n(None, n)),
        }
        match reader.read_tex_coords(0) {
            // MeshData keeps OBJ's convention, v = 0 at the bottom of the image (the mesh
            // input flips it to snell's); glTF's v = 0 is the top.
            Some(it) => uvs.extend(it.into_f32().map(|[u, v]| Some([u, 1.0 - v]))),
            None => uvs.extend(std::iter::repeat_n(None, n)),
        }
        // Not even asked for otherwise: the crate's reader asserts the layout it was not
        // checked for.
        match wants_uv1.then(|| reader.read_tex_coords(1)).flatten() {
            Some(it) => uvs1.extend(it.into_f32().map(|[u, v]| Some([u, 1.0 - v]))),
            None => uvs1.extend(std::iter::repeat_n(None, n)),
        }
        match reader.read_tangents() {
            Some(it) => tangents.extend(it.map(Some)),
            None => tangents.extend(std::iter::repeat_n(None, n)),
        }
        // Linear RGB (glTF's colours are); alpha is not read.
        match reader.read_colors(0) {
            Some(it) => colors.extend(it.into_rgb_f32().map(Some)),
            None => colors.extend(std::iter::repeat_n(None, n)),
        }
        // Attributes shorter or longer than the positions: each kept to the positions'.
        colors.resize(base + n, None);
        normals.resize(base + n, None);
        uvs.resize(base + n, None);
        uvs1.resize(base + n, None);
        tangents.resize(base + n, None);
        let indices: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..n as u32).collect(),
        };
        if let Some(bad) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(format!(
                "{name}: primitive {p} has index {bad}, but only {n} vertices"
            ));
        }
        let slot = prim.material().index();
        let s = match slots.iter().position(|x| *x == slot) {
            Some(s) => s,
            None => {
                slots.push(slot);
                slots.len() - 1
            }
        };
        let at = |i: u32| base as u32 + i;
        let mut push = |a: u32, b: u32, c: u32| {
            data.triangles.push([at(a), at(b), at(c)]);
            data.triangle_materials.push(s as u32);
        };
        match mode {
            Mode::Triangles => indices.chunks_exact(3).for_each(|t| push(t[0], t[1], t[2])),
            // Every other triangle of a strip turns its winding back.
            Mode::TriangleStrip => {
                for (k, t) in indices.windows(3).enumerate() {
                    if k % 2 == 0 {
                        push(t[0], t[1], t[2]);
                    } else {
                        push(t[1], t[0], t[2]);
                    }
                }
            }
            _ => {
                for t in indices.windows(2).skip(1) {
                    push(indices[0], t[0], t[1]);
                }
            }
        }
    }
    if any_normals {
        data.normals = normals.into_iter().map(|n| n.unwrap_or([0.0; 3])).collect();
    }
    // A second set where any primitive has one; a vertex without one takes its first.
    if uvs1.iter().any(Option::is_some) {
        data.uvs1 = uvs1
            .iter()
            .zip(&uvs)
            .map(|(t, first)| t.or(*first).unwrap_or([0.0; 2]))
            .collect();
    }
    if uvs.iter().any(Option::is_some) {
        data.uvs = uvs.into_iter().map(|t| t.unwrap_or([0.0; 2])).collect();
    }
    // A primitive without colours is white beside one with them (its base colour as is).
    if colors.iter().any(Option::is_some) {
        data.colors = colors
            .into_iter()
            .map(|c| {
                c.map_or([1.0; 3], |c| {
                    c.map(|x| if x.is_finite() { x.max(0.0) } else { 0.0 })
                })
            })
            .collect();
    }
    // Tangents only where every vertex has one (a mesh of primitives with and without
    // them gets MikkTSpace's throughout), each made unit with its sign kept to +-1.
    if !tangents.is_empty() && tangents.iter().all(Option::is_some) {
        data.tangents = tangents
            .into_iter()
            .flatten()
            .map(|[x, y, z, w]| {
                let t = glam::Vec3::new(x, y, z).normalize_or(glam::Vec3::X);
                [t.x, t.y, t.z, if w < 0.0 { -1.0 } else { 1.0 }]
            })
            .collect();
    }
    Ok(GltfMesh { name, data, slots })
}

/// A decoded glTF image as an `image` crate image (8- and 16-bit, and float).
fn to_dynamic(d: gltf::image::Data) -> Option<::image::DynamicImage> {
    use ::image::DynamicImage as D;
    use gltf::image::Format as F;
    let (w, h) = (d.width, d.height);
    let u16s = |b: &[u8]| -> Vec<u16> {
        b.chunks_exact(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .collect()
    };
    let f32s = |b: &[u8]| -> Vec<f32> {
        b.chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect()
    };
    Some(match d.format {
        F::R8 => D::ImageLuma8(::image::ImageBuffer::from_raw(w, h, d.pixels)?),
        F::R8G8 => D::ImageLumaA8(::image::ImageBuffer::from_raw(w, h, d.pixels)?),
        F::R8G8B8 => D::ImageRgb8(::image::ImageBuffer::from_raw(w, h, d.pixels)?),
        F::R8G8B8A8 => D::ImageRgba8(::image::ImageBuffer::from_raw(w, h, d.pixels)?),
        F::R16 => D::ImageLuma16(::image::ImageBuffer::from_raw(w, h, u16s(&d.pixels))?),
        F::R16G16 => D::ImageLumaA16(::image::ImageBuffer::from_raw(w, h, u16s(&d.pixels))?),
        F::R16G16B16 => D::ImageRgb16(::image::ImageBuffer::from_raw(w, h, u16s(&d.pixels))?),
        F::R16G16B16A16 => D::ImageRgba16(::image::ImageBuffer::from_raw(w, h, u16s(&d.pixels))?),
        F::R32G32B32FLOAT => D::ImageRgb32F(::image::ImageBuffer::from_raw(w, h, f32s(&d.pixels))?),
        F::R32G32B32A32FLOAT => {
            D::ImageRgba32F(::image::ImageBuffer::from_raw(w, h, f32s(&d.pixels))?)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_decode_their_escapes() {
        assert_eq!(
            decode_uri("my%20model.bin").as_deref(),
            Some("my model.bin")
        );
        assert_eq!(decode_uri("plain.png").as_deref(), Some("plain.png"));
        assert_eq!(decode_uri("%FF.bin"), None);
        assert_eq!(decode_uri("cut%2"), None);
    }

    #[test]
    fn matrices_multiply_column_major() {
        // A translation by (1, 2, 3) after a scale by 2.
        let t = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [1.0, 2.0, 3.0, 1.0],
        ];
        let s = [
            [2.0, 0.0, 0.0, 0.0],
            [0.0, 2.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let m = mul(&t, &s);
        assert_eq!(m[0][0], 2.0);
        assert_eq!(m[3], [1.0, 2.0, 3.0, 1.0]);
        assert_eq!(mul(&IDENTITY, &m), m);
    }
}
