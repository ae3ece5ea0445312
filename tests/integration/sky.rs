//! `[environment] type = "sky"`: the daylight sky and its sun light a floor with the integral
//! of their radiance (the sky's by quadrature, the sun's disk in closed form), high and low;
//! `scale` and `sun_scale` do what they say; the two outdoor scenes differ only in the hour.

use super::environment::floor_irradiance;
use super::{repo, scratch};
use snell::integrator::Path as PathTracer;
use snell::light::EnvironmentSource;
use snell::math::Color;
use snell::render::render;
use snell::scene::{Format, Scene, load_str};
use std::f32::consts::PI;

fn floor_under(sky: &str, spp: u32) -> Scene {
    let dir = scratch("sky");
    let text = format!(
        "[image]\nwidth = 16\nheight = 16\nsamples = {spp}\nmax_depth = 2\n\
         [integrator]\ntype = \"path\"\n\
         [camera]\nposition = [0, 5, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nfov = 20\n\
         [environment]\ntype = \"sky\"\n{sky}\n\
         [materials.m]\ntype = \"diffuse\"\ncolor = 0.5\n\
         [[objects]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"m\"\n"
    );
    let scene = load_str(&text, &dir.join("t.toml"), &dir, Format::Toml)
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    scene
}

fn floor_mean(scene: &Scene) -> Color {
    let img = render(scene, &PathTracer, Some(2), &|_| {}).unwrap().image;
    img.pixels.iter().copied().sum::<Color>() / img.pixels.len() as f32
}

/// The irradiance on an upward floor: the sky by the midpoint rule over the hemisphere
/// (finer than the baked map's texels), the sun's disk as its radiance times its solid
/// angle times the cosine of its height.
fn irradiance(scene: &Scene) -> (Color, Color) {
    let env = scene.environment().unwrap();
    let EnvironmentSource::Sky(sky) = &env.source else {
        panic!("not a sky")
    };
    let sun = sky.sun().unwrap();
    let sky_e = floor_irradiance(|d| env.radiance(d) - sun.radiance(d));
    let sun_e = sun.disk_radiance() * sun.solid_angle() * sun.axis().y;
    (sky_e, sun_e)
}

#[test]
fn the_sky_and_its_sun_light_a_floor_with_their_integral() {
    for place in [
        "sun_elevation = 50\nsun_azimuth = 120",
        "latitude = 45\nday = 172\nhour = 17\nturbidity = 6",
    ] {
        let scene = floor_under(place, 256);
        let (sky_e, sun_e) = irradiance(&scene);
        let sun_share = sun_e.y / (sun_e.y + sky_e.y);
        assert!(
            sun_share > 0.1,
            "{place}: the sun gives {sun_share} of the light"
        );
        let expect = (sky_e + sun_e) * (0.5 / PI);
        let got = floor_mean(&scene);
        for (g, x) in got.to_array().into_iter().zip(expect.to_array()) {
            assert!(
                (g - x).abs() < 0.015 * x,
                "{place}: floor {got:?}, the integral gives {expect:?}"
            );
        }
    }
}

/// `scale` multiplies everything, `sun_scale = 0` leaves the sky alone: renders of the same
/// seed scale exactly, and the sky alone is the sky's part of the integral.
#[test]
fn scale_and_sun_scale_do_what_they_say() {
    let place = "sun_elevation = 35";
    let base = floor_mean(&floor_under(place, 16));
    let double = floor_mean(&floor_under(&format!("{place}\nscale = 2"), 16));
    assert!((double - 2.0 * base).abs().max_element() < 1e-4 * base.max_element());
    let scene = floor_under(&format!("{place}\nsun_scale = 0"), 256);
    let EnvironmentSource::Sky(sky) = &scene.environment().unwrap().source else {
        panic!("not a sky")
    };
    assert!(sky.sun().is_none());
    let with_sun = floor_under(place, 16);
    let (sky_e, _) = irradiance(&with_sun);
    let expect = sky_e * (0.5 / PI);
    let got = floor_mean(&scene);
    for (g, x) in got.to_array().into_iter().zip(expect.to_array()) {
        assert!(
            (g - x).abs() < 0.015 * x,
            "floor {got:?}, sky alone {expect:?}"
        );
    }
}

/// The noon and sunset scenes are one courtyard: they differ in their comments, the hour and
/// the exposure only.
#[test]
fn the_outdoor_scenes_differ_only_in_the_hour() {
    let strip = |name: &str| -> Vec<String> {
        std::fs::read_to_string(repo(name))
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with('#'))
            .filter(|l| !l.starts_with("hour") && !l.starts_with("exposure"))
            .map(str::to_string)
            .collect()
    };
    assert_eq!(
        strip("scenes/outdoor-noon.toml"),
        strip("scenes/outdoor-sunset.toml")
    );
}
