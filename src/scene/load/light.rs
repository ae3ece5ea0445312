//! `[[lights]]` to a [`Light`]: point, directional and spot lights, their placement and
//! aim checked (a spot light's by `look_at` or `direction`) and their colour scaled by
//! intensity.

use super::Builder;
use crate::light::{DirectionalLight, Light, PointLight, SpotLight};
use crate::math::Vec3A;
use crate::scene::diag::DocPath;
use crate::scene::format::LightDef;

impl Builder<'_> {
    pub(super) fn light(&mut self, d: &LightDef, path: &DocPath) -> Light {
        match d {
            LightDef::Point {
                position,
                falloff,
                color,
                intensity,
                ..
            } => Light::Point(PointLight {
                position: self.point(*position, &path.key("position")),
                color: self.color(*color, &path.key("color"))
                    * self.non_negative(*intensity, &path.key("intensity")),
                falloff: *falloff,
            }),
            LightDef::Directional {
                direction,
                color,
                intensity,
                ..
            } => Light::Directional(DirectionalLight {
                direction: self.direction(*direction, &path.key("direction")),
                color: self.color(*color, &path.key("color"))
                    * self.non_negative(*intensity, &path.key("intensity")),
            }),
            LightDef::Spot {
                position,
                falloff,
                look_at,
                direction,
                color,
                intensity,
                angle,
                soft_edge,
                ..
            } => {
                let position = self.point(*position, &path.key("position"));
                let direction = match (look_at, direction) {
                    (Some(_), Some(_)) => {
                        self.error_help(
                            path.key("direction"),
                            "a spot light takes `look_at` or `direction`, not both",
                            "remove one of them",
                        );
                        -Vec3A::Y
                    }
                    (None, None) => {
                        self.error_help(
                            path.clone(),
                            "a spot light needs `look_at` or `direction`",
                            "add `look_at = [x, y, z]`, the point the cone is aimed at",
                        );
                        -Vec3A::Y
                    }
                    (Some(l), None) => {
                        let target = self.point(*l, &path.key("look_at"));
                        let d = target - position;
                        if d.length_squared() == 0.0 {
                            self.error(
                                path.key("look_at"),
                                "the spot light looks at its own position",
                            );
                            -Vec3A::Y
                        } else {
                            d.normalize()
                        }
                    }
                    (None, Some(d)) => self.direction(*d, &path.key("direction")),
                };
                let angle = self.finite(*angle, &path.key("angle"));
                if !(angle > 0.0 && angle < 180.0) {
                    self.error(path.key("angle"), format!("the cone's half-angle must be between 0 and 180 degrees (exclusive), not {angle}"));
                }
                let soft = self.in_range(*soft_edge, 0.0, angle.max(0.0), &path.key("soft_edge"));
                Light::Spot(SpotLight {
                    position,
                    direction,
                    color: self.color(*color, &path.key("color"))
                        * self.non_negative(*intensity, &path.key("intensity")),
                    cos_outer: angle.to_radians().cos(),
                    cos_inner: (angle - soft).to_radians().cos(),
                    falloff: *falloff,
                })
            }
        }
    }
}
