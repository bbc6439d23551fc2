//! Compiles the FMI logger shim (a C-variadic callback; see src/logger.c).

fn main() {
    println!("cargo::rerun-if-changed=src/logger.c");
    cc::Build::new()
        .file("src/logger.c")
        .compile("slender_fmi_logger");
}
