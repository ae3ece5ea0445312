//! The file's objects as the scene's, and groups (`[groups.NAME]`, placed by objects of type
//! `group`): each placement adds the group's objects, each placed by its own transform and
//! then the placement's. Analytic shapes are a few bytes each, so a placement copies them;
//! a group's meshes share their triangles as every mesh placement does.

use super::super::diag::{DocPath, name_help};
use super::super::meshes::{LoadedMesh, Palette};
use super::Builder;
use crate::math::Transform;
use crate::scene::Object;
use crate::scene::format::{GroupDef, GroupObjectDef, ObjectDef};
use std::collections::BTreeMap;

/// What placing objects reads and adds to while the scene is built.
pub(super) struct Placing<'a, 'p> {
    /// The meshes under `[meshes]`, loaded.
    pub named_meshes: &'a [(String, Option<Vec<LoadedMesh>>)],
    /// Which of them an object placed.
    pub used_meshes: &'a mut [bool],
    /// The scene's materials and textures so far.
    pub palette: &'a mut Palette<'p>,
    /// How many of the materials are the file's own (`[materials]`).
    pub user_materials: usize,
}

/// A group's placement: its transform, name, and the material for objects without one.
pub(super) struct Placement {
    pub transform: Option<Transform>,
    pub name: String,
    pub material: Option<(String, DocPath)>,
}

impl Builder<'_> {
    /// One object of the file (or of a group, placed by `placement`) as the scene's
    /// objects: one, or one per mesh a glTF file's nodes place.
    pub(super) fn objects_of(
        &mut self,
        o: &ObjectDef,
        i: usize,
        path: &DocPath,
        placing: &mut Placing,
        placement: Option<&Placement>,
    ) -> Vec<Object> {
        let parts: Vec<Option<LoadedMesh>> = match o {
            ObjectDef::Mesh(m) => match self.mesh_object(
                m,
                path,
                placing.named_meshes,
                placing.used_meshes,
                placing.palette,
            ) {
                Some(parts) => parts.into_iter().map(Some).collect(),
                None => return vec![],
            },
            _ => vec![None],
        };
        let names = &placing.palette.names[..placing.user_materials];
        parts
            .into_iter()
            .filter_map(|mesh| self.object(o, i, path, names, mesh, placement))
            .collect()
    }

    /// An object of type `group`: the group's objects, placed.
    pub(super) fn group_placement(
        &mut self,
        g: &GroupObjectDef,
        i: usize,
        path: &DocPath,
        groups: &BTreeMap<String, GroupDef>,
        used: &mut [bool],
        placing: &mut Placing,
    ) -> Vec<Object> {
        let Some(k) = groups.keys().position(|n| *n == g.group) else {
            let help = name_help(
                &g.group,
                groups.keys().map(String::as_str),
                "defined groups",
                "define it under [groups.NAME] with its objects",
            );
            self.error_help(
                path.key("group"),
                format!("no group named `{}`", g.group),
                help,
            );
            return vec![];
        };
        used[k] = true;
        if g.uv_scale.is_some() {
            self.error_help(
                path.key("uv_scale"),
                "a group placement has no uv of its own",
                "give uv_scale on the group's objects",
            );
        }
        let (name, def) = groups
            .iter()
            .nth(k)
            .expect("the index was found among the keys");
        let placement = Placement {
            transform: g
                .transform
                .as_ref()
                .and_then(|t| self.transform(t, &path.key("transform"))),
            name: g.name.clone().unwrap_or_else(|| format!("{name} #{i}")),
            material: g.material.clone().map(|m| (m, path.key("material"))),
        };
        let at = DocPath::default().key("groups").key(name).key("objects");
        let mut out = vec![];
        for (j, o) in def.objects.iter().enumerate() {
            let member = at.index(j);
            match o {
                ObjectDef::Group(_) => {
                    self.error_help(
                        member.key("type"),
                        "a group's objects cannot be groups",
                        "list the inner group's objects in this one",
                    );
                    continue;
                }
                ObjectDef::Mesh(m) if m.lights.is_some() => {
                    self.error(
                        member.key("lights"),
                        "a glTF file's lights are not placed from a group",
                    );
                }
                _ => {}
            }
            out.extend(self.objects_of(o, j, &member, placing, Some(&placement)));
        }
        out
    }
}
