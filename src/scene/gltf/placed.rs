//! A glTF file's cameras and KHR_lights_punctual lights as the scene's: `[camera] gltf`
//! takes a camera, a mesh object's `lights = true` adds its file's lights, placed as its
//! meshes are. Photometric units become snell's by the luminous efficacy Blender's exporter
//! multiplies by (683 lm/W): a point light of I candela shines I / 683 per steradian, a
//! directional light of E lux gives E / 683.

use crate::camera::Projection;
use crate::light::{DirectionalLight, Falloff, Light, PointLight, SpotLight};
use crate::math::{Color, Transform, Vec3A};
use crate::mesh_file::gltf::{self, GltfLightKind};
use crate::scene::diag::{DocPath, name_help};
use crate::scene::format::{CameraDef, CameraKind, MeshObjectDef};
use crate::scene::load::Builder;
use crate::scene::load::camera::Placement;

/// Lumens per watt: glTF's photometric units to snell's.
const EFFICACY: f32 = 683.0;

/// Column `c` of a column-major matrix, as a vector.
fn column(m: &[[f32; 4]; 4], c: usize) -> Vec3A {
    Vec3A::new(m[c][0], m[c][1], m[c][2])
}

impl Builder<'_> {
    /// The placement of the camera `[camera] gltf` names (see docs/scene-format.md).
    pub(in crate::scene) fn gltf_camera(
        &mut self,
        d: &CameraDef,
        file: &str,
        path: &DocPath,
    ) -> Option<Placement> {
        let given = [
            (d.look_at.is_some(), "look_at"),
            (d.fov.is_some(), "fov"),
            (d.height.is_some(), "height"),
            (d.kind == CameraKind::Orthographic, "type"),
        ];
        for (_, key) in given.iter().filter(|(g, _)| *g) {
            self.error_help(
                path.key(key),
                format!("`{key}` comes from the glTF file's camera"),
                "remove it, or remove `gltf` to place the camera here",
            );
        }
        let full = self.base_dir.join(file);
        self.files.push(full.clone());
        let scene = match gltf::load_placements(&full) {
            Ok(s) => s,
            Err(e) => {
                self.error(path.key("gltf"), format!("cannot load glTF file: {e}"));
                return None;
            }
        };
        let camera = match &d.gltf_camera {
            None => scene.cameras.first(),
            Some(name) => scene.cameras.iter().find(|c| &c.name == name),
        };
        let Some(c) = camera else {
            let names: Vec<&str> = scene.cameras.iter().map(|c| c.name.as_str()).collect();
            let (at, message, help) = match &d.gltf_camera {
                None => (
                    path.key("gltf"),
                    format!("{file} has no camera"),
                    "add one in the file (in Blender, export with Cameras ticked), or place the camera with look_at".to_string(),
                ),
                Some(name) => (
                    path.key("gltf_camera"),
                    format!("{file} has no camera named `{name}`"),
                    name_help(name, names.iter().copied(), "its cameras", "it has no cameras"),
                ),
            };
            self.error_help(at, message, help);
            return None;
        };
        let position = column(&c.matrix, 3);
        let forward = -column(&c.matrix, 2);
        let up = column(&c.matrix, 1);
        let usable = |v: Vec3A| v.is_finite() && v.length_squared() > 0.0;
        if !(position.is_finite() && usable(forward) && usable(up))
            || forward.normalize().cross(up.normalize()).length() < 1e-6
        {
            self.error(
                path.key("gltf"),
                format!(
                    "camera `{}` of {file} has a node matrix that places no view",
                    c.name
                ),
            );
            return None;
        }
        let (fov, projection) = match c.yfov {
            Some(y) if y > 0.0 && y.to_degrees() < 180.0 => {
                (y.to_degrees(), Projection::Perspective)
            }
            None if c.ymag.is_finite() && c.ymag > 0.0 => (
                45.0,
                Projection::Orthographic {
                    height: 2.0 * c.ymag,
                },
            ),
            _ => {
                self.error(
                    path.key("gltf"),
                    format!(
                        "camera `{}` of {file} has no usable field of view or size",
                        c.name
                    ),
                );
                return None;
            }
        };
        Some(Placement {
            position,
            look_at: position + forward.normalize(),
            up: up.normalize(),
            fov,
            projection,
        })
    }

    /// The lights a mesh object with `lights = true` adds: its glTF file's, placed by the
    /// object's transform (an error for an object that places no glTF file).
    pub(in crate::scene) fn gltf_object_lights(
        &mut self,
        m: &MeshObjectDef,
        path: &DocPath,
    ) -> Vec<Light> {
        let at = path.key("lights");
        let gltf = m.file.as_deref().filter(|f| {
            let f = f.to_ascii_lowercase();
            f.ends_with(".gltf") || f.ends_with(".glb")
        });
        let Some(file) = gltf else {
            self.error_help(
                at,
                "`lights` adds a glTF file's lights, and this object places no glTF `file`",
                "remove it, or place a .gltf or .glb file with file = \"FILE\"",
            );
            return vec![];
        };
        // The object's transform as its meshes got it (checked, and any problem with it
        // reported, when the object was built).
        let placement = m.transform.as_ref().and_then(|t| {
            let v = |a: [f32; 3]| crate::math::Vec3::from(a);
            let ok = [t.scale.0, t.rotate, t.translate]
                .iter()
                .flatten()
                .all(|x| x.is_finite())
                && t.scale.0.iter().all(|&x| x != 0.0);
            ok.then(|| Transform::from_srt(v(t.scale.0), v(t.rotate), v(t.translate)))
                .flatten()
        });
        self.gltf_lights(file, placement.as_ref(), &at)
    }

    /// The KHR_lights_punctual lights of glTF file `file`, placed by their nodes and then
    /// by `placement`.
    fn gltf_lights(
        &mut self,
        file: &str,
        placement: Option<&Transform>,
        path: &DocPath,
    ) -> Vec<Light> {
        let full = self.base_dir.join(file);
        let scene = match gltf::load_placements(&full) {
            Ok(s) => s,
            Err(e) => {
                self.error(path.clone(), format!("cannot load glTF file: {e}"));
                return vec![];
            }
        };
        if scene.lights.is_empty() {
            self.warnings.push(format!(
                "{file} has no KHR_lights_punctual lights, so `lights = true` adds none"
            ));
        }
        let place_point = |p: Vec3A| placement.map_or(p, |t| t.point_to_world(p));
        let place_vector = |v: Vec3A| placement.map_or(v, |t| t.vector_to_world(v));
        let mut out = vec![];
        for l in &scene.lights {
            let color = Color::from(l.color).max(Color::ZERO) * (l.intensity.max(0.0) / EFFICACY);
            let position = place_point(column(&l.matrix, 3));
            let direction = place_vector(-column(&l.matrix, 2)).normalize_or_zero();
            if !color.is_finite() || !position.is_finite() || !direction.is_finite() {
                self.warnings.push(format!(
                    "{file}: light `{}` has a value that is not a number: skipped",
                    l.name
                ));
                continue;
            }
            if direction == Vec3A::ZERO && l.kind != GltfLightKind::Point {
                self.warnings.push(format!(
                    "{file}: light `{}` points nowhere (its node is scaled to 0): skipped",
                    l.name
                ));
                continue;
            }
            out.push(match l.kind {
                GltfLightKind::Point => Light::Point(PointLight {
                    position,
                    color,
                    falloff: Some(Falloff::InverseSquare),
                }),
                GltfLightKind::Directional => {
                    Light::Directional(DirectionalLight { direction, color })
                }
                GltfLightKind::Spot { inner, outer } => {
                    let outer = outer.clamp(1e-4, std::f32::consts::FRAC_PI_2);
                    let inner = inner.clamp(0.0, outer);
                    Light::Spot(SpotLight {
                        position,
                        direction,
                        color,
                        cos_outer: outer.cos(),
                        cos_inner: inner.cos(),
                        falloff: Some(Falloff::InverseSquare),
                    })
                }
            });
        }
        out
    }
}
