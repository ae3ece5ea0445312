//! Area lights: the emitting shapes the path tracer samples, in world space. Rectangles
//! (parallelograms), disks and triangles are sampled uniformly by area, spheres uniformly
//! within the cone of directions they fill. Emission leaves the front side (where the
//! shape's outward normal points) or both.

use super::{Emission, Emit, Falloff, LightSample};
use crate::geometry::{
    Disk, Rect, Sphere, SurfaceSample, Triangle, area_to_solid_angle, area_to_solid_angle_across,
};
use crate::math::{Color, Ray, Vec2, Vec3A};

/// An emitting shape in world space.
#[derive(Clone, Debug, PartialEq)]
pub enum Emitter {
    /// A parallelogram.
    Rect(Rect),
    /// A disk.
    Disk(Disk),
    /// A triangle.
    Triangle(Triangle),
    /// A sphere (its centre in world space).
    Sphere(Sphere),
}

impl Emitter {
    /// Where `ray` first meets the shape (its point and outward normal), if it does: what a
    /// light's density for a direction is found from.
    pub fn intersect(&self, ray: &Ray) -> Option<(Vec3A, Vec3A)> {
        use crate::geometry::Intersect;
        let at = |s: &dyn Intersect| {
            let hit = s.intersect(ray, f32::INFINITY)?;
            let surface = s.surface(ray.at(hit.t), &hit, false);
            Some((surface.point, surface.normal))
        };
        match self {
            Emitter::Rect(s) => at(s),
            Emitter::Disk(s) => at(s),
            Emitter::Triangle(s) => at(s),
            Emitter::Sphere(s) => at(s),
        }
    }

    /// The shape's area.
    pub fn area(&self) -> f32 {
        match self {
            Emitter::Rect(s) => s.area(),
            Emitter::Disk(s) => s.area(),
            Emitter::Triangle(s) => s.area(),
            Emitter::Sphere(s) => s.area(),
        }
    }
}

/// An emitting object, as a light.
#[derive(Clone, Debug, PartialEq)]
pub struct AreaLight {
    /// Its shape, in world space.
    pub emitter: Emitter,
    /// Radiance leaving it, linear RGB; where a texture gives it, the texture's mean (its
    /// power is taken from this).
    pub radiance: Color,
    /// The texture (index into the scene's list) giving the radiance point by point, if any:
    /// a sample's radiance is then read there ([`crate::Scene::emission_at`]).
    pub texture: Option<usize>,
    /// Whether both sides emit.
    pub two_sided: bool,
    /// The object it is.
    pub object: usize,
    /// One over the shape's area (the density of a point sampled by area), worked out once:
    /// a rectangle's and a triangle's area take a square root.
    inv_area: f32,
}

/// Which area light each part of an object is: a hit on it names its light through this.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum ObjectLights {
    /// The object is no light (or one light sampling cannot reach).
    #[default]
    None,
    /// The whole object is this light.
    Whole(u32),
    /// A mesh: per lane of its triangles (a hit's `prim`), the light, or `u32::MAX` where
    /// the triangle does not emit.
    Triangles(Box<[u32]>),
}

impl ObjectLights {
    /// The light that triangle `prim` (0 for shapes other than meshes) is part of.
    #[inline]
    pub fn at(&self, prim: u32) -> Option<usize> {
        match self {
            ObjectLights::None => None,
            ObjectLights::Whole(l) => Some(*l as usize),
            ObjectLights::Triangles(t) => t
                .get(prim as usize)
                .filter(|&&l| l != u32::MAX)
                .map(|&l| l as usize),
        }
    }
}

/// A point on an area light seen from a point in the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaSample {
    /// The point on the light.
    pub point: Vec3A,
    /// The light's front normal there.
    pub normal: Vec3A,
    /// The density per unit solid angle at the point it was sampled from.
    pub pdf: f32,
}

impl AreaLight {
    /// A light of `radiance` (linear RGB; a texture's mean where `texture` gives it) on
    /// `emitter`, which is object `object` of the scene.
    pub fn new(
        emitter: Emitter,
        radiance: Color,
        texture: Option<usize>,
        two_sided: bool,
        object: usize,
    ) -> Self {
        let inv_area = 1.0 / emitter.area();
        AreaLight {
            emitter,
            radiance,
            texture,
            two_sided,
            object,
            inv_area,
        }
    }

