//! The preview's denoised picture (`/denoised.png`): the newest frame denoised by Open Image
//! Denoise, guided by the scene's albedo and normal images (made once a render and kept
//! while its frames have the same first samples), tone mapped as the page asks; in a build
//! without the `denoise` feature, a 404 that says how to build one.

use super::http::{Asked, Context, blocking, error};
use super::paths::ViewQuery;
use super::preview::Frame;
use axum::extract::{Query, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use snell::denoise::guides::GUIDE_SAMPLES;
use snell::output::tone::Tone;
use std::sync::Arc;

/// `GET /denoised.png?g=FRAME&exposure=STOPS&tone=CURVE`: the newest frame, denoised (`g`
/// only tells frames apart for the browser's cache).
pub(crate) async fn picture(State(ctx): State<Arc<Context>>, q: Asked<ViewQuery>) -> Response {
    if !snell::denoise::AVAILABLE {
        return error(
            StatusCode::NOT_FOUND,
            &snell::denoise::DenoiseError::NotBuilt.to_string(),
        );
    }
    let Ok(Query(q)) = q else {
        return error(
            StatusCode::BAD_REQUEST,
            "the picture takes g, exposure and tone",
        );
    };
    let (exposure, curve) = match q.asked() {
        Ok(asked) => asked,
        Err(refused) => return *refused,
    };
    let frame = ctx.shared.lock().frame.clone();
    let Some(frame) = frame else {
        return error(StatusCode::NOT_FOUND, "no picture yet");
    };
    let tone = Tone {
        exposure: exposure.unwrap_or(frame.tone.exposure),
        curve: curve.unwrap_or(frame.tone.curve),
    };
    blocking(move || {
        let denoised = guides(&ctx, &frame)
            .and_then(|g| snell::denoise::denoise(&frame.image, &g).map_err(|e| e.to_string()))
            .and_then(|img| {
                snell::output::encode_display(&img, &tone, None).map_err(|e| e.to_string())
            });
        match denoised {
            Ok(png) => ([(header::CONTENT_TYPE, "image/png")], png).into_response(),
            Err(e) => error(
                StatusCode::INTERNAL_SERVER_ERROR,
                &format!("cannot denoise the picture: {e}"),
            ),
        }
    })
    .await
}

/// The guides of `frame` (from the scene it was rendered from): those kept, where they were
/// made for its render and its first samples (guides follow at most [`GUIDE_SAMPLES`] of
/// them), else made now and kept.
fn guides(ctx: &Context, frame: &Frame) -> Result<Arc<snell::denoise::Guides>, String> {
    let key = (frame.generation, frame.spp.min(GUIDE_SAMPLES));
    if let Some((k, g)) = &*ctx.guides_cache.lock().unwrap_or_else(|p| p.into_inner())
        && *k == key
    {
        return Ok(g.clone());
    }
    let options = snell::render::RenderOptions {
        threads: None,
        progress: &|_| {},
        cancel: None,
        region: None,
    };
    let made = Arc::new(
        snell::denoise::guides(&frame.scene, frame.spp, &options).map_err(|e| e.to_string())?,
    );
    *ctx.guides_cache.lock().unwrap_or_else(|p| p.into_inner()) = Some((key, made.clone()));
    Ok(made)
}
