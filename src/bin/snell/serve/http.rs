//! The preview's HTTP routes (axum), and the rules every request passes first: a Host
//! header that names this server (so that a page elsewhere cannot reach it through DNS
//! rebinding), no Origin but this server's own (no cross-origin reads, event streams or
//! camera changes), and only the routes below. No part of a URL is ever used as a path on
//! disk. Work that takes time (encoding, debug views, explaining) runs off the async
//! threads.

use super::preview::{Frame, Shared};
use axum::Router;
use axum::body::Body;
use axum::extract::rejection::QueryRejection;
use axum::extract::{DefaultBodyLimit, Path, Query, Request, State};
use axum::http::{HeaderValue, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use snell::camera::CameraView;
use snell::integrator::aov::Aov;
use snell::math::Vec3A;
use snell::output::tone::{Tone, ToneCurve};
use snell::render::render_aovs;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

const PAGE: &str = include_str!("page/index.html");
/// The page's script, ES modules by concern: `app.js` is the entry and imports the others.
const SCRIPT: &str = include_str!("page/app.js");
const STATE: &str = include_str!("page/state.js");
const PICTURE: &str = include_str!("page/picture.js");
const EXPLAIN: &str = include_str!("page/explain.js");
const PATHS: &str = include_str!("page/paths.js");
const CAMERA: &str = include_str!("page/camera.js");
const STYLE: &str = include_str!("page/style.css");
/// The sampling lab's page and script.
const LAB_PAGE: &str = include_str!("page/lab.html");
const LAB_SCRIPT: &str = include_str!("page/lab.js");
const JS: &str = "text/javascript; charset=utf-8";

/// Event streams open at once; more are refused, so that tabs left open cannot use up the
/// server.
const MAX_STREAMS: usize = 64;
/// A stream says something this often, so that a closed tab is noticed.
const HEARTBEAT: Duration = Duration::from_secs(15);
/// The largest request body read (a camera is a few hundred bytes).
const MAX_BODY: usize = 4096;
/// JPEG quality of the frames.
const QUALITY: u8 = 90;

/// An encoded picture, shared by the answers that send it.
type Encoded = Arc<Vec<u8>>;

/// What a frame was encoded from: the frame, the exposure's bits and the curve.
type FrameKey = (u64, u32, ToneCurve);

/// Which guides: the render's generation and the first samples of its pixels they follow.
pub(super) type GuidesKey = (u64, u32);

/// What the handlers share.
pub(crate) struct Context {
    pub shared: Arc<Shared>,
    /// Host header values this server answers to (`127.0.0.1:PORT`, `localhost:PORT` ...);
    /// empty: any (the server was told to listen on every interface).
    pub hosts: Vec<String>,
    /// Event streams open now.
    streams: AtomicUsize,
    /// The last frame encoded, by frame and tone.
    frame_cache: Mutex<Option<(FrameKey, Encoded)>>,
    /// The debug views of the render shown, by generation and view.
    view_cache: Mutex<Vec<((u64, Aov), Encoded)>>,
    /// The light path views of the render shown, linear, by generation and preset.
    pub(super) lpe_cache: Mutex<Vec<(LpeKey, Arc<snell::film::Image>)>>,
    /// The denoiser's guides of the render shown, by generation and the samples they follow.
    pub(super) guides_cache: Mutex<Option<(GuidesKey, Arc<snell::denoise::Guides>)>>,
}

impl Context {
    pub(crate) fn new(shared: Arc<Shared>, hosts: Vec<String>) -> Self {
        Context {
            shared,
            hosts,
            streams: AtomicUsize::new(0),
            frame_cache: Mutex::new(None),
            view_cache: Mutex::new(vec![]),
            lpe_cache: Mutex::new(vec![]),
            guides_cache: Mutex::new(None),
        }
    }
}

type Ctx = State<Arc<Context>>;

/// A light path view's key: the render's generation and the preset's name.
pub(super) type LpeKey = (u64, String);

/// The routes, behind the Host and Origin rules.
pub(crate) fn router(ctx: Arc<Context>) -> Router {
    Router::new()
        .route("/", get(|| async { page("text/html; charset=utf-8", PAGE) }))
        .route("/app.js", get(|| async { page(JS, SCRIPT) }))
        .route("/state.js", get(|| async { page(JS, STATE) }))
        .route("/picture.js", get(|| async { page(JS, PICTURE) }))
        .route("/explain.js", get(|| async { page(JS, EXPLAIN) }))
        .route("/paths.js", get(|| async { page(JS, PATHS) }))
        .route("/camera.js", get(|| async { page(JS, CAMERA) }))
        .route("/style.css", get(|| async { page("text/css; charset=utf-8", STYLE) }))
        .route("/lab", get(|| async { page("text/html; charset=utf-8", LAB_PAGE) }))
        .route("/lab.js", get(|| async { page(JS, LAB_SCRIPT) }))
        .route("/lab/bsdf", get(super::lab::bsdf))
        .route("/events", get(events))
        .route("/status", get(|State(ctx): Ctx| async move { json(&status(&ctx)) }))
        .route("/frame.jpg", get(frame))
        .route("/view/{file}", get(view))
        .route("/explain", get(explain))
        .route("/lpe/{file}", get(super::paths::view))
        .route("/denoised.png", get(super::denoised::picture))
        .route("/paths", get(super::paths::pixel))
        .route("/pick", get(pick))
        .route("/camera", post(camera))
        .route(
            "/camera/reset",
            post(|State(ctx): Ctx| async move {
                ctx.shared.set_camera(None);
                json(&serde_json::json!({ "ok": true }))
            }),
        )
        .fallback(|| async {
            error(
                StatusCode::NOT_FOUND,
                "not found: the preview serves its page, its pictures and the explain data, nothing else",
            )
        })
        .layer(DefaultBodyLimit::max(MAX_BODY))
        .layer(middleware::from_fn_with_state(ctx.clone(), guard))
        .with_state(ctx)
}

/// The Host rule, the Origin rule where a browser sends one, and the headers every answer
/// carries.
async fn guard(State(ctx): Ctx, req: Request, next: Next) -> Response {
    let why = {
        let header = |name: header::HeaderName| {
            req.headers()
                .get(name)
                .and_then(|v| v.to_str().ok())
                .map(str::to_string)
        };
        let (host, origin) = (header(header::HOST), header(header::ORIGIN));
        refusal(&ctx.hosts, host.as_deref(), origin.as_deref())
    };
    let mut response = match why {
        Some(why) => error(StatusCode::FORBIDDEN, why),
        None => next.run(req).await,
    };
    let h = response.headers_mut();
    for (name, value) in [
        (header::CACHE_CONTROL, "no-store"),
        (header::X_CONTENT_TYPE_OPTIONS, "nosniff"),
        (header::X_FRAME_OPTIONS, "DENY"),
        (header::REFERRER_POLICY, "no-referrer"),
        (
            header::CONTENT_SECURITY_POLICY,
            "default-src 'self'; img-src 'self' blob: data:; connect-src 'self'; frame-ancestors 'none'",
        ),
    ] {
        h.insert(name, HeaderValue::from_static(value));
    }
    response
}

/// Why a request with these Host and Origin headers is refused, if it is: `hosts` are the
/// Host values this server answers to (empty: any).
fn refusal(hosts: &[String], host: Option<&str>, origin: Option<&str>) -> Option<&'static str> {
    let ours = |h: &str| hosts.iter().any(|a| a.eq_ignore_ascii_case(h));
    if !hosts.is_empty() && !host.is_some_and(ours) {
        return Some("this server answers only to its own address (the Host header names another)");
    }
    let origin = origin?;
    let same = match origin.strip_prefix("http://") {
        Some(o) if hosts.is_empty() => host == Some(o),
        Some(o) => ours(o),
        None => false,
    };
    (!same).then_some("cross-origin requests are refused")
}