    /// The radiance leaving a point of front normal `normal` toward `dir` (unit, away from
    /// the light).
    #[inline]
    pub fn emitted(&self, normal: Vec3A, dir: Vec3A) -> Color {
        if self.two_sided || normal.dot(dir) > 0.0 {
            self.radiance
        } else {
            Color::ZERO
        }
    }

    /// A point of the light chosen for `from`, with its density per unit solid angle.
    pub fn sample(&self, from: Vec3A, u: Vec2) -> Option<AreaSample> {
        self.sample_toward(from, u).map(|(s, _, _)| s)
    }

    /// [`AreaLight::sample`], with the unit direction from `from` to the point and the
    /// distance: a shape sampled by area finds them with its density, from one square root
    /// and with the divisions side by side rather than one after another.
    #[inline]
    fn sample_toward(&self, from: Vec3A, u: Vec2) -> Option<(AreaSample, Vec3A, f32)> {
        let by_area = |p: SurfaceSample| {
            let d = p.point - from;
            let (pdf, distance) = area_to_solid_angle_across(self.inv_area, d, p.normal);
            (pdf.is_finite() && pdf > 0.0).then(|| {
                let (point, normal) = (p.point, p.normal);
                (AreaSample { point, normal, pdf }, d / distance, distance)
            })
        };
        let toward = |p: AreaSample| {
            let d = p.point - from;
            let distance = d.length();
            (p, d / distance, distance)
        };
        match &self.emitter {
            // (The shapes' own densities, `1 / area`, go unused and are not worked out.)
            Emitter::Rect(s) => by_area(s.sample_area(u)),
            Emitter::Disk(s) => by_area(s.sample_area(u)),
            Emitter::Triangle(s) => by_area(s.sample_area(u)),
            Emitter::Sphere(s) => {
                let p = s.sample_solid_angle(from, u)?;
                (p.pdf > 0.0 && p.pdf.is_finite()).then(|| {
                    toward(AreaSample {
                        point: p.point,
                        normal: p.normal,
                        pdf: p.pdf,
                    })
                })
            }
        }
    }

    /// The density per unit solid angle with which [`AreaLight::sample`] for `from` picks
    /// `point` (on the light, front normal `normal`).
    pub fn pdf(&self, from: Vec3A, point: Vec3A, normal: Vec3A) -> f32 {
        match &self.emitter {
            Emitter::Sphere(s) => s.solid_angle_pdf(from, point),
            _ => area_to_solid_angle(self.inv_area, from, point, normal).unwrap_or(0.0),
        }
    }
}

impl Emit for AreaLight {
    /// A point of the light chosen for `from` ([`AreaLight::sample`]) and the radiance it
    /// sends there (the untextured radiance: the caller reads a texture's at the point).
    fn sample_li(&self, from: Vec3A, u: Vec2, _default: Falloff) -> Option<LightSample> {
        let (s, to_light, distance) = self.sample_toward(from, u)?;
        let radiance = self.emitted(s.normal, -to_light);
        (radiance != Color::ZERO && distance > 0.0).then_some(LightSample {
            to_light,
            distance,
            radiance,
            pdf: s.pdf,
        })
    }

    /// Its flux in luminance: `pi * area * L` a side.
    fn power(&self, _radius: f32) -> f32 {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        std::f32::consts::PI * self.emitter.area() * crate::math::luminance(self.radiance) * sides
    }

    fn is_delta(&self) -> bool {
        false
    }

