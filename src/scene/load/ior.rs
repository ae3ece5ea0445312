//! A material's `ior` to its index and, for glass that disperses light, how the index
//! changes with wavelength: a number, a named glass, or a Cauchy or Sellmeier formula (the
//! parser refuses unknown names and miscounted coefficients) whose index must stay at least
//! 1 over the visible range.

use super::Builder;
use crate::material::dispersion::{D_LINE_NM, Dispersion};
use crate::scene::diag::DocPath;
use crate::scene::format::{DispersionDef, IorDef, MaterialKind};

impl Builder<'_> {
    /// The index `def` gives (a dispersive one's at 587.6 nm), and its dispersion where the
    /// material `kind` bends light by it (phong glass and dielectrics; the others, whose
    /// light does not bend, use the one index). `None` where it is refused (an error is
    /// recorded at `path`).
    pub(super) fn ior(
        &mut self,
        def: &IorDef,
        path: &DocPath,
        kind: MaterialKind,
    ) -> Option<(f32, Option<Dispersion>)> {
        let dispersion = match def {
            IorDef::Value(v) => return Some((self.positive(*v, path), None)),
            // The parser took only the names of `NAMED`.
            IorDef::Named(name) => Dispersion::named(name)?,
            // The parser counted the coefficients.
            IorDef::Formula(DispersionDef::Cauchy([a, b])) => Dispersion::Cauchy { a: *a, b: *b },
            IorDef::Formula(DispersionDef::Sellmeier([b1, b2, b3, c1, c2, c3])) => {
                Dispersion::Sellmeier {
                    b: [*b1, *b2, *b3],
                    c: [*c1, *c2, *c3],
                }
            }
        };
        if let Some((nm, n)) = dispersion.first_bad() {
            let what = if n.is_nan() {
                "is not a real number (a resonance of the formula lies there)".to_string()
            } else {
                format!("is {n}")
            };
            self.error_help(
                path.clone(),
                format!("this index {what} at {nm} nm: it must be at least 1 everywhere from 360 to 830 nm"),
                "check the coefficients' units: wavelengths in micrometres, b and C in micrometres squared",
            );
            return None;
        }
        let bends = matches!(kind, MaterialKind::Phong | MaterialKind::Dielectric);
        Some((dispersion.ior(D_LINE_NM), bends.then_some(dispersion)))
    }
}