fn page(kind: &'static str, text: &'static str) -> Response {
    ([(header::CONTENT_TYPE, kind)], text).into_response()
}

fn bytes(kind: &'static str, body: Arc<Vec<u8>>) -> Response {
    (
        [(header::CONTENT_TYPE, kind)],
        Body::from(body.as_ref().clone()),
    )
        .into_response()
}

pub(super) fn json(value: &serde_json::Value) -> Response {
    (
        [(header::CONTENT_TYPE, "application/json")],
        value.to_string(),
    )
        .into_response()
}

pub(super) fn error(status: StatusCode, message: &str) -> Response {
    (
        status,
        [(header::CONTENT_TYPE, "text/plain; charset=utf-8")],
        format!("{message}\n"),
    )
        .into_response()
}

/// Runs `f` off the async threads.
pub(super) async fn blocking(f: impl FnOnce() -> Response + Send + 'static) -> Response {
    tokio::task::spawn_blocking(f).await.unwrap_or_else(|e| {
        error(
            StatusCode::INTERNAL_SERVER_ERROR,
            &format!("the request failed: {e}"),
        )
    })
}

/// The query of `/frame.jpg`: both optional; percent-encoded values are decoded.
#[derive(serde::Deserialize)]
struct FrameQuery {
    exposure: Option<f32>,
    tone: Option<String>,
}

