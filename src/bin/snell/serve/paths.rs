//! Light paths in the preview: the picture split by a preset light path expression (`GET
//! /lpe/direct.png`, the View menu's "light paths"), and a pixel's light shared out by the
//! kind of path that brought it, with a few of each kind's paths to draw (`GET
//! /paths?x=&y=`). Both follow the path tracer's paths, whichever integrator the preview
//! shows (the page says so).

use super::http::{Asked, Context, PixelQuery, blocking, error, json, scene_and_pixel};
use axum::extract::{Path, Query, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use snell::lpe::{LpeSet, Preset, Request, expand};
use snell::output::tone::{Tone, ToneCurve};
use snell::render::RenderOptions;
use snell::scene::IntegratorKind;
use std::sync::Arc;

/// Samples per pixel of a light path view at most: a view is rendered on request, whole.
const VIEW_SPP: u32 = 16;
/// Samples of a pixel shared out by kind.
const PIXEL_SAMPLES: u32 = 256;

/// The query of a light path view: a cache-busting generation, and the picture's exposure
/// and tone curve (optional).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ViewQuery {
    #[allow(dead_code)]
    g: Option<u64>,
    exposure: Option<f32>,
    tone: Option<String>,
}

impl ViewQuery {
    /// The exposure and tone curve asked for (each `None` where not given), or the answer
    /// that refuses them (boxed: a response is large).
    pub(crate) fn asked(&self) -> Result<(Option<f32>, Option<ToneCurve>), Box<Response>> {
        if self
            .exposure
            .is_some_and(|e| !(e.is_finite() && e.abs() <= 20.0))
        {
            return Err(Box::new(error(
                StatusCode::BAD_REQUEST,
                "exposure is a number of stops from -20 to 20",
            )));
        }
        match self.tone.as_deref().map(ToneCurve::from_name) {
            None => Ok((self.exposure, None)),
            Some(Some(c)) => Ok((self.exposure, Some(c))),
            Some(None) => Err(Box::new(error(
                StatusCode::BAD_REQUEST,
                "tone is clamp, reinhard or aces",
            ))),
        }
    }
}

/// `GET /lpe/NAME.png`: preset NAME's image of the scene shown (at most [`VIEW_SPP`]
/// samples a pixel), tone mapped like the picture.
pub(crate) async fn view(
    State(ctx): State<Arc<Context>>,
    Path(file): Path<String>,
    q: Asked<ViewQuery>,
) -> Response {
    let preset = file
        .strip_suffix(".png")
        .and_then(|n| Preset::ALL.into_iter().find(|p| p.name() == n))
        .filter(|&p| p != Preset::PerLight);
    let Some(preset) = preset else {
        return error(StatusCode::NOT_FOUND, "no such light path view");
    };
    let Ok(Query(q)) = q else {
        return error(
            StatusCode::BAD_REQUEST,
            "the view takes g, exposure and tone",
        );
    };
    let (exposure, curve) = match q.asked() {
        Ok(asked) => asked,
        Err(refused) => return *refused,
    };
    let (scene, generation) = {
        let s = ctx.shared.lock();
        (s.scene.clone(), s.generation)
    };
    let Some(scene) = scene else {
        return error(StatusCode::NOT_FOUND, "no scene yet");
    };
    blocking(move || {
        // A Whitted preview's scene, path traced.
        let scene = if scene.settings.integrator.kind == IntegratorKind::Path {
            scene
        } else {
            let mut s = (*scene).clone();
            s.settings.integrator.kind = IntegratorKind::Path;
            Arc::new(s)
        };
        let key = (generation, preset.name().to_string());
        let cached = {
            let mut cache = ctx.lpe_cache.lock().unwrap_or_else(|e| e.into_inner());
            cache.retain(|((g, _), _)| *g == generation);
            cache
                .iter()
                .find(|(k, _)| *k == key)
                .map(|(_, i)| i.clone())
        };
        let image = match cached {
            Some(i) => i,
            None => {
                let named = expand(&[Request::Preset(preset)], &scene);
                let set = match LpeSet::new(&scene, &named) {
                    Ok(s) => s,
                    Err(e) => {
                        return error(StatusCode::INTERNAL_SERVER_ERROR, &e.error.to_string());
                    }
                };
                let options = RenderOptions {
                    threads: None,
                    progress: &|_| {},
                    cancel: None,
                    region: None,
                };
                let spp = scene.settings.spp.min(VIEW_SPP);
                match snell::render::lpe::render_lpe_samples(&scene, &set, spp, &options) {
                    Ok(mut r) => {
                        let i = Arc::new(r.layers.remove(0));
                        let mut cache = ctx.lpe_cache.lock().unwrap_or_else(|e| e.into_inner());
                        cache.push((key, i.clone()));
                        i
                    }
                    Err(e) => return error(StatusCode::INTERNAL_SERVER_ERROR, &e.to_string()),
                }
            }
        };
        let t = scene.settings.tone;
        let tone = Tone {
            exposure: exposure.unwrap_or(t.exposure),
            curve: curve.unwrap_or(t.curve),
        };
        match snell::output::encode_display(&image, &tone, None) {
            Ok(png) => ([(header::CONTENT_TYPE, "image/png")], png).into_response(),
            Err(e) => error(StatusCode::INTERNAL_SERVER_ERROR, &e.to_string()),
        }
    })
    .await
}

/// `GET /paths?x=&y=`: pixel (x, y)'s light shared out by the kind of path that brought it
/// ([`snell::lpe::pixel::pixel_paths`], over [`PIXEL_SAMPLES`] of its samples).
pub(crate) async fn pixel(State(ctx): State<Arc<Context>>, q: Asked<PixelQuery>) -> Response {
    let (scene, x, y) = match scene_and_pixel(&ctx, q) {
        Ok(v) => v,
        Err(r) => return *r,
    };
    blocking(
        move || match snell::lpe::pixel::pixel_paths(&scene, (x, y), PIXEL_SAMPLES) {
            Ok(doc) => json(&doc),
            Err(e) => error(StatusCode::UNPROCESSABLE_ENTITY, &e),
        },
    )
    .await
}
