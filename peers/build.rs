//! Links SUNDIALS CVODE (the system library of `apt-get install libsundials-dev`) for the stiff
//! bench's CVODE peer (`benches/cvode/mod.rs`).

fn main() {
    let found = ["/usr/lib", "/usr/local/lib", "/usr/lib/x86_64-linux-gnu", "/usr/lib/aarch64-linux-gnu"]
        .iter()
        .any(|dir| std::path::Path::new(dir).join("libsundials_cvode.so").exists());
    if !found {
        panic!(
            "the stiff bench's CVODE peer needs SUNDIALS CVODE 6.x: apt-get install libsundials-dev"
        );
    }
    for lib in [
        "sundials_cvode",
        "sundials_sunlinsoldense",
        "sundials_sunmatrixdense",
        "sundials_nvecserial",
    ] {
        println!("cargo:rustc-link-lib={lib}");
    }
}
