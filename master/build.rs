//! Compiles the FMI logger shim (a C-variadic callback; see src/fmi/logger.c).

fn main() {
    println!("cargo::rerun-if-changed=src/fmi/logger.c");
    cc::Build::new()
        .file("src/fmi/logger.c")
        .compile("slender_fmi_logger");
}
