//! Links SUNDIALS (the system libraries of `apt-get install libsundials-dev`) for the CVODE peer
//! of the stiff bench (`benches/cvode/mod.rs`) and the IDA peer of the DAE bench
//! (`benches/ida/mod.rs`), and KLU (`apt-get install libsuitesparse-dev`) for IDA's sparse
//! linear solver.

fn main() {
    let dirs = [
        "/usr/lib",
        "/usr/local/lib",
        "/usr/lib/x86_64-linux-gnu",
        "/usr/lib/aarch64-linux-gnu",
    ];
    let found = |lib: &str| {
        dirs.iter()
            .any(|dir| std::path::Path::new(dir).join(lib).exists())
    };
    if !found("libsundials_cvode.so") || !found("libsundials_ida.so") {
        panic!("the CVODE and IDA peers need SUNDIALS 6.x: apt-get install libsundials-dev");
    }
    if !found("libklu.so") || !found("libsundials_sunlinsolklu.so") {
        panic!("the IDA peer's KLU solver needs KLU: apt-get install libsuitesparse-dev");
    }
    for lib in [
        "sundials_cvode",
        "sundials_ida",
        "sundials_sunlinsoldense",
        "sundials_sunlinsolklu",
        "sundials_sunmatrixdense",
        "sundials_sunmatrixsparse",
        "sundials_nvecserial",
        "klu",
    ] {
        println!("cargo:rustc-link-lib={lib}");
    }
}