/// The query that names a pixel: `x=COLUMN&y=ROW`.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PixelQuery {
    x: u32,
    y: u32,
}

/// A query string read into `T` by axum (serde_urlencoded: percent-decoding, `+` as a
/// space), or why it does not fit (a value of the wrong kind, a key given twice).
pub(super) type Asked<T> = Result<Query<T>, QueryRejection>;

/// What a page shows besides the picture: the render's progress, the error, the camera.
pub(crate) fn status(ctx: &Context) -> serde_json::Value {
    let s = ctx.shared.lock();
    let frame = s.frame.as_ref().map(|f: &Arc<Frame>| {
        serde_json::json!({
            "id": f.id,
            "generation": f.generation,
            "width": f.image.width,
            "height": f.image.height,
            "spp": f.spp,
            "passes": f.passes,
            "elapsed": f.elapsed,
            "rays_per_second": f.rays_per_second,
            "done": f.done,
        })
    });
    let camera = s.scene.as_ref().map(|sc| {
        let v = sc.camera.view();
        serde_json::json!({
            "position": v.position.to_array(),
            "look_at": v.look_at.to_array(),
            "up": v.up.to_array(),
            "fov": v.fov,
        })
    });
    serde_json::json!({
        "version": s.version,
        "generation": s.generation,
        "scene": ctx.shared.settings.scene.display().to_string(),
        "integrator": s.integrator,
        "target_spp": s.target_spp,
        "size": s.scene.as_ref().map(|sc| [sc.settings.width, sc.settings.height]),
        "tone": s.scene.as_ref().map(|sc| serde_json::json!({
            "exposure": sc.settings.tone.exposure,
            "curve": sc.settings.tone.curve.name(),
        })),
        "frame": frame,
        "error": s.error,
        "camera": camera,
        "camera_moved": s.camera_override.is_some(),
        "files": s.files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>(),
    })
}

/// Counts an event stream while it is open.
struct Open(Arc<Context>);

