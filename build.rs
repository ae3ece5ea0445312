//! With the `denoise` feature, the folder of the Open Image Denoise library the build links
//! (`OIDN_DIR/lib`, see docs/denoise.md) goes into the binaries' run-time search path, so
//! that snell finds that library when it runs, without `LD_LIBRARY_PATH`. Without the
//! feature it does nothing.

fn main() {
    println!("cargo:rerun-if-env-changed=OIDN_DIR");
    let denoise = std::env::var_os("CARGO_FEATURE_DENOISE").is_some();
    let unix = std::env::var("CARGO_CFG_TARGET_FAMILY").is_ok_and(|f| f == "unix");
    if denoise
        && unix
        && let Some(dir) = std::env::var_os("OIDN_DIR").filter(|d| !d.is_empty())
    {
        let lib = std::path::Path::new(&dir).join("lib");
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", lib.display());
    }
}
