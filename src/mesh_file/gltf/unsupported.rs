//! What a glTF file holds that snell does not read, as warnings that name where: skins,
//! morph targets and animations (the meshes show as stored, the nodes as placed), the
//! material extensions a used material has that snell leaves out (each with what is lost),
//! KHR_materials_transmission where it is more than all or nothing, and the other
//! extensions the file says it uses. Extensions a file may use only with a fallback that
//! snell reads (compressed geometry, texture formats) or that carry only metadata give no
//! warning; those a file requires and snell does not read are errors (mod.rs).

use super::SUPPORTED_REQUIRED;
use std::collections::BTreeMap;

/// Extensions whose optional use leaves what snell reads whole: the file holds an
/// uncompressed or PNG/JPEG fallback, or the extension is metadata.
const FALLBACK_OR_METADATA: &[&str] = &[
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_texture_basisu",
    "EXT_texture_webp",
    "EXT_texture_avif",
    "KHR_xmp_json_ld",
    "KHR_xmp",
];

/// What leaving out an extension costs the picture, for those snell knows of.
fn what_is_lost(ext: &str) -> &'static str {
    match ext {
        "KHR_materials_clearcoat" => {
            "the clear coat is left off (snell has no coat over a glTF material's own layers)"
        }
        "KHR_materials_pbrSpecularGlossiness" => {
            "the material shows its metallic-roughness terms (glTF's defaults where it has none), not its specular-glossiness ones"
        }
        "KHR_materials_sheen" => "the sheen is left off",
        "KHR_materials_specular" => {
            "the dielectric's specular strength and colour are glTF's defaults"
        }
        "KHR_materials_volume" => "glass is clear inside: no attenuation colour",
        "KHR_materials_iridescence" => "the thin-film colours are left off",
        "KHR_materials_anisotropy" => "highlights are round, not stretched",
        "KHR_materials_unlit" => "the material is lit and shaded as any other",
        "KHR_materials_dispersion" => "glass does not split colours",
        "KHR_materials_diffuse_transmission" => "no light passes through: the surface is opaque",
        "KHR_materials_variants" => "the default materials show",
        "EXT_mesh_gpu_instancing" => {
            "each node shows its mesh once, at the node, not at its instances"
        }
        "KHR_animation_pointer" => "nothing is animated",
        _ => "what it adds is left out",
    }
}

/// `kind` and the names, `nodes `A`, `B`` (the first few of a long list).
pub fn named(kind: &str, names: &[String]) -> String {
    const SHOWN: usize = 4;
    let mut out = format!("{kind}{}", if names.len() == 1 { "" } else { "s" });
    for (i, n) in names.iter().take(SHOWN).enumerate() {
        out += if i == 0 { " `" } else { ", `" };
        out += n;
        out += "`";
    }
    if names.len() > SHOWN {
        out += &format!(" and {} more", names.len() - SHOWN);
    }
    out
}

fn node_name(n: &gltf::Node) -> String {
    n.name()
        .map_or_else(|| format!("node {}", n.index()), str::to_string)
}

fn material_name(m: &gltf::Material) -> String {
    m.name().map_or_else(
        || format!("material {}", m.index().unwrap_or(0)),
        str::to_string,
    )
}

/// Warnings for what `doc` holds and snell does not read: `placed` are the nodes that show
/// a mesh, `used` says which materials their meshes use (only those are looked at).
pub(super) fn warnings(doc: &gltf::Document, placed: &[usize], used: &[bool]) -> Vec<String> {
    let mut out = vec![];
    let mut is_placed = vec![false; doc.nodes().len()];
    for &i in placed {
        if let Some(p) = is_placed.get_mut(i) {
            *p = true;
        }
    }
    let nodes: Vec<gltf::Node> = doc.nodes().filter(|n| is_placed[n.index()]).collect();

    let skinned: Vec<String> = nodes
        .iter()
        .filter(|n| n.skin().is_some())
        .map(node_name)
        .collect();
    if !skinned.is_empty() {
        out.push(format!(
            "skins are not read ({}): the skinned meshes show as stored (their bind pose), not posed by their joints",
            named("node", &skinned)
        ));
    }

    let mut morphed = vec![];
    let mut weighted = false;
    for n in &nodes {
        let Some(mesh) = n.mesh() else { continue };
        if mesh
            .primitives()
            .any(|p| p.morph_targets().next().is_some())
        {
            morphed.push(node_name(n));
            let weights = n.weights().or(mesh.weights()).unwrap_or(&[]);
            weighted |= weights.iter().any(|w| *w != 0.0);
        }
    }
    if !morphed.is_empty() {
        out.push(format!(
            "morph targets are not read ({}): the meshes show their base shape{}",
            named("node", &morphed),
            if weighted {
                ", not the blend of targets their weights ask for"
            } else {
                ""
            }
        ));
    }

    let animations: Vec<String> = doc
        .animations()
        .map(|a| {
            a.name()
                .map_or_else(|| format!("animation {}", a.index()), str::to_string)
        })
        .collect();
    if !animations.is_empty() {
        out.push(format!(
            "animations are not read ({}): the nodes stand as the file places them",
            named("animation", &animations)
        ));
    }

    // Each material extension left out, with the used materials that have it; every
    // extension any material has (used or not) is a material's, not the file's.
    let mut by_extension: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut on_materials: Vec<String> = vec![];
    let mut partly_clear = vec![];
    for m in doc.materials() {
        let is_used = m.index().is_some_and(|i| used.get(i) == Some(&true));
        for ext in m.extensions().into_iter().flat_map(|e| e.keys()) {
            on_materials.push(ext.clone());
            if is_used {
                by_extension
                    .entry(ext.clone())
                    .or_default()
                    .push(material_name(&m));
            }
        }
        if let Some(t) = m.transmission().filter(|_| is_used) {
            let f = t.transmission_factor();
            if (f > 0.0 && f < 1.0) || t.transmission_texture().is_some() {
                partly_clear.push(material_name(&m));
            }
        }
    }
    for (ext, materials) in &by_extension {
        out.push(format!(
            "{ext} is not read ({}): {}",
            named("material", materials),
            what_is_lost(ext)
        ));
    }
    if !partly_clear.is_empty() {
        out.push(format!(
            "KHR_materials_transmission is read as all or nothing ({}): a factor under 0.5 is opaque, 0.5 or more clear glass, and transmission maps are not read",
            named("material", &partly_clear)
        ));
    }

    for ext in doc.extensions_used() {
        if SUPPORTED_REQUIRED.contains(&ext)
            || FALLBACK_OR_METADATA.contains(&ext)
            || on_materials.iter().any(|m| m == ext)
        {
            continue;
        }
        out.push(format!(
            "the file uses {ext}, which snell does not read: {}",
            what_is_lost(ext)
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_lists_are_cut_short() {
        let names = |n: usize| (0..n).map(|i| format!("N{i}")).collect::<Vec<_>>();
        assert_eq!(named("node", &names(1)), "node `N0`");
        assert_eq!(named("node", &names(2)), "nodes `N0`, `N1`");
        assert_eq!(
            named("material", &names(6)),
            "materials `N0`, `N1`, `N2`, `N3` and 2 more"
        );
    }
}
