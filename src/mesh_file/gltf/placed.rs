//! A glTF file's cameras and KHR_lights_punctual lights, each with the world matrix of the
//! node that places it.

/// A camera placed by a node: it looks down its local -z with +y up (glTF's convention).
#[derive(Clone, Debug, PartialEq)]
pub struct GltfCamera {
    /// The camera's name, or its node's, or `camera N`.
    pub name: String,
    /// Vertical field of view in radians (perspective), or `None` for orthographic.
    pub yfov: Option<f32>,
    /// Orthographic: half the view's height.
    pub ymag: f32,
    /// Its node's world matrix (column-major).
    pub matrix: [[f32; 4]; 4],
}

/// A KHR_lights_punctual light placed by a node (spot and directional lights shine down
/// the node's local -z).
#[derive(Clone, Debug, PartialEq)]
pub struct GltfLight {
    /// The light's name, or `light N`.
    pub name: String,
    /// What kind.
    pub kind: GltfLightKind,
    /// Linear RGB.
    pub color: [f32; 3],
    /// Candela (point, spot) or lux (directional).
    pub intensity: f32,
    /// Its node's world matrix (column-major).
    pub matrix: [[f32; 4]; 4],
}

/// The kinds of KHR_lights_punctual light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GltfLightKind {
    /// From a point, every way.
    Point,
    /// From a point, in a cone: inner and outer half-angles in radians.
    Spot {
        /// Where the light starts to fall off.
        inner: f32,
        /// Where it reaches zero.
        outer: f32,
    },
    /// Parallel, from far away.
    Directional,
}

/// The camera `node` places, if any, at `world`.
pub(super) fn camera(node: &gltf::Node, world: [[f32; 4]; 4]) -> Option<GltfCamera> {
    let c = node.camera()?;
    use gltf::camera::Projection as P;
    let (yfov, ymag) = match c.projection() {
        P::Perspective(p) => (Some(p.yfov()), 0.0),
        P::Orthographic(o) => (None, o.ymag()),
    };
    Some(GltfCamera {
        name: c
            .name()
            .or(node.name())
            .map_or_else(|| format!("camera {}", c.index()), str::to_string),
        yfov,
        ymag,
        matrix: world,
    })
}

/// The light `node` places, if any, at `world`.
pub(super) fn light(node: &gltf::Node, world: [[f32; 4]; 4]) -> Option<GltfLight> {
    let l = node.light()?;
    use gltf::khr_lights_punctual::Kind as K;
    Some(GltfLight {
        name: l
            .name()
            .map_or_else(|| format!("light {}", l.index()), str::to_string),
        kind: match l.kind() {
            K::Point => GltfLightKind::Point,
            K::Directional => GltfLightKind::Directional,
            K::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => GltfLightKind::Spot {
                inner: inner_cone_angle,
                outer: outer_cone_angle,
            },
        },
        color: l.color(),
        intensity: l.intensity(),
        matrix: world,
    })
}
