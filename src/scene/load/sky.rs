//! `[environment] type = "sky"` to the sky's settings: the sun placed by one of the three
//! ways the format allows, each number in the range the model holds for.

use super::Builder;
use crate::light::sky::solar_position::{When, from_elevation_azimuth};
use crate::light::sky::{SkySettings, TURBIDITY_RANGE};
use crate::math::Vec3A;
use crate::scene::diag::DocPath;
use crate::scene::format::EnvironmentDef;

/// What the error says when the sun has no place.
const PLACES: &str =
    "give `sun_elevation` (and `sun_azimuth`), or `sun_direction`, or `latitude`, `day` and `hour`";

impl Builder<'_> {
    /// The settings of a sky definition, or `None` (with the problems recorded).
    pub(super) fn sky(&mut self, d: &EnvironmentDef, path: &DocPath) -> Option<SkySettings> {
        let EnvironmentDef::Sky {
            sun_direction,
            sun_elevation,
            sun_azimuth,
            latitude,
            longitude,
            timezone,
            day,
            hour,
            turbidity,
            scale,
            sun_scale,
            sun_size,
            ..
        } = d
        else {
            return None;
        };
        let (lo, hi) = TURBIDITY_RANGE;
        let turbidity = self.in_range(*turbidity, lo as f32, hi as f32, &path.key("turbidity"));
        let scale = self.non_negative(*scale, &path.key("scale"));
        let sun_scale = self.non_negative(*sun_scale, &path.key("sun_scale"));
        let size = self.positive(*sun_size, &path.key("sun_size"));
        let size = self.in_range(size, 0.0, 30.0, &path.key("sun_size"));

        let by_angles = sun_elevation.is_some() || sun_azimuth.is_some();
        let by_date = [latitude, longitude, timezone, day, hour]
            .iter()
            .any(|k| k.is_some());
        let ways = [sun_direction.is_some(), by_angles, by_date];
        if ways.iter().filter(|w| **w).count() > 1 {
            let key = if sun_direction.is_some() && by_angles {
                "sun_elevation"
            } else if by_date {
                ["latitude", "longitude", "timezone", "day", "hour"]
                    .into_iter()
                    .zip([latitude, longitude, timezone, day, hour])
                    .find_map(|(k, v)| v.is_some().then_some(k))
                    .unwrap_or("latitude")
            } else {
                "sun_direction"
            };
            self.error_help(
                path.key(key),
                "places the sun a second way: the sky takes one of them",
                PLACES,
            );
            return None;
        }
        let sun_direction = if let Some(v) = sun_direction {
            let d = self.direction(*v, &path.key("sun_direction"));
            if d.y < 0.0 {
                self.error_help(
                    path.key("sun_direction"),
                    format!(
                        "points below the horizon (y = {:.3}): the sky model covers daylight only",
                        d.y
                    ),
                    "the sun must be at or above the horizon: y >= 0",
                );
                return None;
            }
            d
        } else if by_angles {
            let Some(e) = sun_elevation else {
                self.error_help(
                    path.key("sun_azimuth"),
                    "needs `sun_elevation` beside it",
                    PLACES,
                );
                return None;
            };
            let e = self.in_range(*e, 0.0, 90.0, &path.key("sun_elevation"));
            let a = self.finite(sun_azimuth.unwrap_or(180.0), &path.key("sun_azimuth"));
            from_elevation_azimuth(e as f64, a as f64)
        } else if by_date {
            self.sun_on_date([*latitude, *longitude, *timezone, *day, *hour], path)?
        } else {
            self.error_help(path.clone(), "the sky needs the sun's place", PLACES);
            return None;
        };
        Some(SkySettings {
            sun_direction,
            turbidity: turbidity as f64,
            scale,
            sun_scale,
            sun_diameter_deg: size as f64,
        })
    }

    /// The sun's direction from `[latitude, longitude, timezone, day, hour]`, the first,
    /// fourth and fifth required.
    fn sun_on_date(&mut self, keys: [Option<f32>; 5], path: &DocPath) -> Option<Vec3A> {
        let [latitude, longitude, timezone, day, hour] = keys;
        let mut missing = Vec::new();
        for (name, v) in [("latitude", latitude), ("day", day), ("hour", hour)] {
            if v.is_none() {
                missing.push(name);
            }
        }
        if !missing.is_empty() {
            self.error_help(
                path.clone(),
                format!("the sun's place by date needs `{}` too", missing.join("`, `")),
                "give `latitude`, `day` and `hour` (and `longitude` and `timezone` if the hour is a clock's)",
            );
            return None;
        }
        let when = When {
            latitude: self.in_range(latitude.unwrap_or(0.0), -90.0, 90.0, &path.key("latitude"))
                as f64,
            longitude: self.in_range(
                longitude.unwrap_or(0.0),
                -180.0,
                180.0,
                &path.key("longitude"),
            ) as f64,
            timezone: self.in_range(timezone.unwrap_or(0.0), -12.0, 14.0, &path.key("timezone"))
                as f64,
            day: self.in_range(day.unwrap_or(1.0), 1.0, 366.0, &path.key("day")) as f64,
            hour: self.in_range(hour.unwrap_or(12.0), 0.0, 24.0, &path.key("hour")) as f64,
        };
        let (elevation, azimuth) = when.elevation_azimuth();
        if elevation < 0.0 {
            self.error_help(
                path.key("hour"),
                format!(
                    "the sun is {:.1}° below the horizon then (latitude {}, day {}, hour {}): the sky model covers daylight only",
                    -elevation, when.latitude, when.day, when.hour
                ),
                "choose an hour between sunrise and sunset",
            );
            return None;
        }
        Some(from_elevation_azimuth(elevation, azimuth))
    }
}
