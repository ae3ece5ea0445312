//! A material's `ior` to its index and, for glass that disperses light, how the index
//! changes with wavelength: a number, a named glass (with a did-you-mean), or a Cauchy or
//! Sellmeier formula whose coefficients are counted and whose index must stay at least 1
//! over the visible range.

use super::Builder;
use crate::material::dispersion::{D_LINE_NM, Dispersion, NAMED};
use crate::scene::diag::{DocPath, name_help};
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
            IorDef::Named(name) => match Dispersion::named(name) {
                Some(d) => d,
                None => {
                    self.error_help(
                        path.clone(),
                        format!("no glass named `{name}`"),
                        name_help(name, NAMED.iter().map(|(n, _)| *n), "the named glasses", ""),
                    );
                    return None;
                }
            },
            IorDef::Formula(f) => {
                let (name, c, want, form) = match f {
                    DispersionDef::Cauchy(c) => ("Cauchy", c, 2, "[a, b]"),
                    DispersionDef::Sellmeier(c) => ("Sellmeier", c, 6, "[B1, B2, B3, C1, C2, C3]"),
                };
                if c.len() != want {
                    self.error_help(
                        path.clone(),
                        format!(
                            "a {name} index takes {want} coefficients, {} given",
                            c.len()
                        ),
                        format!("give {form} (in micrometres squared where they have units)"),
                    );
                    return None;
                }
                match f {
                    DispersionDef::Cauchy(_) => Dispersion::Cauchy { a: c[0], b: c[1] },
                    DispersionDef::Sellmeier(_) => Dispersion::Sellmeier {
                        b: [c[0], c[1], c[2]],
                        c: [c[3], c[4], c[5]],
                    },
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
