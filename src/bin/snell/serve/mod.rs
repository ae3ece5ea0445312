//! `snell serve`: a live preview in the browser. The page (page/, built into the binary)
//! shows the picture as it refines, re-rendered whenever the scene file or a file it reads
//! is saved, and explains any pixel it is clicked on. http.rs answers the requests (axum on
//! a small tokio runtime), preview.rs holds the state and runs the render loop on a thread
//! of its own, watch.rs watches the files.

mod denoised;
mod http;
mod lab;
mod paths;
mod preview;
mod watch;

use crate::args::ServeArgs;
use std::net::{IpAddr, SocketAddr};
use std::process::ExitCode;
use std::sync::Arc;

pub(crate) fn serve(args: ServeArgs) -> ExitCode {
    let limits = match args.limits.get() {
        Ok(l) => l,
        Err(code) => return code,
    };
    if let Err(e) = snell::read_regular_file(&args.scene) {
        return crate::usage_error(
            &format!("cannot read {}: {e}", args.scene.display()),
            Some("give the scene file to preview, for example scenes/seed.toml"),
        );
    }
    let ip: IpAddr = match args.host.parse() {
        Ok(ip) => ip,
        Err(_) if args.host == "localhost" => IpAddr::from([127, 0, 0, 1]),
        Err(_) => {
            return crate::usage_error(
                &format!("`{}` is not an address to listen on", args.host),
                Some(
                    "use 127.0.0.1 (this machine only, the default), or 0.0.0.0 for every interface",
                ),
            );
        }
    };
    // Two threads answer requests; rendering has its own (rayon's), and slow answers
    // (encoding, debug views) run on tokio's blocking pool.
    let runtime = match tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .thread_name("snell-http")
        .enable_all()
        .build()
    {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: cannot start the server's threads: {e}");
            return ExitCode::from(1);
        }
    };
    let listener = match runtime.block_on(tokio::net::TcpListener::bind(SocketAddr::new(
        ip, args.port,
    ))) {
        Ok(l) => l,
        Err(e) => {
            eprintln!("error: cannot listen on {}:{}: {e}", args.host, args.port);
            eprintln!(
                "  help: another program may use the port: pick another with --port, or --port 0 for any free one"
            );
            return ExitCode::from(1);
        }
    };
    let addr = match listener.local_addr() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: the server has no address: {e}");
            return ExitCode::from(1);
        }
    };
    let port = addr.port();
    let hosts = if ip.is_unspecified() {
        vec![]
    } else {
        let mut hosts = vec![
            format!("127.0.0.1:{port}"),
            format!("localhost:{port}"),
            format!("[::1]:{port}"),
        ];
        hosts.push(match ip {
            IpAddr::V6(v6) => format!("[{v6}]:{port}"),
            IpAddr::V4(v4) => format!("{v4}:{port}"),
        });
        hosts
    };
    let shown = if ip.is_unspecified() || ip.is_loopback() {
        format!("http://127.0.0.1:{port}/")
    } else {
        format!("http://{addr}/")
    };
    let shared = Arc::new(preview::Shared::new(preview::Settings {
        scene: args.scene.clone(),
        size: args.size,
        frame: args.frame,
        overrides: snell::job::Overrides {
            noise: args.noise,
            ..args.sampling.overrides()
        },
        limits,
    }));
    let watcher = {
        let shared = shared.clone();
        match watch::Watch::new(move || shared.files_changed()) {
            Ok(w) => Some(w),
            Err(e) => {
                eprintln!(
                    "warning: cannot watch files ({e}): the preview will not follow saves; restart it after editing"
                );
                None
            }
        }
    };
    outln!("snell serve: {shown} shows {}", args.scene.display());
    outln!("  the picture follows every save of the scene and the files it reads; Ctrl-C stops");
    if !ip.is_loopback() {
        eprintln!(
            "warning: listening on {addr}: other machines can see the picture and read the scene's file names and the explain data"
        );
    }
    if args.open {
        open_browser(&shown);
    }
    let app = http::router(Arc::new(http::Context::new(shared.clone(), hosts)));
    let served = std::thread::scope(|scope| {
        scope.spawn(|| {
            preview::run(&shared, &|files| {
                if let Some(w) = &watcher {
                    w.set(files);
                }
            })
        });
        let stopped = {
            let shared = shared.clone();
            async move {
                let _ = tokio::signal::ctrl_c().await;
                shared.shut_down();
            }
        };
        let served = runtime.block_on(async {
            axum::serve(listener, app)
                .with_graceful_shutdown(stopped)
                .await
        });
        // However the server ended, the render loop ends with it.
        shared.shut_down();
        served
    });
    // Event streams and slow answers still under way are not waited for.
    runtime.shutdown_timeout(std::time::Duration::from_millis(200));
    match served {
        Ok(()) => {
            outln!("snell serve: stopped");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: the server failed: {e}");
            ExitCode::from(1)
        }
    }
}

/// Opens `url` in the desktop's browser, or says how to.
fn open_browser(url: &str) {
    let tried: &[(&str, &[&str])] = if cfg!(target_os = "macos") {
        &[("open", &[])]
    } else if cfg!(windows) {
        &[("cmd", &["/C", "start", ""])]
    } else {
        &[("xdg-open", &[]), ("sensible-browser", &[])]
    };
    for (program, args) in tried {
        let started = std::process::Command::new(program)
            .args(*args)
            .arg(url)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn();
        if started.is_ok() {
            return;
        }
    }
    eprintln!("note: no browser could be started; open {url} yourself");
}