impl Drop for Open {
    fn drop(&mut self) {
        self.0.streams.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Server-sent events: the status at once, then at every change. A page that cannot keep up
/// gets the newest status when it next reads: nothing is queued for it.
async fn events(State(ctx): Ctx) -> Response {
    if ctx.streams.fetch_add(1, Ordering::SeqCst) >= MAX_STREAMS {
        ctx.streams.fetch_sub(1, Ordering::SeqCst);
        return error(StatusCode::SERVICE_UNAVAILABLE, "too many pages are open");
    }
    let open = Open(ctx.clone());
    let changes = ctx.shared.versions.subscribe();
    let stream = futures_util::stream::unfold(
        (open, changes, true),
        |(open, mut changes, first)| async move {
            if !first && changes.changed().await.is_err() {
                return None;
            }
            if open.0.shared.stop.load(Ordering::SeqCst) {
                return None;
            }
            changes.mark_unchanged();
            let event = Event::default()
                .event("status")
                .data(status(&open.0).to_string());
            Some((
                Ok::<_, std::convert::Infallible>(event),
                (open, changes, false),
            ))
        },
    );
    Sse::new(stream)
        .keep_alive(KeepAlive::new().interval(HEARTBEAT).text("still here"))
        .into_response()
}

/// The newest frame as a JPEG, after `exposure` (stops) and `tone` (a curve's name), each
/// the scene's where not given.
async fn frame(State(ctx): Ctx, q: Asked<FrameQuery>) -> Response {
    let q = q.map(|Query(q)| q);
    let exposure = match q.as_ref().map(|q| q.exposure) {
        Ok(e) if e.is_none_or(|e| e.is_finite() && e.abs() <= 20.0) => e,
        _ => {
            return error(
                StatusCode::BAD_REQUEST,
                "exposure is a number of stops from -20 to 20",
            );
        }
    };
    let tone = q.ok().and_then(|q| q.tone);
    let curve = match tone.as_deref().map(ToneCurve::from_name) {
        None => None,
        Some(Some(c)) => Some(c),
        Some(None) => return error(StatusCode::BAD_REQUEST, "tone is clamp, reinhard or aces"),
    };
    let Some(frame) = ctx.shared.lock().frame.clone() else {
        return error(StatusCode::NOT_FOUND, "no picture yet");
    };
    let exposure = exposure.unwrap_or(frame.tone.exposure);
    let curve = curve.unwrap_or(frame.tone.curve);
    blocking(move || {
        let key = (frame.id, exposure.to_bits(), curve);
        let mut cache = ctx.frame_cache.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((k, bytes)) = cache.as_ref()
            && *k == key
        {
            return self::bytes("image/jpeg", bytes.clone());
        }
        let tone = Tone { exposure, curve };
        match snell::output::encode_display(&frame.image, &tone, Some(QUALITY)) {
            Ok(encoded) => {
                let encoded = Arc::new(encoded);
                *cache = Some((key, encoded.clone()));
                self::bytes("image/jpeg", encoded)
            }
            Err(e) => error(
                StatusCode::INTERNAL_SERVER_ERROR,
                &format!("cannot encode the picture: {e}"),
            ),
        }
    })
    .await
}

/// A debug view of the scene shown, as a PNG (one ray through each pixel's centre):
/// `/view/NAME.png`.
async fn view(State(ctx): Ctx, Path(file): Path<String>) -> Response {
    let Some(aov) = file.strip_suffix(".png").and_then(Aov::from_name) else {
        return error(StatusCode::NOT_FOUND, "no such view");
    };
    if aov.from_film() {
        return film_view(ctx, aov).await;
    }
    let (scene, generation) = {
        let s = ctx.shared.lock();
        (s.scene.clone(), s.generation)
    };
    let Some(scene) = scene else {
        return error(StatusCode::NOT_FOUND, "no scene yet");
    };
    blocking(move || {
        let mut cache = ctx.view_cache.lock().unwrap_or_else(|e| e.into_inner());
        cache.retain(|((g, _), _)| *g == generation);
        if let Some((_, b)) = cache.iter().find(|(k, _)| *k == (generation, aov)) {
            return bytes("image/png", b.clone());
        }
        let picture = render_aovs(&scene, None)
            .map_err(|e| e.to_string())
            .and_then(|b| {
                let img = b.display(aov, scene.settings.max_depth);
                snell::output::encode_display(&img, &Tone::default(), None)
                    .map_err(|e| e.to_string())
            });
        match picture {
            Ok(png) => {
                let png = Arc::new(png);
                cache.push(((generation, aov), png.clone()));
                bytes("image/png", png)
            }
            Err(e) => error(
                StatusCode::INTERNAL_SERVER_ERROR,
                &format!("cannot render the view: {e}"),
            ),
        }
    })
    .await
}

/// A view read from the newest frame's film of sums (`variance`, `spp`): the path tracer's
/// alone (its samples are random; Whitted's are fixed strata, bdpt's land anywhere).
async fn film_view(ctx: Arc<Context>, aov: Aov) -> Response {
    let frame = ctx.shared.lock().frame.clone();
    let Some(frame) = frame else {
        return error(StatusCode::NOT_FOUND, "no picture yet");
    };
    if frame.film.is_none() {
        return error(
            StatusCode::NOT_FOUND,
            &format!(
                "the {} view is the path tracer's (its film of samples)",
                aov.name()
            ),
        );
    }
    blocking(move || {
        let Some(film) = &frame.film else {
            return error(StatusCode::NOT_FOUND, "no film");
        };
        let img = snell::integrator::aov::AovBuffers::of_film(film).display(aov, 2);
        match snell::output::encode_display(&img, &Tone::default(), None) {
            Ok(png) => bytes("image/png", Arc::new(png)),
            Err(e) => error(
                StatusCode::INTERNAL_SERVER_ERROR,
                &format!("cannot encode the view: {e}"),
            ),
        }
    })
    .await
}

/// The scene shown and the pixel a query names inside it (or the answer that says why
/// not, boxed: a response is large).
pub(super) fn scene_and_pixel(
    ctx: &Context,
    q: Asked<PixelQuery>,
) -> Result<(Arc<snell::Scene>, u32, u32), Box<Response>> {
    let Some(scene) = ctx.shared.lock().scene.clone() else {
        return Err(Box::new(error(StatusCode::NOT_FOUND, "no scene yet")));
    };
    let (w, h) = (scene.settings.width, scene.settings.height);
    match q {
        Ok(Query(PixelQuery { x, y })) if x < w && y < h => Ok((scene, x, y)),
        _ => Err(Box::new(error(
            StatusCode::BAD_REQUEST,
            &format!("give the pixel as x=COLUMN&y=ROW inside the {w} x {h} picture"),
        ))),
    }
}

/// The explain data of a pixel, as `snell explain --json` gives it for the scene's
/// integrator (`explain_pixel::pixel_json`): the Whitted tree of the ray through its centre,
/// the path of sample 0 under the path tracer (and under light tracing, with a `note` that
/// says so), or bdpt's sample 0, with each point's place on the picture (`screen`) for
/// drawing.
async fn explain(State(ctx): Ctx, q: Asked<PixelQuery>) -> Response {
    let (scene, x, y) = match scene_and_pixel(&ctx, q) {
        Ok(v) => v,
        Err(r) => return *r,
    };
    blocking(move || {
        let path = &ctx.shared.settings.scene;
        match snell::explain_pixel::pixel_json(&scene, path, (x, y), 200) {
            Some(doc) => json(&doc),
            None => error(StatusCode::INTERNAL_SERVER_ERROR, "no ray was recorded"),
        }
    })
    .await
}

/// The object and material under a pixel's centre.
async fn pick(State(ctx): Ctx, q: Asked<PixelQuery>) -> Response {
    let (scene, x, y) = match scene_and_pixel(&ctx, q) {
        Ok(v) => v,
        Err(r) => return *r,
    };
    let s = &scene.settings;
    let ray = scene
        .camera
        .ray(x as f32 + 0.5, y as f32 + 0.5, s.width, s.height);
    let hit = scene.closest_hit(&ray, f32::INFINITY);
    json(&serde_json::json!({
        "pixel": [x, y],
        "object": hit.as_ref().map(|h| scene.objects[h.object].name.clone()),
        "material": hit.as_ref().and_then(|h| scene.material_names.get(h.material).cloned()),
        "distance": hit.as_ref().map(|h| h.t),
    }))
}

/// A camera the page moved to: `{"position": [x, y, z], "look_at": [...], "up": [...],
/// "fov": degrees}`. The scene file is never written.
async fn camera(State(ctx): Ctx, body: String) -> Response {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Body {
        position: [f32; 3],
        look_at: [f32; 3],
        up: [f32; 3],
        fov: f32,
    }
    let view = match serde_json::from_str::<Body>(&body) {
        // The file's projection and lens are kept (preview.rs puts them back).
        Ok(b) => CameraView::perspective(
            Vec3A::from(b.position),
            Vec3A::from(b.look_at),
            Vec3A::from(b.up),
            b.fov,
        ),
        Err(e) => return error(StatusCode::BAD_REQUEST, &format!("not a camera: {e}")),
    };
    if !view.is_valid() {
        return error(
            StatusCode::BAD_REQUEST,
            "not a camera: positions must be finite, look_at away from position, up not along the view, fov between 0 and 180",
        );
    }
    ctx.shared.set_camera(Some(view));
    json(&serde_json::json!({ "ok": true }))
}
