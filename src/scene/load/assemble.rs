//! The whole [`Scene`] from a parsed file: settings, camera, textures, materials, lights and
//! objects built in the order they name each other, the warnings about what is defined but
//! unused, then the area lights, the object BVH and the per-object tables the integrators
//! read (transparency, cut-outs, uv needs). Here because it is the one place that sees every
//! part at once.

use super::Builder;
use super::emitters;
use super::group::Placing;
use super::material::MaterialTextures;
use crate::accel::Bvh;
use crate::geometry::Shape;
use crate::light::{Light, LightSampler};
use crate::material::detail::SurfaceDetail;
use crate::scene::diag::DocPath;
use crate::scene::format::{ColorSpaceDef, ObjectDef, SceneFile, TextureDef};
use crate::scene::meshes::Palette;
use crate::scene::{MeshStats, Object, Scene};
use crate::texture::{Mapping, Pattern, Texture};
use std::collections::BTreeMap;
use std::sync::Arc;

impl Builder<'_> {
    pub(super) fn scene(&mut self, def: SceneFile) -> Scene {
        let root = DocPath::default();
        let settings = self.settings(&def.image, &def.integrator, &root.key("image"));
        let camera = self.camera(&def.camera, &root.key("camera"));
        let background = self.color(def.image.background, &root.key("image").key("background"));
        let ambient = self.color(def.world.ambient, &root.key("world").key("ambient"));
        let fog = def.fog.as_ref().map(|f| self.fog(f, &root.key("fog")));
        let environment = def
            .environment
            .as_ref()
            .and_then(|e| self.environment(e, &root.key("environment")));

        let mut textures = vec![];
        let mut texture_names = BTreeMap::new();
        // Textures a material reads as a normal or bump map hold data, not colours.
        let data: std::collections::BTreeSet<&str> = def
            .materials
            .values()
            .flat_map(|m| [&m.normal_map, &m.bump])
            .flatten()
            .map(String::as_str)
            .collect();
        for (name, t) in &def.textures {
            let path = root.key("textures").key(name);
            texture_names.insert(name.clone(), textures.len());
            let data = data.contains(name.as_str());
            if data
                && let TextureDef::Image {
                    color_space: Some(ColorSpaceDef::Srgb),
                    ..
                } = t
            {
                self.warnings.push(format!(
                    "texture `{name}` is a normal or bump map but says color_space = \"srgb\": such maps hold data, stored linear"
                ));
            }
            textures.push(self.texture(t, &path, data));
        }
        let mut used_textures = vec![false; textures.len()];

        let mut materials = vec![];
        let mut material_names = vec![];
        for (name, m) in &def.materials {
            let path = root.key("materials").key(name);
            let mut names = MaterialTextures {
                textures: &mut textures,
                names: &texture_names,
                used: &mut used_textures,
            };
            materials.push(self.material(m, &path, &mut names));
            material_names.push(name.clone());
        }
        for (name, &i) in &texture_names {
            if !used_textures[i] {
                self.warnings.push(format!(
                    "texture `{name}` is defined but no material uses it"
                ));
            }
        }

        let mut lights: Vec<Light> = def
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| self.light(l, &root.key("lights").index(i)))
            .collect();
        // The point, spot and directional lights' names: given, or kind and index.
        let mut light_names: Vec<String> = def
            .lights
            .iter()
            .zip(&lights)
            .enumerate()
            .map(|(i, (d, l))| {
                d.name()
                    .clone()
                    .unwrap_or_else(|| format!("{} #{i}", l.kind_name()))
            })
            .collect();

        let mut used_materials = vec![false; materials.len()];
        let user_materials = materials.len();
        let mut palette = Palette {
            materials: &mut materials,
            names: &mut material_names,
            textures: &mut textures,
        };
        let named_meshes = self.named_meshes(&def.meshes, &root.key("meshes"), &mut palette);
        let mut used_meshes = vec![false; named_meshes.len()];
        let mut objects = vec![];
        let mut used_groups = vec![false; def.groups.len()];
        let mut placing = Placing {
            named_meshes: &named_meshes,
            used_meshes: &mut used_meshes,
            palette: &mut palette,
            user_materials,
        };
        for (i, o) in def.objects.iter().enumerate() {
            let path = root.key("objects").index(i);
            let placed = match o {
                ObjectDef::Group(g) => {
                    self.group_placement(g, i, &path, &def.groups, &mut used_groups, &mut placing)
                }
                _ => self.objects_of(o, i, &path, &mut placing, None),
            };
            for obj in placed {
                if obj.slot_materials.is_empty() {
                    used_materials[obj.material] = true;
                }
                // A combination's solids name scene materials (a mesh's slots are the
                // file's own, after them).
                if matches!(obj.shape, Shape::Csg(_)) {
                    for &m in &obj.slot_materials {
                        used_materials[m] = true;
                    }
                }
                objects.push(obj);
            }
            if let ObjectDef::Mesh(m) = o
                && m.lights == Some(true)
            {
                let added = self.gltf_object_lights(m, &path);
                let object = m.name.clone().unwrap_or_else(|| format!("mesh #{i}"));
                light_names.extend((0..added.len()).map(|j| format!("{object} light #{j}")));
                lights.extend(added);
            }
        }
        for (name, used) in def.groups.keys().zip(&used_groups) {
            if !used {
                self.warnings
                    .push(format!("group `{name}` is defined but no object places it"));
            }
        }
        for ((name, _), used) in named_meshes.iter().zip(&used_meshes) {
            if !used {
                self.warnings
                    .push(format!("mesh `{name}` is defined but no object places it"));
            }
        }
        for (name, used) in material_names.iter().zip(&used_materials) {
            if !used {
                self.warnings.push(format!(
                    "material `{name}` is defined but no object uses it"
                ));
            }
        }
        if objects.is_empty() && self.problems.is_empty() {
            self.warnings
                .push("the scene has no objects: the image will be the background".into());
        }
        for (li, l) in lights.iter().enumerate() {
            if let Some(p) = l.position() {
                for o in objects.iter().filter(|o| o.contains(p)) {
                    let m = &materials[o.material];
                    if !m.is_transparent() {
                        self.warnings.push(format!(
                            "light {li} at {p} is inside object `{}`: nothing outside it will be lit by this light",
                            o.name
                        ));
                    }
                }
            }
        }

        let area_light_of = emitters::area_lights(
            &objects,
            &materials,
            &textures,
            &mut self.warnings,
            &mut lights,
        );
        let environment_light = environment.map(|e| {
            lights.push(Light::Environment(e));
            lights.len() - 1
        });
        // The radius of the bounded objects' box, for a directional light's power.
        let radius = objects
            .iter()
            .filter_map(|o| o.world_bounds)
            .reduce(|a, b| a.union(&b))
            .map_or(1.0, |b| 0.5 * (b.max - b.min).length());
        let light_sampler = LightSampler::new(&lights, radius);
        let start = std::time::Instant::now();
        let accel = Bvh::build(&objects);
        self.stats.object_bvh_time = start.elapsed();
        let cache = &self.mesh_cache;
        let file_of = |m: &Arc<crate::geometry::Mesh>| {
            cache
                .values()
                .flatten()
                .flatten()
                .find(|l| Arc::ptr_eq(&l.mesh, m))
                .map_or_else(MeshStats::default, |l| MeshStats {
                    file: l.file.clone(),
                    label: l.label.clone(),
                    file_images: l.file_images,
                    ..MeshStats::default()
                })
        };
        let mut stats = std::mem::take(&mut self.stats);
        stats.record_objects(&objects, file_of);
        self.stats = stats;
        self.stats.bvh_bytes += accel.bytes();
        // An object with several materials (a mesh with an MTL file) counts as transparent,
        // or as reading uv (through any texture of any of them), when any of them does.
        let materials_of = |o: &Object| -> Vec<usize> {
            if o.slot_materials.is_empty() {
                vec![o.material]
            } else {
                o.slot_materials.clone()
            }
        };
        // Meshes a normal map reads through their own uv get tangents (MikkTSpace's where the
        // file gave none).
        for o in &objects {
            if let Shape::Mesh(m) = &o.shape
                && materials_of(o).iter().any(|&i| {
                    matches!(materials[i].detail, Some(SurfaceDetail::Normal { texture, .. })
                        if textures[texture].mapping.keeps_uv_axes())
                })
            {
                m.ensure_tangents();
            }
        }
        let cutouts: Vec<bool> = objects
            .iter()
            .map(|o| {
                materials_of(o)
                    .iter()
                    .any(|&m| materials[m].cutout.is_some())
            })
            .collect();
        // Shadow rays look through cut-outs as through glass (their holes, that is).
        let transparent: Vec<bool> = objects
            .iter()
            .zip(&cutouts)
            .map(|(o, &cut)| {
                cut || materials_of(o)
                    .iter()
                    .any(|&m| materials[m].is_transparent())
            })
            .collect();
        let transparent_objects = (0..objects.len()).filter(|&i| transparent[i]).collect();
        // Whether a texture one of object `o`'s materials reads is one `like` says.
        let reads = |o: &Object, like: &dyn Fn(&Texture) -> bool| {
            materials_of(o)
                .iter()
                .any(|&m| materials[m].textures().iter().any(|&t| like(&textures[t])))
        };
        let needs_uv = objects
            .iter()
            .map(|o| {
                reads(o, &|t| {
                    !matches!(t.pattern, Pattern::Solid(_)) && t.mapping.reads_shape_uv()
                })
            })
            .collect();
        let needs_uv1 = objects
            .iter()
            .map(|o| {
                matches!(&o.shape, Shape::Mesh(m) if m.has_second_uv())
                    && reads(o, &|t| matches!(t.mapping, Mapping::SecondUv { .. }))
            })
            .collect();
        let textured = materials
            .iter()
            .map(|m| {
                m.textures()
                    .iter()
                    .any(|&t| !matches!(textures[t].pattern, Pattern::Solid(_)))
            })
            .collect();
        let base_only = materials
            .iter()
            .map(|m| {
                let mut varying = m
                    .textures()
                    .into_iter()
                    .filter(|&t| !matches!(textures[t].pattern, Pattern::Solid(_)));
                varying.all(|t| t == m.texture)
            })
            .collect();
        let dispersive = materials.iter().any(|m| m.dispersion.is_some());
        let alone_inside = crate::scene::inside::alone_inside(&objects, &cutouts);
        let mut scene = Scene {
            camera,
            settings,
            background,
            environment_light,
            ambient,
            fog,
            objects,
            materials,
            textures,
            texture_names,
            material_names,
            lights,
            light_names,
            lpe: vec![],
            area_light_of,
            light_sampler,
            warnings: std::mem::take(&mut self.warnings),
            accel,
            transparent,
            transparent_objects,
            needs_uv,
            needs_uv1,
            textured,
            base_only,
            any_cutout: cutouts.contains(&true),
            alone_inside,
            dispersive,
            cutouts,
            stats: std::mem::take(&mut self.stats),
            limits: self.limits,
            files: vec![],
            animation: None,
            source: "".into(),
            frame: 0,
        };
        scene.warnings.extend(scene.lighting_warning());
        scene.lpe = self.light_path_expressions(&def.image.lpe, &root.key("image"), &scene);
        scene
    }
}
