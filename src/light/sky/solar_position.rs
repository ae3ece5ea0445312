//! Where the sun stands for a place, a day and a clock time, by the formulas of Preetham et
//! al.'s appendix (after Iqbal): the declination from the day of the year, the equation of
//! time, and the hour angle; good to about a degree, which is what a picture needs. The
//! scene's axes: `+y` up, north toward `−z`, east toward `+x`.

use crate::math::Vec3A;
use std::f64::consts::PI;

/// The place and time to find the sun for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct When {
    /// Degrees north of the equator (south negative), −90 to 90.
    pub latitude: f64,
    /// Degrees east of Greenwich (west negative).
    pub longitude: f64,
    /// Hours east of UTC of the clock `hour` is read on.
    pub timezone: f64,
    /// Day of the year, 1 (1 January) to 365.
    pub day: f64,
    /// Clock time in hours, 0 to 24 (16.5 is half past four in the afternoon).
    pub hour: f64,
}

/// The unit direction toward a sun `elevation_deg` above the horizon and `azimuth_deg`
/// from north toward east (90 is east).
pub fn from_elevation_azimuth(elevation_deg: f64, azimuth_deg: f64) -> Vec3A {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    Vec3A::new(
        (e.cos() * a.sin()) as f32,
        e.sin() as f32,
        (-e.cos() * a.cos()) as f32,
    )
}

impl When {
    /// The sun's elevation above the horizon and azimuth from north toward east, degrees.
    pub fn elevation_azimuth(&self) -> (f64, f64) {
        let j = self.day;
        let lat = self.latitude.to_radians();
        let declination = 0.4093 * (2.0 * PI * (j - 81.0) / 368.0).sin();
        let equation_of_time = 0.170 * (4.0 * PI * (j - 80.0) / 373.0).sin()
            - 0.129 * (2.0 * PI * (j - 8.0) / 355.0).sin();
        let solar_time =
            self.hour + equation_of_time + (self.longitude - 15.0 * self.timezone) / 15.0;
        let hour_angle = PI * (solar_time - 12.0) / 12.0;
        let (sd, cd) = declination.sin_cos();
        let (sl, cl) = lat.sin_cos();
        let east = -cd * hour_angle.sin();
        let north = sd * cl - cd * sl * hour_angle.cos();
        let up = sd * sl + cd * cl * hour_angle.cos();
        let elevation = up.clamp(-1.0, 1.0).asin().to_degrees();
        let azimuth = east.atan2(north).to_degrees().rem_euclid(360.0);
        (elevation, azimuth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(latitude: f64, day: f64, hour: f64) -> (f64, f64) {
        When {
            latitude,
            longitude: 0.0,
            timezone: 0.0,
            day,
            hour,
        }
        .elevation_azimuth()
    }

    /// Known positions: at an equinox on the equator the noon sun is overhead and it rises
    /// due east; at 40° N on the June solstice the noon sun stands 73.4° high in the south,
    /// and on the December solstice 26.6°; in the afternoon it is in the west.
    #[test]
    fn the_sun_stands_where_the_almanac_puts_it() {
        // (The equation of time puts 12:00 on the clock 7 minutes before noon by the sun.)
        let (e, _) = at(0.0, 81.0, 12.0);
        assert!(e > 87.5, "{e}");
        let (e, a) = at(0.0, 81.0, 6.0);
        assert!(e.abs() < 2.5 && (a - 90.0).abs() < 1.0, "{e} {a}");
        let (e, a) = at(40.0, 172.0, 12.0);
        assert!((e - 73.4).abs() < 0.5 && (a - 180.0).abs() < 2.0, "{e} {a}");
        let (e, _) = at(40.0, 355.0, 12.0);
        assert!((e - 26.6).abs() < 0.5, "{e}");
        let (_, a) = at(40.0, 172.0, 16.0);
        assert!(a > 180.0 && a < 300.0, "{a}");
        // South of the equator the noon sun is in the north.
        let (_, a) = at(-35.0, 172.0, 12.0);
        assert!(!(2.0..358.0).contains(&a), "{a}");
        // Longitude and time zone: 15° east of the zone's meridian, the clock runs an hour
        // behind the sun.
        let shifted = When {
            latitude: 40.0,
            longitude: 15.0,
            timezone: 0.0,
            day: 172.0,
            hour: 11.0,
        }
        .elevation_azimuth();
        let (e, a) = at(40.0, 172.0, 12.0);
        assert!((shifted.0 - e).abs() < 1e-9 && (shifted.1 - a).abs() < 1e-9);
    }

    /// Elevation and azimuth give the scene's axes: north −z, east +x, up +y.
    #[test]
    fn directions_follow_the_axes() {
        let close = |a: Vec3A, b: Vec3A| (a - b).length() < 1e-6;
        assert!(close(from_elevation_azimuth(0.0, 0.0), -Vec3A::Z));
        assert!(close(from_elevation_azimuth(0.0, 90.0), Vec3A::X));
        assert!(close(from_elevation_azimuth(90.0, 30.0), Vec3A::Y));
        assert!(close(from_elevation_azimuth(0.0, 180.0), Vec3A::Z));
    }
}
