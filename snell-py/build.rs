//! With the `denoise` feature, the folder of the Open Image Denoise library the module links
//! (`OIDN_DIR/lib`) goes into its run-time search path, as snell's own build.rs does for
//! the command line (a dependency's link arguments do not reach this library).

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
