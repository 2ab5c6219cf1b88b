//! Links the `screwdyn` program as a position-dependent executable on Linux (`-no-pie`): the
//! linker then resolves the program's ≈ 3 400 internal addresses itself, so the dynamic loader
//! does not fix them up in every process and the pages holding them are not copied on
//! first write (≈ 50 K instructions and 20 page faults less per process; BENCHMARKS.md, "The
//! CLI's start and finish"). The code stays position-independent (the library, the tests and
//! the Python extension are unchanged); only this program's address is fixed.
fn main() {
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