    fn kind_name(&self) -> &'static str {
        "area"
    }

    /// A point uniform over the light's area and a cosine-weighted direction from it (on
    /// either side, half and half, for a two-sided light): the radiance times the cosine
    /// over both densities, `L pi / pdf_area` (twice that for two sides). A textured
    /// light's radiance is its mean: the caller reads the texture at the point
    /// ([`crate::Scene::emission_from`]).
    fn sample_le(&self, u: Vec2, v: Vec2, _world: (Vec3A, f32)) -> Option<Emission> {
        let s = match &self.emitter {
            Emitter::Rect(e) => e.sample_area(u),
            Emitter::Disk(e) => e.sample_area(u),
            Emitter::Triangle(e) => e.sample_area(u),
            Emitter::Sphere(e) => e.sample_area(u),
        };
        if !(s.pdf > 0.0 && s.pdf.is_finite()) {
            return None;
        }
        let (normal, v, sides) = match (self.two_sided, v.x < 0.5) {
            (true, true) => (-s.normal, Vec2::new(2.0 * v.x, v.y), 2.0),
            (true, false) => (s.normal, Vec2::new(2.0 * v.x - 1.0, v.y), 2.0),
            (false, _) => (s.normal, v, 1.0),
        };
        let v = v.min(Vec2::splat(1.0 - f32::EPSILON / 2.0));
        let local = crate::math::sampling::cosine_hemisphere(v);
        (local.z > 0.0).then(|| Emission {
            origin: s.point,
            dir: crate::math::Frame::from_axis(normal).to_world(local),
            normal: Some(normal),
            pdf_point: s.pdf,
            weight: self.radiance * (std::f32::consts::PI * sides / s.pdf),
            unfalling: false,
        })
    }

    /// A point by area (as [`Emit::sample_le`] picks it), a direction by the cosine about
    /// the normal of the side it leaves (each side half the time, for a two-sided light).
    fn pdf_le(&self, normal: Option<Vec3A>, dir: Vec3A, _radius: f32) -> (f32, f32) {
        let cos = normal.map_or(0.0, |n| n.dot(dir));
        let (cos, sides) = if self.two_sided {
            (cos.abs(), 0.5)
        } else {
            (cos, 1.0)
        };
        let pdf_dir = if cos > 0.0 {
            cos * std::f32::consts::FRAC_1_PI * sides
        } else {
            0.0
        };
        (self.inv_area, pdf_dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::chi2::{SphereBins, chi2_sphere};

    fn light(emitter: Emitter) -> AreaLight {
        AreaLight::new(emitter, Color::ONE, None, false, 0)
    }

    /// Each shape's sampling, seen from a point, has the solid-angle density `pdf` says:
    /// chi-square over the directions toward the samples.
    #[test]
    fn sampling_matches_the_solid_angle_pdf() {
        let from = Vec3A::new(0.3, -0.2, 0.1);
        let lights = [
            light(Emitter::Rect(
                Rect::new(
                    Vec3A::new(-1.0, 1.0, -0.5),
                    Vec3A::new(2.0, 0.0, 0.0),
                    Vec3A::new(0.3, 0.0, 1.5),
                )
                .unwrap(),
            )),
            light(Emitter::Disk(Disk::new(
                Vec3A::new(0.0, 0.0, 1.5),
                Vec3A::new(0.2, 0.1, -1.0),
                1.0,
            ))),
            light(Emitter::Triangle(
                Triangle::new(
                    Vec3A::new(-1.0, -1.0, 1.0),
                    Vec3A::new(1.0, -1.2, 0.8),
                    Vec3A::new(0.0, 1.0, 1.3),
                )
                .unwrap(),
            )),
            light(Emitter::Sphere(Sphere {
                center: Vec3A::new(1.0, 0.5, 1.0),
                radius: 0.7,
            })),
        ];
        for l in &lights {
            let result = chi2_sphere(
                &format!("{:?}", l.emitter),
                SphereBins::default(),
                |u| l.sample(from, u).map(|s| (s.point - from).normalize()),
                |dir| {
                    // The point of the light in `dir`, if any: where a ray meets it.
                    let ray = crate::math::Ray::new(from, dir);
                    let shape = match &l.emitter {
                        Emitter::Rect(s) => crate::geometry::Shape::Rect(s.clone()),
                        Emitter::Disk(s) => crate::geometry::Shape::Disk(s.clone()),
                        Emitter::Triangle(s) => crate::geometry::Shape::Triangle(s.clone()),
                        Emitter::Sphere(s) => crate::geometry::Shape::Sphere(s.clone()),
                    };
                    match shape.intersect(&ray, f32::INFINITY) {
                        Some(h) => {
                            let p = ray.at(h.t);
                            let n = shape.surface(p, &h, false).normal;
                            l.pdf(from, p, n)
                        }
                        None => 0.0,
                    }
                },
            );
            if let Err(e) = result {
                panic!("{e}");
            }
        }
    }

    #[test]
    fn emits_from_the_front_unless_two_sided() {
        let mut l = light(Emitter::Disk(Disk::new(Vec3A::ZERO, Vec3A::Z, 1.0)));
        assert_eq!(l.emitted(Vec3A::Z, Vec3A::new(0.0, 0.6, 0.8)), Color::ONE);
        assert_eq!(l.emitted(Vec3A::Z, -Vec3A::Z), Color::ZERO);
        l.two_sided = true;
        assert_eq!(l.emitted(Vec3A::Z, -Vec3A::Z), Color::ONE);
        assert!((l.power(1.0) - 2.0 * std::f32::consts::PI * std::f32::consts::PI).abs() < 1e-4);
    }
}
