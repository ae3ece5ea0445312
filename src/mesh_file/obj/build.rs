//! The end of a parse: the corners gathered into the mesh's vertices and triangles, the
//! materials assigned triangle by triangle, and what was ignored summarised in warnings.

use super::*;

impl Parser<'_> {
    pub(super) fn finish(mut self) -> Result<MeshData, MeshError> {
        let counts = [
            self.positions.len(),
            self.texcoords.len(),
            self.normals.len(),
        ];
        for kind in [Kind::Vertex, Kind::TexCoord, Kind::Normal] {
            if let Some((max, line)) = self.forward[kind as usize]
                && max as usize >= counts[kind as usize]
            {
                let count = counts[kind as usize];
                return Err(self.err(
                    line,
                    format!(
                        "{} index {} is out of range: the file has {}",
                        kind.name(),
                        u64::from(max) + 1,
                        if count == 0 {
                            format!("no {}", kind.plural())
                        } else {
                            format!("only {}", count_of(count, kind.name(), kind.plural()))
                        }
                    ),
                ));
            }
        }
        let mut warnings = std::mem::take(&mut self.warnings);
        self.summarise_ignored(&mut warnings);
        let mut mesh = self.build(&mut warnings)?;
        self.assign_materials(&mut mesh, &mut warnings);
        mesh.warnings = warnings;
        mesh.unread_mtl = std::mem::take(&mut self.unread_mtl);
        mesh.mtl_files = self.loaded_mtl.iter().cloned().collect();
        mesh.mtl_files.sort();
        crate::mesh_file::drop_degenerate(&mut mesh);
        Ok(mesh)
    }

    pub(super) fn summarise_ignored(&self, warnings: &mut Vec<String>) {
        for ((count, line), what) in [
            (self.lines_ignored, "line (`l`) element"),
            (self.points_ignored, "point (`p`) element"),
        ] {
            if count > 0 {
                let s = if count == 1 { "" } else { "s" };
                warnings.push(format!(
                    "ignored {count} {what}{s} (first on line {line}); only faces are rendered"
                ));
            }
        }
        for (keyword, line, count) in &self.unknown {
            let times = if *count > 1 {
                format!(" ({count} times)")
            } else {
                String::new()
            };
            warnings.push(format!(
                "line {line}: unknown statement `{keyword}` ignored{times}"
            ));
        }
        if self.unknown_other > 0 {
            warnings.push(format!(
                "{} other unknown statements ignored",
                self.unknown_other
            ));
        }
    }

    /// Turns file-index triangles into output vertices: positions as they are when faces
    /// use positions only, otherwise one vertex per distinct (v, vt, vn) triple.
    pub(super) fn build(&mut self, warnings: &mut Vec<String>) -> Result<MeshData, MeshError> {
        let tri_v = std::mem::take(&mut self.tri_v);
        if !self.any_vt && !self.any_vn {
            return Ok(MeshData {
                positions: std::mem::take(&mut self.positions),
                triangles: tri_v,
                ..MeshData::default()
            });
        }
        let (want_vt, want_vn) = (self.any_vt, self.any_vn);
        let corner_count = tri_v.len() * 3;
        let mut map: HashMap<(u32, u32, u32), u32, BuildHasherDefault<FxHasher>> =
            HashMap::with_capacity_and_hasher(corner_count.min(1 << 20), Default::default());
        let mut positions = Vec::with_capacity(corner_count.min(1 << 20) / 2);
        let mut uvs = Vec::new();
        let mut normals = Vec::new();
        let mut triangles = Vec::with_capacity(tri_v.len());
        let (mut missing_vt, mut missing_vn) = (0usize, 0usize);
        for (t, v) in tri_v.iter().enumerate() {
            let vt = self.tri_vt.get(t).copied().unwrap_or([NONE; 3]);
            let vn = self.tri_vn.get(t).copied().unwrap_or([NONE; 3]);
            let mut out = [0u32; 3];
            for (k, slot) in out.iter_mut().enumerate() {
                let key = (v[k], vt[k], vn[k]);
                if let Some(&i) = map.get(&key) {
                    *slot = i;
                    continue;
                }
                let Ok(i) = u32::try_from(positions.len()) else {
                    return Err(MeshError::new(self.path, "too many distinct vertices"));
                };
                positions.push(
                    self.positions
                        .get(key.0 as usize)
                        .copied()
                        .unwrap_or_default(),
                );
                if want_vt {
                    let uv = self.texcoords.get(key.1 as usize).copied();
                    missing_vt += usize::from(uv.is_none());
                    uvs.push(uv.unwrap_or_default());
                }
                if want_vn {
                    let n = self.normals.get(key.2 as usize).copied();
                    missing_vn += usize::from(n.is_none());
                    normals.push(n.unwrap_or_default());
                }
                map.insert(key, i);
                *slot = i;
            }
            triangles.push(out);
        }
        if missing_vt > 0 {
            warnings.push(format!(
                "{} no texture coordinates while others have; they were given (0, 0)",
                count_of(missing_vt, "vertex has", "vertices have")
            ));
        }
        if missing_vn > 0 {
            warnings.push(format!(
                "{} no normal while others have; their normals were set to zero",
                count_of(missing_vn, "vertex has", "vertices have")
            ));
        }
        Ok(MeshData {
            positions,
            normals,
            uvs,
            triangles,
            ..MeshData::default()
        })
    }

    pub(super) fn assign_materials(&mut self, mesh: &mut MeshData, warnings: &mut Vec<String>) {
        mesh.materials = std::mem::take(&mut self.materials);
        if self.tri_mat.is_empty() {
            return;
        }
        let mut unknown = 0usize;
        let resolved: Vec<u32> = self
            .used_names
            .iter()
            .map(|(name, line)| match self.material_lookup.get(name) {
                Some(&i) => i,
                None => {
                    unknown += 1;
                    // Name a few; a file with thousands of unknown names gets one more line.
                    if unknown <= MAX_UNKNOWN_KINDS {
                        warnings.push(format!(
                            "line {line}: `usemtl {name}`: no such material in the loaded MTL \
                             files; its faces get no material"
                        ));
                    }
                    NONE
                }
            })
            .collect();
        if unknown > MAX_UNKNOWN_KINDS {
            warnings.push(format!(
                "{} more unknown material names used",
                unknown - MAX_UNKNOWN_KINDS
            ));
        }
        let mut per_triangle: Vec<u32> = self
            .tri_mat
            .iter()
            .map(|&u| resolved.get(u as usize).copied().unwrap_or(NONE))
            .collect();
        if per_triangle.iter().all(|&m| m == NONE) {
            return;
        }
        if per_triangle.contains(&NONE) {
            let default = mesh.materials.len() as u32;
            mesh.materials.push(MtlMaterial {
                name: NO_MATERIAL_NAME.to_string(),
                ..MtlMaterial::default()
            });
            for m in per_triangle.iter_mut().filter(|m| **m == NONE) {
                *m = default;
            }
        }
        mesh.triangle_materials = per_triangle;
    }
}
