//! The sampling lab in the browser (`/lab`): a material's BSDF tested against its density
//! (snell::lab) on request, with a bounded number of samples and only the keys a form sends.

use super::http::{Asked, blocking, error, json};
use axum::http::StatusCode;
use axum::response::Response;
use snell::lab::{BINS, leaving_at, material_bsdf, warp_test};

/// Samples per test: a quarter of the command line's million, so an answer takes a fraction
/// of a second and a page cannot keep the server busy for long.
const SAMPLES: usize = 1 << 18;

/// What the lab's form sends; any other key is refused.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BsdfQuery {
    #[serde(rename = "type")]
    kind: String,
    roughness: Option<f32>,
    ior: Option<f32>,
    /// A named metal (`Au`, `Ag` ...), for a conductor.
    metal: Option<String>,
    /// Degrees from the normal, 0 to 89.
    angle: Option<f32>,
}

/// `GET /lab/bsdf?type=plastic&roughness=0.3&angle=40`: the test's figures and both
/// histograms, as JSON; 400 with the loader's words for a material it cannot build.
pub(crate) async fn bsdf(q: Asked<BsdfQuery>) -> Response {
    let q = match q {
        Ok(q) => q.0,
        Err(e) => return error(StatusCode::BAD_REQUEST, &e.body_text()),
    };
    let angle = q.angle.unwrap_or(40.0);
    if !(0.0..=89.0).contains(&angle) {
        return error(
            StatusCode::BAD_REQUEST,
            "angle: degrees from the normal, 0 to 89",
        );
    }
    let mut params = vec![];
    for (key, v) in [("roughness", q.roughness), ("ior", q.ior)] {
        match v {
            Some(v) if !v.is_finite() => {
                return error(StatusCode::BAD_REQUEST, &format!("{key}: not a number"));
            }
            Some(v) => params.push((key.to_string(), v.to_string())),
            None => {}
        }
    }
    if let Some(m) = &q.metal {
        if m.is_empty() || m.len() > 16 || !m.chars().all(|c| c.is_ascii_alphanumeric()) {
            return error(StatusCode::BAD_REQUEST, "metal: a metal's name, such as Au");
        }
        params.push(("metal".into(), format!("\"{m}\"")));
    }
    blocking(move || {
        let lab = match material_bsdf(&q.kind, &params) {
            Ok(lab) => lab,
            Err(e) => return error(StatusCode::BAD_REQUEST, &e.to_string()),
        };
        match warp_test(&lab.bsdf, leaving_at(angle), SAMPLES, BINS) {
            Ok(t) => json(&serde_json::json!({
                "title": lab.title,
                "angle": angle,
                "samples": t.samples,
                "specular": t.specular,
                "absorbed": t.absorbed,
                "chi2": t.chi2.chi2,
                "dof": t.chi2.dof,
                "p": t.chi2.p,
                "passed": t.passed(),
                "inconsistent": t.inconsistent,
                "bins": [BINS.theta, BINS.phi],
                "observed": t.observed,
                "expected": t.expected,
            })),
            Err(e) => error(StatusCode::UNPROCESSABLE_ENTITY, &e),
        }
    })
    .await
}
