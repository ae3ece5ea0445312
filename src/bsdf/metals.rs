//! Measured complex indices of refraction of common metals in linear RGB, so a scene can
//! say `"Au"` instead of six numbers: the values Mitsuba 3.9.1's `scalar_rgb` variant gives
//! its conductors of these names (their measured spectra integrated against the sRGB
//! primaries), as it prints them (`mi.traverse(mi.load_dict({'type': 'conductor',
//! 'material': 'Au'}))`); src/bsdf/mitsuba_tests.rs checks the reflectance they give.

use crate::math::Color;

/// A metal by its chemical symbol: `(eta, k)`, or `None` for a name snell does not know.
pub fn named(name: &str) -> Option<(Color, Color)> {
    let (eta, k) = match name {
        "Au" => (
            [0.143_036, 0.375_307, 1.442_05],
            [3.983, 2.385_56, 1.603_36],
        ),
        "Ag" => (
            [0.155_276, 0.116_728, 0.138_388],
            [4.828_35, 3.122_22, 2.146_9],
        ),
        "Cu" => (
            [0.201_005, 0.923_75, 1.102_22],
            [3.913_26, 2.453_05, 2.142_09],
        ),
        "Al" => ([1.657_5, 0.880_405, 0.521_244], [9.223_81, 6.269_5, 4.837]),
        _ => return None,
    };
    Some((Color::from(eta), Color::from(k)))
}

/// The names [`named`] knows, for messages.
pub const NAMES: [&str; 4] = ["Au", "Ag", "Cu", "Al"];

#[cfg(test)]
mod tests {
    use super::super::fresnel::conductor_rgb;
    use super::*;

    /// Seen straight on: gold reflects red over blue, copper red most, silver and aluminium
    /// nearly everything, evenly.
    #[test]
    fn the_metals_have_their_colours() {
        let r = |name| {
            let (eta, k) = named(name).unwrap();
            conductor_rgb(1.0, eta, k)
        };
        let (au, ag, cu, al) = (r("Au"), r("Ag"), r("Cu"), r("Al"));
        assert!(
            au.x > 0.9 && au.x > au.y && au.y > au.z && au.z < 0.5,
            "gold {au}"
        );
        assert!(cu.x > 0.9 && cu.x > cu.y && cu.y > cu.z, "copper {cu}");
        assert!(ag.min_element() > 0.9, "silver {ag}");
        assert!(
            al.min_element() > 0.85 && al.max_element() - al.min_element() < 0.05,
            "aluminium {al}"
        );
        assert!(NAMES.iter().all(|n| named(n).is_some()) && named("Fe").is_none());
    }
}
