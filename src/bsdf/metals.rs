//! Measured complex indices of refraction of common metals, as linear-RGB fits (the values
//! renderers such as Mitsuba and Tungsten use for their named conductors, from measured
//! spectra integrated against the sRGB primaries), so a scene can say `"Au"` instead of six
//! numbers.

use crate::math::Color;

/// A metal by its chemical symbol: `(eta, k)`, or `None` for a name snell does not know.
pub fn named(name: &str) -> Option<(Color, Color)> {
    let (eta, k) = match name {
        "Au" => (
            [0.143_119, 0.374_957, 1.442_48],
            [3.983_16, 2.385_72, 1.603_22],
        ),
        "Ag" => (
            [0.155_265, 0.116_723, 0.138_342],
            [4.828_35, 3.122_25, 2.146_96],
        ),
        "Cu" => (
            [0.200_438, 0.924_033, 1.102_21],
            [3.912_95, 2.452_85, 2.142_19],
        ),
        "Al" => (
            [1.657_46, 0.880_369, 0.521_229],
            [9.223_87, 6.269_52, 4.837],
        ),
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
